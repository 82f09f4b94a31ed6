// Outputs that never clobber and never leave debris: what `--output` may replace, what a kill leaves,
// and the report's reference cache checked record by record. The executable is driven as a user would.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <smithlab/csv.hpp>

#include "cli_run.hpp"

using namespace smithlab_test;

extern char** environ;

namespace {

// The executable started in the background, its output discarded.
pid_t spawn(const std::vector<std::string>& args) {
    std::vector<char*> argv{const_cast<char*>(SMITHLAB_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = -1;
    REQUIRE(posix_spawn(&pid, SMITHLAB_EXE, &fa, nullptr, argv.data(), environ) == 0);
    posix_spawn_file_actions_destroy(&fa);
    return pid;
}

// Waits (up to 60 s) until `ready` holds, the process still running; false if it ended first.
template <class Ready>
bool wait_for(pid_t pid, Ready ready) {
    for (int i = 0; i < 6000; ++i) {
        if (ready()) return true;
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

// Sends `sig` and returns the wait status.
int kill_and_wait(pid_t pid, int sig) {
    kill(pid, sig);
    int status = 0;
    waitpid(pid, &status, 0);
    return status;
}

// The first `n` comma-separated fields of every line, the lines sorted: a CSV without its timing columns, and
// without the row order that follows them (variants.csv is sorted by measured ns, which ties reorder under load).
std::string first_fields(const std::string& csv, int n) {
    std::vector<std::string> lines;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) {
        std::size_t pos = 0;
        for (int k = 0; k < n && pos != std::string::npos; ++k) pos = line.find(',', pos + 1);
        lines.push_back(line.substr(0, pos));
    }
    std::sort(lines.begin(), lines.end());
    std::string out;
    for (const std::string& l : lines) out += l + "\n";
    return out;
}

const char* small_points = "ndf,mu\n\"ggx(alpha=0.5)\",1\n";

}  // namespace

TEST_CASE("outputs: devices and FIFOs are written in place, symlinks followed, the rest refused", "[outputs]") {
    const fs::path d = scratch() / "targets";
    fs::remove_all(d);
    fs::create_directories(d);
    write(d / "in.csv", small_points);
    const std::string in = "--input '" + (d / "in.csv").string() + "'";

    SECTION("/dev/null stays the system's null device") {
        CHECK(run("eval " + in + " --output /dev/null").rc == 0);
        CHECK(fs::is_character_file("/dev/null"));
    }
    SECTION("a FIFO is written, not replaced") {
        REQUIRE(mkfifo((d / "fifo").c_str(), 0600) == 0);
        // The test holds the reading end open (a FIFO with no reader is refused), and reads what was written.
        const std::string fifo = (d / "fifo").string();
        const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
        REQUIRE(reader >= 0);
        CHECK(run("eval " + in + " --output '" + fifo + "'").rc == 0);
        std::string got;
        char buffer[4096];
        for (ssize_t k; (k = ::read(reader, buffer, sizeof buffer)) > 0;)
            got.append(buffer, static_cast<std::size_t>(k));
        ::close(reader);
        CHECK_THAT(got, Catch::Contains("lambda,g1") && Catch::Contains("0.05901699437494"));
        CHECK(fs::is_fifo(d / "fifo"));
    }
    SECTION("a symlink: its target is written, the link kept") {
        write(d / "target.csv", "old\n");
        fs::create_symlink("target.csv", d / "link.csv");
        CHECK(run("eval " + in + " --output '" + (d / "link.csv").string() + "'").rc == 0);
        CHECK(fs::is_symlink(d / "link.csv"));
        CHECK_THAT(slurp(d / "target.csv"), Catch::Contains("lambda,g1"));
    }
    SECTION("a read-only file is refused and kept") {
        write(d / "ro.csv", "keep me\n");
        fs::permissions(d / "ro.csv", fs::perms::owner_read | fs::perms::group_read);
        const Run r = run("eval " + in + " --output '" + (d / "ro.csv").string() + "'");
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("ro.csv") && Catch::Contains("read-only"));
        CHECK(slurp(d / "ro.csv") == "keep me\n");
    }
    SECTION("a directory is refused, and nothing is left beside it") {
        fs::create_directories(d / "dir.csv");
        const Run r = run("eval " + in + " --output '" + (d / "dir.csv").string() + "'");
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("dir.csv") && Catch::Contains("is a directory"));
        CHECK(temporaries(d).empty());
    }
    SECTION("the input as the output is refused, and the input kept") {
        const Run r = run("eval " + in + " --output '" + (d / "in.csv").string() + "'");
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("is the input file"));
        CHECK(slurp(d / "in.csv") == small_points);
    }
    SECTION("an output in a directory that does not exist is refused before any work") {
        const Run r =
            run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 10 --output '" + (d / "no" / "x.csv").string() + "'");
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("does not exist"));
    }
    CHECK(temporaries(d).empty());
}

