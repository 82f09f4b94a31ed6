// Drawing a run's figures with one of smithlab's matplotlib scripts (Debian's python3-matplotlib).
#pragma once

#include <filesystem>
#include <string>

namespace smithlab::output {

// Runs `/usr/bin/python3 SCRIPT DIR`, SCRIPT found next to an installed binary (PREFIX/share/smithlab/NAME) or else at
// `fallback` (the source tree of this build). `who` prefixes the lines on stderr ("report: drawing the figures ...").
// A signal that ended the script (the user's Ctrl-C reached it too) ends this process the same way. Returns whether the
// script succeeded; when not, a warning names dir as where the figures' data is.
bool run_plot_script(const std::string& name, const std::filesystem::path& fallback, const std::filesystem::path& dir,
                     const std::string& who);

}  // namespace smithlab::output
