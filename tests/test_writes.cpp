// Every write checked: standard output into a full device or past a file-size limit, an output file or directory
// past the limit, and the outputs that cannot be written into (a dangling symbolic link, a FIFO with no reader, a
// read-only directory). Each is exit 2 with a message naming what could not be written, and nothing half-written.
#include <sys/stat.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "cli_run.hpp"

using namespace smithlab_test;

namespace {

// `smithlab ARGS` run by the shell after `prefix` (shell commands ending in ';', or empty), through `wrapper` (a
// command such as `timeout 30`, or empty), its stdout sent to `stdout_to`; stderr captured.
Run run_sh(const std::string& prefix, const std::string& wrapper, const std::string& args,
           const std::string& stdout_to) {
    const fs::path d = scratch();
    const std::string cmd = prefix + " exec " + wrapper + " '" + SMITHLAB_EXE + "' " + args + " > " + stdout_to +
        " 2> '" + (d / "err").string() + "'";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, "", slurp(d / "err")};
}

// Under a file-size limit of 512 bytes, the signal it raises ignored (as a Python subprocess has it): a write past
// the limit fails with EFBIG.
const std::string small_files = "trap '' XFSZ; ulimit -f 1;";

fs::path fresh(const std::string& name) {
    const fs::path d = scratch() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

// A CSV for eval --input of 200 rows (about 3 KB of output).
fs::path csv_input(const fs::path& d) {
    std::string text = "ndf,mu\n";
    for (int i = 1; i <= 200; ++i) text += "ggx(alpha=0.5)," + std::to_string(0.01 * i) + "\n";
    write(d / "in.csv", text);
    return d / "in.csv";
}

const std::string eval_one = "eval --ndf 'ggx(alpha=0.5)' --mu 0.5";

}  // namespace

TEST_CASE("standard output into a full device is exit 2, naming standard output", "[writes]") {
    const std::vector<std::string> commands = {
        eval_one,
        "brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 45,180 --walks 1000",
        "list",
        "report --print-scene",
        "trace --print-scene",
        "fit --print-scene",
        "check --ndf 'ggx(alpha=0.5)' --no-2d",
        "eval --help",
        // A long stream stops at its first failed write.
        "sample --ndf 'ggx(alpha=0.5)' --sampler dcos --n 1000000",
    };
    for (const std::string& args : commands) {
        const Run r = run_sh("", "", args, "/dev/full");
        INFO(args << "\n" << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("smithlab: error: cannot write to standard output: No space left on device"));
    }
}

TEST_CASE("standard output past a file-size limit is exit 2, not a truncated table", "[writes]") {
    const fs::path d = fresh("writes_stdout_limit");
    const Run r =
        run_sh(small_files, "", "eval --input '" + csv_input(d).string() + "'", "'" + (d / "out").string() + "'");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("cannot write to standard output: File too large"));
}

TEST_CASE("an output file past a file-size limit is exit 2 naming it, and nothing is left", "[writes]") {
    const fs::path d = fresh("writes_file_limit");
    const fs::path out = d / "table.csv";
    const Run r =
        run_sh(small_files, "", "eval --input '" + csv_input(d).string() + "' -o '" + out.string() + "'", "/dev/null");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("cannot write " + out.string() + ": File too large"));
    CHECK_FALSE(fs::exists(out));
    CHECK(temporaries(d).empty());
}

TEST_CASE("a trace past a file-size limit is exit 2 naming the file, and no table is published", "[writes]") {
    const fs::path d = fresh("writes_trace_limit");
    write(d / "scene.toml",
          "materials = [\"mirror\"]\n[walks]\nn = 500\n[grid]\nalpha = [0.3, 0.6]\ntheta_i = [30, 60]\n"
          "[[ndf]]\nfamily = \"ggx\"\n");
    const fs::path out = d / "out";
    const Run r =
        run_sh(small_files, "", "trace '" + (d / "scene.toml").string() + "' --threads 2 -o '" + out.string() + "'",
               "/dev/null");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(
        r.err,
        Catch::Contains("smithlab: error: cannot write " + out.string() + "/") && Catch::Contains(": File too large"));
    CHECK_FALSE(fs::exists(out / "albedo.csv"));
    CHECK_FALSE(fs::exists(out / "meta.json"));
    CHECK(temporaries(d).empty());
}