TEST_CASE("error paths: directories as input, duplicate columns, seeds, unknown subcommands", "[outputs][errors]") {
    const fs::path d = scratch() / "errors";
    fs::remove_all(d);
    fs::create_directories(d);
    Run r = run("eval --input '" + d.string() + "'");
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("is a directory"));

    write(d / "dup.csv", "ndf,mu,ndf\n\"ggx(alpha=0.5)\",1,\"ggx(alpha=0.1)\"\n");
    r = run("eval --input '" + (d / "dup.csv").string() + "'");
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("dup.csv:1") && Catch::Contains("two 'ndf' columns"));

    for (const char* seed : {"-1", "18446744073709551616", "''", "1e3", "0x10", "' 7'"}) {
        r = run(std::string("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 1 --seed ") + seed);
        INFO("seed " << seed << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("--seed"));
    }
    CHECK(run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 1 --seed 18446744073709551615").rc == 0);
    // The largest seed and its wrapped twin (2^64 + 0 would have been 0) draw different normals.
    CHECK(run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 2 --seed 0").out !=
          run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 2 --seed 18446744073709551615").out);

    r = run("frobnicate");
    CHECK(r.rc == 2);
    CHECK_THAT(
        r.err,
        Catch::Contains("unknown subcommand 'frobnicate'") && Catch::Contains("eval") && Catch::Contains("sample"));
}

TEST_CASE("a killed sample leaves nothing half-written, and the rerun is right", "[outputs][kill]") {
    const fs::path d = scratch() / "kill_sample";
    fs::remove_all(d);
    fs::create_directories(d);
    const fs::path out = d / "m.csv";
    const std::vector<std::string> big = {"sample", "--ndf", "ggx(alpha=0.1)", "--sampler", "dcos", "--n", "100000000",
                                          "--seed", "3",     "--output",       out.string()};
    const auto writing = [&] {
        const auto t = temporaries(d);
        std::error_code ec;
        return !t.empty() && fs::file_size(t.front(), ec) > 100000 && !ec;
    };
    for (int sig : {SIGTERM, SIGINT}) {
        const pid_t pid = spawn(big);
        REQUIRE(wait_for(pid, writing));
        const int status = kill_and_wait(pid, sig);
        CHECK((WIFSIGNALED(status) && WTERMSIG(status) == sig));
        CHECK(temporaries(d).empty());
        CHECK_FALSE(fs::exists(out));
    }
    // SIGKILL cannot be caught: its temporary stays until the next run into the same place removes it.
    const pid_t pid = spawn(big);
    REQUIRE(wait_for(pid, writing));
    kill_and_wait(pid, SIGKILL);
    CHECK(temporaries(d).size() == 1);
    const Run r = run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 1000 --seed 3 --output '" + out.string() + "'");
    REQUIRE(r.rc == 0);
    CHECK(temporaries(d).empty());
    // Right: the same rows as the same run to stdout.
    CHECK(slurp(out) == run("sample --ndf 'ggx(alpha=0.1)' --sampler dcos --n 1000 --seed 3").out);
}

TEST_CASE("a killed report leaves the previous report whole, and the rerun is right", "[outputs][kill][report]") {
    const fs::path d = scratch() / "kill_report";
    fs::remove_all(d);
    fs::create_directories(d);
    // Long enough in Google Benchmark (3 variants x 1 s) to be killed while timing.
    write(d / "scene.toml",
          "[grid]\nalpha = [0.1, 0.5]\nmu = [0.1, 1.0, 10.0]\n[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5, 3.0]\n"
          "[variants]\ninclude = [\"dimov-spline\", \"closed-form\", \"table\"]\n[timing]\nmin_time = 1.0\n");
    const fs::path out = d / "rep";
    const std::vector<std::string> args = {"report", (d / "scene.toml").string(), "--output", out.string()};
    const auto staging = [&] { return fs::exists(out) && !temporaries(out).empty(); };

    // Killed on its first run: no report at all, and no stage.
    pid_t pid = spawn(args);
    REQUIRE(wait_for(pid, staging));
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill_and_wait(pid, SIGTERM);
    CHECK(temporaries(out).empty());
    CHECK_FALSE(fs::exists(out / "report.md"));
    CHECK_FALSE(fs::exists(out / "bench.json"));

    const std::string cmd = "report '" + (d / "scene.toml").string() + "' --output '" + out.string() + "'";
    Run r = run(cmd);
    REQUIRE(r.rc == 0);
    std::string report = slurp(out / "report.md");
    const std::string variants = first_fields(slurp(out / "variants.csv"), 6);

    // Killed while replacing it (SIGKILL, then SIGTERM): the previous report stays whole; the stage goes.
    for (int sig : {SIGKILL, SIGTERM}) {
        pid = spawn(args);
        REQUIRE(wait_for(pid, staging));
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        kill_and_wait(pid, sig);
        CHECK(slurp(out / "report.md") == report);
        CHECK(temporaries(out).size() == (sig == SIGKILL ? 1u : 0u));
        if (sig == SIGKILL) {
            r = run(cmd);  // removes the dead run's stage
            REQUIRE(r.rc == 0);
            CHECK(temporaries(out).empty());
            CHECK(first_fields(slurp(out / "variants.csv"), 6) == variants);
            report = slurp(out / "report.md");
        }
    }
}

TEST_CASE("report: a damaged reference cache record is computed again, not reused", "[outputs][report]") {
    const fs::path d = scratch() / "cache";
    fs::remove_all(d);
    fs::create_directories(d);
    write(d / "scene.toml",
          "[grid]\nalpha = [0.1, 0.5]\nmu = [0.1, 1.0, 10.0]\n[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5]\n"
          "[variants]\ninclude = [\"dimov-spline\"]\n[timing]\nmin_time = 0.01\n");
    const std::string cmd = "report '" + (d / "scene.toml").string() + "' --output '" + (d / "rep").string() + "'";
    Run r = run(cmd);
    REQUIRE(r.rc == 0);
    const std::string clean = first_fields(slurp(d / "rep" / "variants.csv"), 6);
    const fs::path cache = d / "rep" / "cache" / "references.csv";
    std::string text = slurp(cache);
    // Cut one value short, as a kill mid-write would (0.0123456789 -> 0.01): its check no longer matches.
    const std::size_t line2 = text.find('\n') + 1, value = text.find(",q1d", line2);
    REQUIRE(value != std::string::npos);
    const std::size_t start = text.find(',', value + 1) + 1;
    text.erase(start + 4, text.find(',', start) - start - 4);
    write(cache, text);
    r = run(cmd);
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.err, Catch::Contains("5 reused from the cache, 1 computed (1 damaged cache records discarded)"));
    CHECK(first_fields(slurp(d / "rep" / "variants.csv"), 6) == clean);
}

