#include "output/plot_script.hpp"

#include <sys/wait.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>

#include "output/signal_cleanup.hpp"

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

bool run_plot_script(const std::string& name, const fs::path& fallback, const fs::path& dir, const std::string& who) {
    const fs::path exe = fs::canonical("/proc/self/exe");
    // Beside an installed executable, else where this library was installed to, else the source tree's.
    fs::path script = exe.parent_path().parent_path() / "share" / "smithlab" / name;
    if (!fs::exists(script)) script = fs::path(SMITHLAB_DATA_DIR) / name;
    if (!fs::exists(script)) script = fallback;
    const std::string cmd = "/usr/bin/python3 " + shell_quoted(script.string()) + " " + shell_quoted(dir.string());
    std::fprintf(stderr, "%s: drawing the figures (%s)\n", who.c_str(), cmd.c_str());
    const int status = std::system(cmd.c_str());
    if (WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM))
        end_as_signalled(WTERMSIG(status));  // the user's Ctrl-C reached the plot script too
    if (status == 0) return true;
    std::fprintf(stderr,
                 "%s: warning: the figures were not drawn; their data is in %s (needs Debian's "
                 "python3-matplotlib, see .ci/deps)\n",
                 who.c_str(), dir.string().c_str());
    return false;
}

}  // namespace smithlab::output
