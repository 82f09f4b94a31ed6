// The strict reading of scenes and numbers, driven through the executable: nesting and file size bounded before
// toml11 parses, integers and reals beyond their types refused (in scenes and in options), the size of a trace or
// fit bounded before work starts, and keys that name nothing refused with the nearest name. Each refusal is exit 2
// with "smithlab: error:" naming the item (FILE:LINE and the key for scenes, the option for options).
#include <catch2/catch.hpp>

#include <string>

#include "cli_run.hpp"

using namespace smithlab_test;

namespace {

// A small valid trace scene; `extra` is appended to [walks] (after its n = ...), `grid` replaces the grid's theta_i.
std::string trace_scene(const std::string& walks, const std::string& theta_i = "[45.0]") {
    return "materials = [\"mirror\"]\n"
           "[walks]\n" +
        walks +
        "\n"
        "[grid]\n"
        "theta_i = " +
        theta_i +
        "\n"
        "[[ndf]]\n"
        "spec = \"ggx(alpha=0.5)\"\n";
}

// `smithlab trace` on a scene written to d/name; the run must be refused (exit 2, no output directory) with a
// message holding every one of `expected`.
void refused_trace(const fs::path& d, const std::string& name, const std::string& text,
                   const std::vector<std::string>& expected, const std::string& extra = "") {
    write(d / name, text);
    const Run r = run("trace '" + (d / name).string() + "' -o '" + (d / "never").string() + "' " + extra);
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind("smithlab: error: ", 0) == 0);
    for (const std::string& e : expected) CHECK(r.err.find(e) != std::string::npos);
    CHECK_FALSE(fs::exists(d / "never"));
}

Run refused_option(const std::string& args, const std::string& option, const std::string& why) {
    const Run r = run(args);
    INFO(args << "\n" << r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.find(option) != std::string::npos);
    CHECK(r.err.find(why) != std::string::npos);
    return r;
}

}  // namespace

TEST_CASE("scene: lists nested past the depth limit are refused before parsing, with FILE:LINE", "[scene][strict]") {
    const fs::path d = scratch();
    const std::string deep = "a = " + std::string(6000, '[') + std::string(6000, ']') + "\n";
    refused_trace(d, "deep.toml", "title = \"x\"\n" + deep, {"deep.toml:2:", "nested deeper than 64"});
    write(d / "deep_fit.toml", deep);
    const Run fit = run("fit '" + (d / "deep_fit.toml").string() + "' -o '" + (d / "never").string() + "'");
    CHECK(fit.rc == 2);
    CHECK(fit.err.find("deep_fit.toml:1:") != std::string::npos);
    const Run report = run_scene(d, "deep_report.toml", "x = " + std::string(100, '{') + "\n", "never");
    CHECK(report.rc == 2);
    CHECK(report.err.find("nested deeper than 64") != std::string::npos);
    // Dotted keys nest a table per dot.
    refused_trace(d, "dotted.toml", "a" + std::string(100, '.') + " = 1\n", {"dotted.toml:1:"});
    // Brackets inside strings and comments do not count.
    write(d / "strings.toml",
          "title = \"" + std::string(100, '[') + "\"\n" + trace_scene("n = 10 # " + std::string(100, '[')));
    const Run ok = run("trace '" + (d / "strings.toml").string() + "' -o '" + (d / "ok").string() + "'");
    INFO(ok.err);
    CHECK(ok.rc == 0);
}

TEST_CASE("scene: integers beyond 64 bits and reals beyond the doubles are refused, naming key and line",
          "[scene][strict]") {
    const fs::path d = scratch();
    refused_trace(d, "seed.toml", trace_scene("n = 10\nseed = 18446744073709551616"),
                  {"seed.toml:4: walks.seed is out of range", "18446744073709551616"});
    refused_trace(d, "hex.toml", trace_scene("n = 10\nseed = 0xffffffffffffffff"),
                  {"hex.toml:4: walks.seed is out of range", "0xffffffffffffffff"});
    refused_trace(d, "n.toml", trace_scene("n = 100000000000000000000"),
                  {"n.toml:3: walks.n is out of range", "100000000000000000000"});
    refused_trace(d, "big.toml", trace_scene("n = 10", "[1e400]"),
                  {"big.toml:5: grid.theta_i is out of range", "1e400"});
    refused_trace(d, "tiny.toml", trace_scene("n = 10", "[45.0, 1e-400]"),
                  {"tiny.toml:5: grid.theta_i is out of range", "1e-400"});
    // The largest int64 and the smallest subnormal are values, not overflows.
    write(d / "edge.toml", trace_scene("n = 10\nseed = 9223372036854775807", "[5e-324]"));
    const Run ok = run("trace '" + (d / "edge.toml").string() + "' -o '" + (d / "edge").string() + "'");
    INFO(ok.err);
    CHECK(ok.rc == 0);
}