TEST_CASE("a killed trace resumes from its last finished cell, and its files are the uninterrupted run's bits",
          "[outputs][kill][walk]") {
    const fs::path d = scratch() / "kill_trace";
    fs::remove_all(d);
    fs::create_directories(d);
    write(d / "scene.toml",
          "materials = [\"lambert(albedo=0.9)\"]\n[walks]\nn = 40000\nseed = 9\n[grid]\nalpha = [0.2, 0.4, 0.6, 0.8]\n"
          "theta_i = [0, 20, 40, 60, 80]\n[[ndf]]\nfamily = \"ggx\"\n");
    const fs::path out = d / "out", cells = out / "cells";
    const auto finished = [&] {
        std::error_code ec;
        int n = 0;
        for (const auto& e : fs::directory_iterator(cells, ec))
            if (e.path().extension() == ".csv") ++n;
        return n;
    };
    // Killed (SIGKILL: nothing of it runs after) once two of its 20 cells are done.
    const pid_t pid = spawn({"trace", (d / "scene.toml").string(), "--output", out.string(), "--threads", "1"});
    REQUIRE(wait_for(pid, [&] { return finished() >= 2; }));
    kill_and_wait(pid, SIGKILL);
    const int kept = finished();
    REQUIRE(kept < 20);
    CHECK_FALSE(fs::exists(out / "albedo.csv"));
    // The rerun traces only the rest; its files are those of a run never killed (another thread count, too).
    const std::string cmd = "trace '" + (d / "scene.toml").string() + "' --threads 2 --output ";
    Run r = run(cmd + "'" + out.string() + "'");
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.out,
               Catch::Contains("traced " + std::to_string(20 - kept) + "\nreused " + std::to_string(kept) + "\n"));
    CHECK(temporaries(out).empty());
    REQUIRE(run(cmd + "'" + (d / "whole").string() + "'").rc == 0);
    CHECK(slurp(out / "albedo.csv") == slurp(d / "whole" / "albedo.csv"));
    // A damaged cell file (cut short) is traced again, not read.
    const fs::path one = cells / "cell-000007.csv";
    std::string text = slurp(one);
    write(one, text.substr(0, text.size() / 2));
    r = run(cmd + "'" + out.string() + "'");
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.out, Catch::Contains("traced 1\nreused 19\n"));
    CHECK(slurp(out / "albedo.csv") == slurp(d / "whole" / "albedo.csv"));
}

