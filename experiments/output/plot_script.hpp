// Drawing a run's figures with one of smithlab's matplotlib scripts (Debian's python3-matplotlib).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace smithlab::output {

// The exit status of a plot script that cannot import matplotlib (plot_common.py): the figures are left out, with a
// warning, and the run goes on. Any other failure of the script is the run's.
inline constexpr int plot_script_missing_matplotlib = 4;

// Runs `/usr/bin/python3 SCRIPT DIR`, SCRIPT found next to an installed binary (PREFIX/share/smithlab/NAME) or else at
// `fallback` (the source tree of this build). `who` prefixes the lines on stderr ("report: drawing the figures ...").
// A signal that ended the script (the user's Ctrl-C reached it too) ends this process the same way. Returns true when
// the figures are drawn, false when matplotlib is missing (a warning names the published directory, where the
// figures' data is). Throws input_error "cannot write the figures of DIR: ..." (exit 2) when the script fails in any
// other way (a full disk, a damaged file) or leaves out one of the `promised` files (names relative to dir).
bool run_plot_script(const std::string& name, const std::filesystem::path& fallback, const std::filesystem::path& dir,
                     const std::string& who, const std::vector<std::string>& promised = {});

}  // namespace smithlab::output