TEST_CASE("the report's bench.json past a file-size limit is exit 2 naming it, not a parse error", "[writes]") {
    const fs::path d = fresh("writes_report_limit");
    write(d / "scene.toml",
          "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n"
          "[variants]\ninclude = [\"closed-form\"]\n[timing]\nmin_time = 0.01\n");
    const fs::path out = d / "rep";
    const Run r = run_sh(small_files, "", report_args(d, "scene.toml", "rep"), "/dev/null");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err,
               Catch::Contains("smithlab: error: cannot write " + (out / "bench.json").string() + ": File too large"));
    CHECK_FALSE(fs::exists(out / "bench.json"));
    CHECK_FALSE(fs::exists(out / "report.md"));
    CHECK(temporaries(d).empty());
}

TEST_CASE("outputs that cannot be written into are refused, naming what they are", "[writes]") {
    const fs::path d = fresh("writes_refused");

    SECTION("a dangling symbolic link as the output directory") {
        fs::create_symlink(d / "nowhere" / "deeper", d / "link");
        const Run r = run_sh("", "", "trace --walks 100 -o '" + (d / "link").string() + "'", "/dev/null");
        INFO(r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err,
                   Catch::Contains("output directory '" + (d / "link").string() + "' is a dangling symbolic link to '" +
                                   (d / "nowhere" / "deeper").string() + "'"));
        CHECK_FALSE(fs::exists(d / "nowhere"));
    }

    const std::string eval_csv = "eval --input '" + csv_input(d).string() + "'";

    SECTION("a FIFO with no reader, never waited on") {
        REQUIRE(::mkfifo((d / "fifo").c_str(), 0600) == 0);
        const Run r = run_sh("", "timeout 30", eval_csv + " -o '" + (d / "fifo").string() + "'", "/dev/null");
        INFO(r.err);
        CHECK(r.rc == 2);  // 124 when it waits for a reader
        CHECK_THAT(r.err, Catch::Contains("output '" + (d / "fifo").string() + "': is a FIFO with no reader"));
    }

    SECTION("a FIFO with a reader gets the table") {
        REQUIRE(::mkfifo((d / "fifo").c_str(), 0600) == 0);
        const std::string got = (d / "got").string();
        const Run r = run_sh("cat '" + (d / "fifo").string() + "' > '" + got + "' & sleep 1;", "timeout 30",
                             eval_csv + " -o '" + (d / "fifo").string() + "'", "/dev/null");
        INFO(r.err);
        CHECK(r.rc == 0);
        const std::string want = run(eval_csv).out;
        for (int i = 0; i < 100 && slurp(got).size() < want.size(); ++i) ::usleep(50000);  // cat's last write
        CHECK(slurp(got) == want);
    }

    SECTION("/dev/stdout onto a pipe gets the table") {
        const std::string got = (d / "got").string(), rc = (d / "rc").string(), err = (d / "err").string();
        const std::string cmd = "{ '" + std::string(SMITHLAB_EXE) + "' " + eval_csv + " -o /dev/stdout 2> '" + err +
            "'; echo $? > '" + rc + "'; } | cat > '" + got + "'";
        REQUIRE(std::system(cmd.c_str()) == 0);
        INFO(slurp(err));
        CHECK(slurp(rc) == "0\n");
        CHECK(slurp(got) == run(eval_csv).out);
    }

    SECTION("a read-only directory, for root too") {
        fs::create_directories(d / "ro");
        fs::permissions(d / "ro", fs::perms::owner_read | fs::perms::owner_exec);
        const Run file = run_sh("", "", eval_csv + " -o '" + (d / "ro" / "x.csv").string() + "'", "/dev/null");
        const Run dir = run_sh("", "", "trace --walks 100 -o '" + (d / "ro").string() + "'", "/dev/null");
        const Run below = run_sh("", "", "trace --walks 100 -o '" + (d / "ro" / "sub").string() + "'", "/dev/null");
        fs::permissions(d / "ro", fs::perms::owner_all);
        INFO(file.err << dir.err << below.err);
        CHECK(file.rc == 2);
        CHECK_THAT(file.err, Catch::Contains("its directory '" + (d / "ro").string() + "' is read-only"));
        CHECK(dir.rc == 2);
        CHECK_THAT(dir.err, Catch::Contains("output directory '" + (d / "ro").string() + "' is read-only"));
        CHECK(below.rc == 2);
        CHECK_THAT(below.err, Catch::Contains("its parent '" + (d / "ro").string() + "' is read-only"));
        CHECK(fs::is_empty(d / "ro"));
    }
}