TEST_CASE(
    "trace: a column per NDF parameter after the ndf column, empty where the NDF has no such parameter, and "
    "the cell files hold the rows without them",
    "[outputs][walk]") {
    const fs::path d = scratch() / "trace_ndf_columns";
    fs::remove_all(d);
    fs::create_directories(d);
    write(
        d / "scene.toml",
        "materials = [\"mirror\"]\n[walks]\nn = 500\n[grid]\nalpha = [0.3]\ntheta_i = [30]\n"
        "[[ndf]]\nfamily = \"ggx\"\n[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5]\n[brdf]\ntheta_bins = 1\nphi_bins = 2\n");
    const std::string cmd = "trace '" + (d / "scene.toml").string() + "' --threads 2 --output ";
    REQUIRE(run(cmd + "'" + (d / "out").string() + "'").rc == 0);
    const std::string albedo = slurp(d / "out" / "albedo.csv"), brdf = slurp(d / "out" / "brdf.csv");
    CHECK(albedo.rfind("ndf,alpha,gamma,material,theta_i,phi_i,hemisphere,order,component,albedo,stderr,walks\n", 0) ==
          0);
    CHECK(brdf.rfind("ndf,alpha,gamma,material,theta_i,phi_i,hemisphere,theta_o_lo,theta_o_hi,phi_o_lo,phi_o_hi,order,"
                     "component,value,stderr,walks\n",
                     0) == 0);
    CHECK_THAT(albedo, Catch::Contains("\nggx(alpha=0.3),0.3,,mirror,30,0,reflection,1,specular,"));
    CHECK_THAT(albedo, Catch::Contains("\n\"gtr(alpha=0.3, gamma=1.5)\",0.3,1.5,mirror,30,0,all,all,all,1,"));
    CHECK_THAT(brdf, Catch::Contains("\n\"gtr(alpha=0.3, gamma=1.5)\",0.3,1.5,mirror,30,0,reflection,0,"));
    // Every row as long as the header; without the two parameter fields, the rows are the cell files' "a," lines.
    std::string cell_rows;
    for (const char* name : {"cell-000000.csv", "cell-000001.csv"}) {
        std::istringstream cell(slurp(d / "out" / "cells" / name));
        for (std::string line; std::getline(cell, line);)
            if (line.rfind("a,", 0) == 0) cell_rows += line.substr(2) + "\n";
    }
    std::istringstream in(albedo);
    const std::vector<smithlab::CsvRecord> records = smithlab::read_csv(in);
    REQUIRE(records.size() == 1 + 2 * 45);
    std::string without_params;
    for (std::size_t i = 1; i < records.size(); ++i) {
        CHECK(records[i].fields.size() == records[0].fields.size());
        std::vector<std::string> f = records[i].fields;
        f.erase(f.begin() + 1, f.begin() + 3);
        std::ostringstream row;
        smithlab::write_csv_record(row, f);
        without_params += row.str();
    }
    CHECK(without_params == cell_rows);
    // A rerun reads every cell back from its file: the same bytes.
    const Run again = run(cmd + "'" + (d / "out").string() + "'");
    REQUIRE(again.rc == 0);
    CHECK_THAT(again.out, Catch::Contains("traced 0\nreused 2\n"));
    CHECK(slurp(d / "out" / "albedo.csv") == albedo);
    CHECK(slurp(d / "out" / "brdf.csv") == brdf);
}
