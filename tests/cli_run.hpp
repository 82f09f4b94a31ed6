// Drive the smithlab executable from a test as a user would: run it through the shell, capture stdout, stderr and
// the exit code. Shared by the CLI, scene, output and fuzz tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace smithlab_test {

struct Run {
    int rc;
    std::string out, err;
};

inline std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline fs::path scratch() {
    const fs::path d = fs::temp_directory_path() / ("smithlab_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// args is passed to the shell as is: quote specs with single quotes.
inline Run run(const std::string& args) {
    const fs::path d = scratch();
    const std::string cmd = std::string("'") + SMITHLAB_EXE + "' " + args + " > '" + (d / "out").string() + "' 2> '" +
        (d / "err").string() + "'";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(d / "out"), slurp(d / "err")};
}

inline void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// `smithlab report` on a scene written to d/name, into d/out.
inline std::string report_args(const fs::path& d, const std::string& name, const std::string& out) {
    return "report '" + (d / name).string() + "' --output '" + (d / out).string() + "'";
}
inline Run run_scene(const fs::path& d, const std::string& name, const std::string& text, const std::string& out) {
    write(d / name, text);
    return run(report_args(d, name, out));
}

// `smithlab fit` on scene_text written to d/s.toml, into d/out, on two threads.
inline Run run_fit(const fs::path& d, const std::string& scene_text) {
    write(d / "s.toml", scene_text);
    return run("fit '" + (d / "s.toml").string() + "' --output '" + (d / "out").string() + "' --threads 2");
}

// A malformed scene: exit 2, a message holding `expected`, and no output directory. Returns the message.
inline std::string check_bad_scene(const fs::path& d, const std::string& name, const std::string& text,
                                   const std::string& expected) {
    const Run r = run_scene(d, name, text, "never");
    INFO(name << ": " << r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains(expected));
    CHECK_FALSE(fs::exists(d / "never"));
    return r.err;
}

// Every temporary smithlab names ".NAME.PID.smithlab-partial" under dir (recursively).
inline std::vector<fs::path> temporaries(const fs::path& dir) {
    std::vector<fs::path> found;
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec))
        if (e.path().filename().string().ends_with(".smithlab-partial")) found.push_back(e.path());
    return found;
}

}  // namespace smithlab_test
