#include "output/plot_script.hpp"

#include <sys/wait.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "output/signal_cleanup.hpp"
#include "output/write_error.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::output {

namespace fs = std::filesystem;

namespace {

// text as one word of the shell: in single quotes, each quote in it as '\'' (a path may hold any character).
std::string shell_quoted(const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}  // namespace

bool run_plot_script(const std::string& name, const fs::path& fallback, const fs::path& dir, const std::string& who,
                     const std::vector<std::string>& promised) {
    const fs::path exe = fs::canonical("/proc/self/exe");
    // Beside an installed executable, else where this library was installed to, else the source tree's.
    fs::path script = exe.parent_path().parent_path() / "share" / "smithlab" / name;
    if (!fs::exists(script)) script = fs::path(SMITHLAB_DATA_DIR) / name;
    if (!fs::exists(script)) script = fallback;
    const std::string cmd = "/usr/bin/python3 " + shell_quoted(script.string()) + " " + shell_quoted(dir.string());
    // dir may be a stage directory itself, whose files land in the output directory: named through a file in it.
    const std::string shown = fs::path(published_name((dir / "figure").string())).parent_path().string();
    std::fprintf(stderr, "%s: drawing the figures (%s)\n", who.c_str(), cmd.c_str());
    const int status = std::system(cmd.c_str());
    if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM))
        end_as_signalled(WTERMSIG(status));  // the user's Ctrl-C reached the plot script too
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == plot_script_missing_matplotlib) {
        std::fprintf(stderr,
                     "%s: warning: the figures were not drawn: python3 has no matplotlib (Debian's "
                     "python3-matplotlib, see .ci/deps); their data is in %s\n",
                     who.c_str(), shown.c_str());
        return false;
    }
    if (status != 0)
        throw input_error("cannot write the figures of " + shown + ": " + name +
                          (code >= 0 ? " exited with status " + std::to_string(code) : std::string(" was killed")) +
                          " (its message is above)");
    for (const std::string& file : promised)
        if (!fs::is_regular_file(dir / file))
            throw input_error("cannot write the figures of " + shown + ": " + name + " did not write " + file);
    return true;
}

}  // namespace smithlab::output