TEST_CASE("options: numbers beyond their types, NaN and underflow are refused, naming the option", "[scene][strict]") {
    const fs::path d = scratch();
    const std::string out = " -o '" + (d / "never").string() + "'";
    refused_option("trace --theta-i 1e-400" + out, "--theta-i", "below the smallest double");
    refused_option("trace --theta-i 1e400" + out, "--theta-i", "beyond the largest double");
    refused_option("trace --phi-i nan" + out, "--phi-i", "NaN");
    CHECK(run("trace --phi-i nan" + out).err.find("--theta-i") == std::string::npos);
    refused_option("trace --phi-i inf" + out, "--phi-i", "finite");
    refused_option("trace --walks 99999999999999999999" + out, "--walks", "out of range");
    refused_option("brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 45,180 --walks 99999999999999999999",
                   "--walks", "out of range");
    refused_option("brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 45,180 --threads -1", "--threads",
                   ">= 0");
    refused_option("sample --ndf 'ggx(alpha=0.5)' --sampler vndf --theta-i 1e-400", "--theta-i",
                   "below the smallest double");
    CHECK_FALSE(fs::exists(d / "never"));
    // A subnormal result is a value.
    const Run ok = run("trace --theta-i 5e-324 --walks 10" + std::string(" -o '") + (d / "sub").string() + "'");
    INFO(ok.err);
    CHECK(ok.rc == 0);
}

TEST_CASE("scene: sizes are bounded before work starts, with a flag to raise them", "[scene][strict]") {
    const fs::path d = scratch();
    const std::string grid = "[grid]\ntheta_i = {lin = [0, 80], n = 10000}\nphi_i = {lin = [0, 360], n = 10000}\n";
    const std::string scene =
        "materials = [\"mirror\"]\n[walks]\nn = 10\n" + grid + "[[ndf]]\nspec = \"ggx(alpha=0.5)\"\n";
    refused_trace(d, "cells.toml", scene, {"cells.toml:8: ndf.spec", "1e+08 cells", "--max-cells 1e+06"});
    refused_trace(d, "walks.toml", trace_scene("n = 1000000000000", "[0, 30, 60]"),
                  {"walks.toml:7: ndf.spec", "3e+12 walks", "--max-walks 1e+11"});
    refused_trace(d, "bins.toml", trace_scene("n = 10") + "[brdf]\ntheta_bins = 10000\nphi_bins = 1000\n",
                  {"bins.toml:7: ndf.spec", "brdf bins", "--max-cells"});
    refused_option("trace --walks 1000000000000 -o '" + (d / "never").string() + "'", "--walks", "--max-walks");
    // The flag raises the bound: the same scene is then refused no more (--max-walks only, run on 3 cells of 10 walks).
    refused_trace(d, "raise.toml", trace_scene("n = 10", "[0, 30, 60]"), {"--max-walks 1"}, "--max-walks 1");
    write(d / "raised.toml", trace_scene("n = 10", "[0, 30, 60]"));
    const Run ok =
        run("trace '" + (d / "raised.toml").string() + "' --max-walks 30 -o '" + (d / "raised").string() + "'");
    INFO(ok.err);
    CHECK(ok.rc == 0);
    // fit: the default scene under a tiny bound names the [[ndf]] entry and the flag.
    const Run fit = refused_option("fit --max-walks 1000 -o '" + (d / "never").string() + "'", "--max-walks", "walks");
    CHECK(fit.err.find("<default scene>:") != std::string::npos);
}

TEST_CASE("scene files are read with a size cap: /dev/zero and a large file are refused", "[scene][strict]") {
    const fs::path d = scratch();
    refused_option("trace /dev/zero -o '" + (d / "never").string() + "'", "/dev/zero", "1048576 bytes");
    write(d / "large.toml", "# " + std::string(2 << 20, 'x') + "\n");
    refused_option("fit '" + (d / "large.toml").string() + "' -o '" + (d / "never").string() + "'", "large.toml",
                   "1048576 bytes");
    refused_option(report_args(d, "large.toml", "never"), "large.toml", "1048576 bytes");
}

TEST_CASE("scene: a duplicated fit model, an unknown estimator and an include pattern that matches nothing are refused",
          "[scene][strict]") {
    const fs::path d = scratch();
    write(d / "fit.toml",
          "models = [\"lambert\", \"lambert\"]\n[[ndf]]\nfamily = \"ggx\"\n"
          "[training]\nalpha = [0.5]\ntheta = [0.0]\nphi = [0.0]\nwalks = 100\n");
    const Run fit = refused_option("fit '" + (d / "fit.toml").string() + "' -o '" + (d / "never").string() + "'",
                                   "fit.toml:1: models", "names 'lambert' twice");
    CHECK_FALSE(fs::exists(d / "never"));
    write(d / "estimator.toml",
          "estimator = \"position-free\"\n[[ndf]]\nfamily = \"ggx\"\n"
          "[training]\nalpha = [0.5]\ntheta = [0.0]\nphi = [0.0]\nwalks = 100\n");
    refused_option("fit '" + (d / "estimator.toml").string() + "' -o '" + (d / "never").string() + "'",
                   "estimator.toml:1: estimator", "\"position_free\", got 'position-free'");
    CHECK_FALSE(fs::exists(d / "never"));
    const std::string report = "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\n";
    const std::string typo = check_bad_scene(d, "typo.toml", report + "include = [\"schlick-ggx\", \"schlik-ggx\"]\n",
                                             "typo.toml:7: variants.include pattern 'schlik-ggx' matches no name");
    CHECK(typo.find("did you mean 'schlick-ggx'?") != std::string::npos);
    check_bad_scene(d, "exclude.toml", report + "include = [\"*\"]\nexclude = [\"quadrature\"]\n",
                    "exclude.toml:8: variants.exclude pattern 'quadrature' matches no name");
}