TEST_CASE("the fit's compensation tables past a file-size limit are exit 2 naming the file, not an internal error",
          "[writes]") {
    const fs::path d = fresh("writes_compensation_limit");
    write(d / "s.toml",
          slurp(SMITHLAB_TESTS_DIR "/fit_tiny_scene.toml") +
              "[compensation]\nalpha = [0.5, 1.0]\ncosines = 4\nrefine = 2\nfurnace_alpha = [0.5]\n"
              "furnace_theta = [0.0]\nfurnace_walks = 100\n");
    const fs::path out = d / "out";
    const Run r =
        run_sh(small_files, "", "fit '" + (d / "s.toml").string() + "' -o '" + out.string() + "'", "/dev/null");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(
        r.err,
        Catch::Contains("smithlab: error: cannot write " + out.string() + "/") && Catch::Contains(": File too large"));
    CHECK_FALSE(fs::exists(out / "report.md"));
    CHECK(temporaries(d).empty());
}

TEST_CASE("a plot script that fails is exit 2 naming the figures, and without matplotlib a warning names the output",
          "[writes]") {
    // A matplotlib of our own first on the path: one that fails as a full disk would, one that is not there.
    const fs::path d = fresh("writes_plot_script");
    for (const auto& [name, body] : {std::pair{"failing", "raise OSError(28, 'No space left on device')\n"},
                                     std::pair{"missing", "raise ImportError('no matplotlib here')\n"}}) {
        fs::create_directories(d / name / "matplotlib");
        write(d / name / "matplotlib" / "__init__.py", body);
    }
    write(d / "scene.toml",
          "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n"
          "[variants]\ninclude = [\"closed-form\"]\n[timing]\nmin_time = 0.01\n[figures]\npareto = true\n");
    const std::string report = report_args(d, "scene.toml", "rep");

    const Run failed = run_sh("export PYTHONPATH='" + (d / "failing").string() + "';", "", report, "/dev/null");
    INFO(failed.err);
    CHECK(failed.rc == 2);
    CHECK_THAT(failed.err,
               Catch::Contains("smithlab: error: cannot write the figures of " + (d / "rep").string() +
                               ": report_plots.py exited with status 1"));
    CHECK_FALSE(fs::exists(d / "rep" / "report.md"));
    CHECK(temporaries(d).empty());

    const Run missing = run_sh("export PYTHONPATH='" + (d / "missing").string() + "';", "", report, "/dev/null");
    INFO(missing.err);
    CHECK(missing.rc == 0);
    CHECK_THAT(missing.err,
               Catch::Contains("report: warning: the figures were not drawn: python3 has no matplotlib") &&
                   Catch::Contains("their data is in " + (d / "rep").string() + "\n"));
    CHECK_THAT(slurp(d / "rep" / "report.md"), Catch::Contains("**The figures were not drawn**"));
}
