// Strict scenes (issue 9): a report scene with an unknown key, a value of the wrong type, an integer out of its
// bounds, or more work than the stated limit is refused before anything is computed: exit 2, a message naming the
// key with FILE:LINE (and the nearest known key, the expected type, or the estimate and how to raise the limit),
// and no output directory.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "cli_run.hpp"

using namespace smithlab_test;

namespace {

// A scene that would run quickly; its lines are numbered in the comments, for the FILE:LINE the messages name.
const std::string grid_lines =
    "[grid]\n"                      // 1
    "alpha = [0.1, 0.5]\n"          // 2
    "mu = [1.0, 2.0, 3.0]\n"        // 3
    "[[ndf]]\n"                     // 4
    "family = \"ggx\"\n";           // 5
const std::string variant_lines =
    "[variants]\n"                  // 6
    "include = [\"schlick-ggx\"]\n";  // 7

// FILE:LINE as the messages write it, for a scene written to d/name.
std::string at(const fs::path& d, const std::string& name, int line) { return (d / name).string() + ":" + std::to_string(line) + ": "; }

std::string fresh_dir(const std::string& name) {
    const fs::path d = scratch() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

}  // namespace

TEST_CASE("scenes: an unknown key or section is refused with FILE:LINE and the nearest known key", "[scenes]") {
    const fs::path d = fresh_dir("unknown");
    std::string err = check_bad_scene(d, "titel.toml", "titel = \"x\"\n" + grid_lines + variant_lines, "unknown key 'titel'");
    CHECK_THAT(err, Catch::Contains(at(d, "titel.toml", 1)) && Catch::Contains("did you mean 'title'?"));

    err = check_bad_scene(d, "timng.toml", grid_lines + variant_lines + "[timng]\nmin_time = 0.01\n", "unknown section 'timng'");
    CHECK_THAT(err, Catch::Contains(at(d, "timng.toml", 8)) && Catch::Contains("did you mean 'timing'?"));

    err = check_bad_scene(d, "min_tme.toml", grid_lines + variant_lines + "[timing]\nmin_tme = 0.01\n", "unknown key 'timing.min_tme'");
    CHECK_THAT(err, Catch::Contains(at(d, "min_tme.toml", 9)) && Catch::Contains("did you mean 'timing.min_time'?"));

    err = check_bad_scene(d, "exlude.toml", grid_lines + variant_lines + "exlude = [\"q2d-*\"]\n", "unknown key 'variants.exlude'");
    CHECK_THAT(err, Catch::Contains(at(d, "exlude.toml", 8)) && Catch::Contains("did you mean 'variants.exclude'?"));

    err = check_bad_scene(d, "gama.toml", grid_lines + "[[ndf]]\nfamily = \"gtr\"\ngama = [1.5]\n" + variant_lines,
                          "unknown key 'ndf.gama'");
    CHECK_THAT(err, Catch::Contains(at(d, "gama.toml", 8)) && Catch::Contains("did you mean 'ndf.gamma'?"));

    // In an inline table, and a misspelt required key (refused as unknown, not as "family is missing").
    err = check_bad_scene(d, "lgo.toml", "[grid]\nalpha = { lgo = [0.1, 1.0], n = 3 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                          "unknown key 'grid.alpha.lgo'");
    CHECK_THAT(err, Catch::Contains(at(d, "lgo.toml", 2)) && Catch::Contains("did you mean 'grid.alpha.log'?"));
    err = check_bad_scene(d, "familiy.toml", "[grid]\nalpha = [0.1]\nmu = [1.0]\n[[ndf]]\nfamiliy = \"ggx\"\n" + variant_lines,
                          "unknown key 'ndf.familiy'");
    CHECK_THAT(err, Catch::Contains("did you mean 'ndf.family'?"));

    // Nothing near: the known keys are listed. Every unknown key of a table is named, in the file's order.
    err = check_bad_scene(d, "far.toml", "colour = 3\n" + grid_lines + variant_lines + "[figures]\nparetto = true\nheat = true\n",
                          "unknown key 'colour'");
    CHECK_THAT(err, Catch::Contains(at(d, "far.toml", 1)) && Catch::Contains("known here: title, grid, ndf, variants"));
    err = check_bad_scene(d, "figs.toml", grid_lines + variant_lines + "[figures]\nparetto = true\nheat = true\n",
                          "unknown key 'figures.paretto' (did you mean 'figures.pareto'?)");
    CHECK_THAT(err, Catch::Contains(at(d, "figs.toml", 10) + "unknown key 'figures.heat'"));
    CHECK(err.find("paretto") < err.find("heat"));
}

TEST_CASE("scenes: a value of the wrong type is refused naming key, FILE:LINE and the expected type", "[scenes]") {
    const fs::path d = fresh_dir("types");
    // An integer where a real is meant is that real: min_time = 1 is 1.0, the scene goes on to the next check.
    const Run ok = run_scene(d, "int_real.toml", grid_lines + "[variants]\ninclude = [\"nothing*\"]\n[timing]\nmin_time = 1\n", "never");
    INFO(ok.err);
    CHECK(ok.rc == 2);
    CHECK_THAT(ok.err, Catch::Contains("selects no variant"));
    CHECK_FALSE(fs::exists(d / "never"));

    std::string err = check_bad_scene(d, "title.toml", "title = 5\n" + grid_lines + variant_lines, "title must be a string, got an integer (5)");
    CHECK_THAT(err, Catch::Contains(at(d, "title.toml", 1)));

    err = check_bad_scene(d, "samples.toml",
                          grid_lines + variant_lines + "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.1]\nsamples = 1000.5\n",
                          "sampling.samples must be an integer in [100, 100000000], got a real (1000.5)");
    CHECK_THAT(err, Catch::Contains(at(d, "samples.toml", 11)));

    err = check_bad_scene(d, "flag.toml", grid_lines + variant_lines + "[figures]\npareto = \"yes\"\n", "figures.pareto must be true or false");
    CHECK_THAT(err, Catch::Contains(at(d, "flag.toml", 9)));
    err = check_bad_scene(d, "include.toml", grid_lines + "[variants]\ninclude = \"*\"\n", "variants.include must be a list of strings, got a string");
    CHECK_THAT(err, Catch::Contains(at(d, "include.toml", 7)));
    err = check_bad_scene(d, "alpha.toml", "[grid]\nalpha = [0.1, \"big\"]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                          "grid.alpha must be a list of numbers, got a string (\"big\") in it");
    CHECK_THAT(err, Catch::Contains(at(d, "alpha.toml", 2)));
    err = check_bad_scene(d, "ndf.toml", "[grid]\nalpha = [0.1]\nmu = [1.0]\n[ndf]\nfamily = \"ggx\"\n" + variant_lines,
                          "ndf must be tables, each opened by [[ndf]]");
    CHECK_THAT(err, Catch::Contains(at(d, "ndf.toml", 4)));
    err = check_bad_scene(d, "time.toml", grid_lines + variant_lines + "[timing]\nmin_time = 20\n", "timing.min_time must be in (0, 10] seconds");
    CHECK_THAT(err, Catch::Contains(at(d, "time.toml", 9)));
    // A missing section is named, with the file.
    err = check_bad_scene(d, "novariants.toml", grid_lines, "variants is missing");
    CHECK_THAT(err, Catch::Contains((d / "novariants.toml").string()));
}

TEST_CASE("scenes: integers are 64-bit and bounded, an axis holds at most 1e7 points", "[scenes]") {
    const fs::path d = fresh_dir("integers");
    // 4294967298 = 2^32 + 2 was a 2-point grid through an int.
    std::string err = check_bad_scene(d, "wrap.toml",
                                      "[grid]\nalpha = { log = [1e-4, 1.0], n = 4294967298 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                                      "grid.alpha.n must be an integer in [2, 10000000], got 4294967298");
    CHECK_THAT(err, Catch::Contains(at(d, "wrap.toml", 2)));
    err = check_bad_scene(d, "float_n.toml", "[grid]\nalpha = [0.1]\nmu = { lin = [0.1, 10.0], n = 1e8 }\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                          "grid.mu.n must be an integer in [2, 10000000], got a real");
    CHECK_THAT(err, Catch::Contains(at(d, "float_n.toml", 3)));
    check_bad_scene(d, "big_n.toml", "[grid]\nalpha = [0.1]\nmu = { lin = [0.1, 10.0], n = 100000000 }\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                    "grid.mu.n must be an integer in [2, 10000000], got 100000000");
    check_bad_scene(d, "seed.toml", grid_lines + variant_lines + "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.1]\nseed = -1\n",
                    "sampling.seed must be an integer in [0, 9223372036854775807], got -1");
    check_bad_scene(d, "both.toml", "[grid]\nalpha = { log = [0.1, 1.0], lin = [0.1, 1.0], n = 3 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                    "grid.alpha must hold exactly one of log = [lo, hi] and lin = [lo, hi]");
}

TEST_CASE("scenes: work beyond the limit is refused at once with the estimate, and --max-work raises the limit", "[scenes]") {
    const fs::path d = fresh_dir("work");
    // 3000 alpha x 3000 mu x 100 gamma: ~1e9 points per variant. Refused before anything is made.
    const std::string huge =
        "[grid]\nalpha = { log = [1e-4, 1.0], n = 3000 }\nmu = { log = [1e-4, 1e4], n = 3000 }\n"
        "[[ndf]]\nfamily = \"gtr\"\ngamma = { lin = [0.0, 20.0], n = 100 }\n[variants]\ninclude = [\"table\"]\n";
    const std::string err = check_bad_scene(d, "huge.toml", huge, "the scene's work is estimated at 1.8e+09 evaluations (Lambda 9e+08, G2 0, references 9e+08, samples 0)");
    CHECK_THAT(err, Catch::Contains((d / "huge.toml").string()) && Catch::Contains("above the limit of 1e+08 evaluations") &&
                        Catch::Contains("nothing was computed") && Catch::Contains("--max-work 1.8e+09"));

    // The override lets it through the limit: it then stops at the scene's next error (an unknown family, checked
    // before anything is computed), not at the limit.
    write(d / "huge_bad.toml", "[grid]\nalpha = { log = [1e-4, 1.0], n = 3000 }\nmu = { log = [1e-4, 1e4], n = 3000 }\n"
                               "[[ndf]]\nfamily = \"nosuch\"\n[[ndf]]\nfamily = \"gtr\"\ngamma = { lin = [0.0, 20.0], n = 100 }\n"
                               "[variants]\ninclude = [\"table\"]\n");
    const Run limited = run(report_args(d, "huge_bad.toml", "never"));
    CHECK(limited.rc == 2);
    CHECK_THAT(limited.err, Catch::Contains("above the limit"));
    const Run raised = run(report_args(d, "huge_bad.toml", "never") + " --max-work 2e9");
    INFO(raised.err);
    CHECK(raised.rc == 2);
    CHECK_THAT(raised.err, Catch::Contains("unknown ndf family 'nosuch'"));
    CHECK_FALSE(fs::exists(d / "never"));

    // Samples and G2 count too; the sampling experiment alone can exceed the limit.
    check_bad_scene(d, "samples.toml", grid_lines + variant_lines + "[sampling]\nfamilies = [\"ggx\", \"beckmann\"]\nalpha = { log = [1e-3, 1.0], n = 10 }\nsamples = 100000000\n",
                    "(Lambda 6, G2 0, references 6, samples 6e+09)");

    // The estimate is exact for a small scene: 2 alpha x 3 mu x 1 NDF x 1 variant = 6 Lambdas and 6 references.
    // Below it, refused; at it, the report runs (and says the estimate).
    write(d / "small.toml", grid_lines + variant_lines + "[timing]\nmin_time = 0.01\n");
    const Run below = run(report_args(d, "small.toml", "never") + " --max-work 11");
    CHECK(below.rc == 2);
    CHECK_THAT(below.err, Catch::Contains("estimated at 12 evaluations") && Catch::Contains("above the limit of 11 evaluations"));
    CHECK_FALSE(fs::exists(d / "never"));
    const Run at_limit = run(report_args(d, "small.toml", "rep") + " --max-work 12");
    INFO(at_limit.err);
    CHECK(at_limit.rc == 0);
    CHECK_THAT(at_limit.err, Catch::Contains("work estimated at 12 evaluations (Lambda 6, G2 0, references 6, samples 0)"));
    CHECK_THAT(slurp(d / "rep" / "variants.csv"), Catch::Contains("schlick-ggx,6,"));

    // A limit that is not a positive number is refused.
    for (const char* bad : {"0", "-5", "nan", "many"}) {
        const Run r = run(report_args(d, "small.toml", "never") + " --max-work " + bad);
        INFO(bad << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("--max-work"));
    }
}

TEST_CASE("scenes: a grid mu outside the quadrature's domain is refused before any work where a quadrature would meet it", "[scenes]") {
    const fs::path d = fresh_dir("domain");
    // closed-form is checked against Boost 1D quadrature, which takes mu in [1e-12, 1e12]: mu = 1e154 is refused
    // up front, naming the mu, the NDF and the variant (it used to fail mid-run and leave an empty --out).
    const std::string grid = "[grid]\nalpha = [0.2, 0.6]\nmu = [1e154, 0.5]\n[[ndf]]\nfamily = \"ggx\"\n";
    const std::string err = check_bad_scene(d, "closed.toml", grid + "[variants]\ninclude = [\"closed-form\"]\n",
                                            "scene: grid.mu = 1e+154 for ggx(alpha=0.2) (variant closed-form): mu must be in [1e-12, 1e12]");
    // A quadrature variant itself, at a tiny mu below 1e-12 x the slope scale alpha.
    check_bad_scene(d, "q1d.toml", "[grid]\nalpha = [0.2]\nmu = [1e-13]\n[[ndf]]\nfamily = \"beckmann\"\n[variants]\ninclude = [\"q1d-gsl-1e-8\"]\n",
                    "scene: grid.mu = 1e-13 for beckmann(alpha=0.2) (variant q1d-gsl-1e-8): mu must be in [1e-12, 1e12]");
    // An approximation checked against the closed form meets no quadrature: the same grid runs, right to the end.
    write(d / "approx.toml", grid + "[variants]\ninclude = [\"schlick-ggx\"]\n[timing]\nmin_time = 0.01\n");
    const Run ok = run(report_args(d, "approx.toml", "rep"));
    INFO(ok.err);
    CHECK(ok.rc == 0);
    CHECK_THAT(slurp(d / "rep" / "variants.csv"), Catch::Contains("schlick-ggx,4,"));
}

TEST_CASE("scenes: the default scene is read strictly and is far inside the default limit", "[scenes]") {
    const fs::path d = fresh_dir("default");
    // --max-work 1 refuses it with its estimate: about 1.2e7 evaluations, most of them the sampling experiment's.
    const Run r = run("report --out '" + (d / "never").string() + "' --max-work 1");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("<default scene>: the scene's work is estimated at 1.2") && Catch::Contains("e+07 evaluations"));
    CHECK_FALSE(fs::exists(d / "never"));
    CHECK_THAT(run("report --help").out, Catch::Contains("--max-work"));
}

TEST_CASE("scenes: --scene naming a directory, a missing or an unreadable file is refused naming it", "[scenes]") {
    const fs::path d = fresh_dir("files");
    fs::create_directories(d / "a_dir");
    Run r = run(report_args(d, "a_dir", "never"));
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("scene file '" + (d / "a_dir").string() + "' is a directory"));
    r = run(report_args(d, "absent.toml", "never"));
    CHECK(r.rc == 2);
    CHECK_THAT(r.err, Catch::Contains("cannot open scene file '" + (d / "absent.toml").string() + "'"));
    if (::geteuid() != 0) {  // root reads any file
        write(d / "locked.toml", grid_lines + variant_lines);
        fs::permissions(d / "locked.toml", fs::perms::none);
        r = run(report_args(d, "locked.toml", "never"));
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("cannot open scene file '" + (d / "locked.toml").string() + "': Permission denied"));
    }
    CHECK_FALSE(fs::exists(d / "never"));
}
