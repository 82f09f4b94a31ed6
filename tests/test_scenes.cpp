// Strict scenes: a report scene with an unknown key, a value of the wrong type, an integer out of its
// bounds, or more work than the stated limit is refused before anything is computed: exit 2, a message naming the
// key with FILE:LINE (and the nearest known key, the expected type, or the estimate and how to raise the limit),
// and no output directory.
#include <catch2/catch.hpp>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/single_scattering.hpp"

using namespace smithlab_test;

namespace {

// A scene that would run quickly; its lines are numbered in the comments, for the FILE:LINE the messages name.
const std::string grid_lines =
    "[grid]\n"                // 1
    "alpha = [0.1, 0.5]\n"    // 2
    "mu = [1.0, 2.0, 3.0]\n"  // 3
    "[[ndf]]\n"               // 4
    "family = \"ggx\"\n";     // 5
const std::string variant_lines =
    "[variants]\n"                    // 6
    "include = [\"schlick-ggx\"]\n";  // 7

// FILE:LINE as the messages write it, for a scene written to d/name.
std::string at(const fs::path& d, const std::string& name, int line) {
    return (d / name).string() + ":" + std::to_string(line) + ": ";
}

std::string fresh_dir(const std::string& name) {
    const fs::path d = scratch() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}

}  // namespace

TEST_CASE("scenes: an unknown key or section is refused with FILE:LINE and the nearest known key", "[scenes]") {
    const fs::path d = fresh_dir("unknown");
    std::string err =
        check_bad_scene(d, "titel.toml", "titel = \"x\"\n" + grid_lines + variant_lines, "unknown key 'titel'");
    CHECK_THAT(err, Catch::Contains(at(d, "titel.toml", 1)) && Catch::Contains("did you mean 'title'?"));

    err = check_bad_scene(d, "timng.toml", grid_lines + variant_lines + "[timng]\nmin_time = 0.01\n",
                          "unknown section 'timng'");
    CHECK_THAT(err, Catch::Contains(at(d, "timng.toml", 8)) && Catch::Contains("did you mean 'timing'?"));

    err = check_bad_scene(d, "min_tme.toml", grid_lines + variant_lines + "[timing]\nmin_tme = 0.01\n",
                          "unknown key 'timing.min_tme'");
    CHECK_THAT(err, Catch::Contains(at(d, "min_tme.toml", 9)) && Catch::Contains("did you mean 'timing.min_time'?"));

    err = check_bad_scene(d, "exlude.toml", grid_lines + variant_lines + "exlude = [\"q2d-*\"]\n",
                          "unknown key 'variants.exlude'");
    CHECK_THAT(err, Catch::Contains(at(d, "exlude.toml", 8)) && Catch::Contains("did you mean 'variants.exclude'?"));

    err = check_bad_scene(d, "gama.toml", grid_lines + "[[ndf]]\nfamily = \"gtr\"\ngama = [1.5]\n" + variant_lines,
                          "unknown key 'ndf.gama'");
    CHECK_THAT(err, Catch::Contains(at(d, "gama.toml", 8)) && Catch::Contains("did you mean 'ndf.gamma'?"));

    // In an inline table, and a misspelt required key (refused as unknown, not as "family is missing").
    err = check_bad_scene(
        d, "lgo.toml",
        "[grid]\nalpha = { lgo = [0.1, 1.0], n = 3 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
        "unknown key 'grid.alpha.lgo'");
    CHECK_THAT(err, Catch::Contains(at(d, "lgo.toml", 2)) && Catch::Contains("did you mean 'grid.alpha.log'?"));
    err = check_bad_scene(d, "familiy.toml",
                          "[grid]\nalpha = [0.1]\nmu = [1.0]\n[[ndf]]\nfamiliy = \"ggx\"\n" + variant_lines,
                          "unknown key 'ndf.familiy'");
    CHECK_THAT(err, Catch::Contains("did you mean 'ndf.family'?"));

    // Nothing near: the known keys are listed. Every unknown key of a table is named, in the file's order.
    err = check_bad_scene(d, "far.toml",
                          "colour = 3\n" + grid_lines + variant_lines + "[figures]\nparetto = true\nheat = true\n",
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
    const Run ok = run_scene(d, "int_real.toml",
                             grid_lines + "[variants]\ninclude = [\"nothing*\"]\n[timing]\nmin_time = 1\n", "never");
    INFO(ok.err);
    CHECK(ok.rc == 2);
    CHECK_THAT(ok.err, Catch::Contains("pattern 'nothing*' matches no name"));
    CHECK_FALSE(fs::exists(d / "never"));

    std::string err = check_bad_scene(d, "title.toml", "title = 5\n" + grid_lines + variant_lines,
                                      "title must be a string, got an integer (5)");
    CHECK_THAT(err, Catch::Contains(at(d, "title.toml", 1)));

    err = check_bad_scene(
        d, "samples.toml",
        grid_lines + variant_lines + "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.1]\nsamples = 1000.5\n",
        "sampling.samples must be an integer in [100, 100000000], got a real (1000.5)");
    CHECK_THAT(err, Catch::Contains(at(d, "samples.toml", 11)));

    err = check_bad_scene(d, "flag.toml", grid_lines + variant_lines + "[figures]\npareto = \"yes\"\n",
                          "figures.pareto must be true or false");
    CHECK_THAT(err, Catch::Contains(at(d, "flag.toml", 9)));
    err = check_bad_scene(d, "include.toml", grid_lines + "[variants]\ninclude = \"*\"\n",
                          "variants.include must be a list of strings, got a string");
    CHECK_THAT(err, Catch::Contains(at(d, "include.toml", 7)));
    err = check_bad_scene(d, "alpha.toml",
                          "[grid]\nalpha = [0.1, \"big\"]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
                          "grid.alpha must be a list of numbers, got a string (\"big\") in it");
    CHECK_THAT(err, Catch::Contains(at(d, "alpha.toml", 2)));
    err = check_bad_scene(d, "ndf.toml", "[grid]\nalpha = [0.1]\nmu = [1.0]\n[ndf]\nfamily = \"ggx\"\n" + variant_lines,
                          "ndf must be tables, each opened by [[ndf]]");
    CHECK_THAT(err, Catch::Contains(at(d, "ndf.toml", 4)));
    err = check_bad_scene(d, "time.toml", grid_lines + variant_lines + "[timing]\nmin_time = 20\n",
                          "timing.min_time must be in (0, 10] seconds");
    CHECK_THAT(err, Catch::Contains(at(d, "time.toml", 9)));
    // A missing section is named, with the file.
    err = check_bad_scene(d, "novariants.toml", grid_lines, "variants is missing");
    CHECK_THAT(err, Catch::Contains((d / "novariants.toml").string()));
}

TEST_CASE("scenes: integers are 64-bit and bounded, an axis holds at most 1e7 points", "[scenes]") {
    const fs::path d = fresh_dir("integers");
    // 4294967298 = 2^32 + 2 was a 2-point grid through an int.
    std::string err = check_bad_scene(
        d, "wrap.toml",
        "[grid]\nalpha = { log = [1e-4, 1.0], n = 4294967298 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" +
            variant_lines,
        "grid.alpha.n must be an integer in [2, 10000000], got 4294967298");
    CHECK_THAT(err, Catch::Contains(at(d, "wrap.toml", 2)));
    err = check_bad_scene(
        d, "float_n.toml",
        "[grid]\nalpha = [0.1]\nmu = { lin = [0.1, 10.0], n = 1e8 }\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
        "grid.mu.n must be an integer in [2, 10000000], got a real");
    CHECK_THAT(err, Catch::Contains(at(d, "float_n.toml", 3)));
    check_bad_scene(
        d, "big_n.toml",
        "[grid]\nalpha = [0.1]\nmu = { lin = [0.1, 10.0], n = 100000000 }\n[[ndf]]\nfamily = \"ggx\"\n" + variant_lines,
        "grid.mu.n must be an integer in [2, 10000000], got 100000000");
    check_bad_scene(d, "seed.toml",
                    grid_lines + variant_lines + "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.1]\nseed = -1\n",
                    "sampling.seed must be an integer in [0, 9223372036854775807], got -1");
    check_bad_scene(
        d, "both.toml",
        "[grid]\nalpha = { log = [0.1, 1.0], lin = [0.1, 1.0], n = 3 }\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n" +
            variant_lines,
        "grid.alpha must hold exactly one of log = [lo, hi], lin = [lo, hi], sqrt = [lo, hi] and cbrt = [lo, hi]");
}

TEST_CASE("scenes: work beyond the limit is refused at once with the estimate, and --max-work raises the limit",
          "[scenes]") {
    const fs::path d = fresh_dir("work");
    // 3000 alpha x 3000 mu x 100 gamma: ~1e9 points per variant. Refused before anything is made.
    const std::string huge =
        "[grid]\nalpha = { log = [1e-4, 1.0], n = 3000 }\nmu = { log = [1e-4, 1e4], n = 3000 }\n"
        "[[ndf]]\nfamily = \"gtr\"\ngamma = { lin = [0.0, 20.0], n = 100 }\n[variants]\ninclude = [\"table\"]\n";
    const std::string err = check_bad_scene(
        d, "huge.toml", huge,
        "the scene's work is estimated at 1.8e+09 evaluations (Lambda 9e+08, references 9e+08, G2 0, samples 0)");
    CHECK_THAT(err,
               Catch::Contains((d / "huge.toml").string()) && Catch::Contains("above the limit of 1e+08 evaluations") &&
                   Catch::Contains("nothing was computed") && Catch::Contains("--max-work 1.8e+09"));

    // The override lets it through the limit: it then stops at the scene's next error (a value out of its family's
    // domain, checked before anything is computed), not at the limit.
    write(
        d / "huge_bad.toml",
        "[grid]\nalpha = { log = [1e-4, 1.0], n = 3000 }\nmu = { log = [1e-4, 1e4], n = 3000 }\n"
        "[[ndf]]\nfamily = \"gtr\"\ngamma = [-1.0]\n[[ndf]]\nfamily = \"gtr\"\ngamma = { lin = [0.0, 20.0], n = 100 }\n"
        "[variants]\ninclude = [\"table\"]\n");
    const Run limited = run(report_args(d, "huge_bad.toml", "never"));
    CHECK(limited.rc == 2);
    CHECK_THAT(limited.err, Catch::Contains("above the limit"));
    const Run raised = run(report_args(d, "huge_bad.toml", "never") + " --max-work 2e9");
    INFO(raised.err);
    CHECK(raised.rc == 2);
    CHECK_THAT(raised.err, Catch::Contains("ndf.family 'gtr' at gtr(alpha=1e-04, gamma=-1): gtr: gamma must be"));
    CHECK_FALSE(fs::exists(d / "never"));

    // Samples and G2 count too; the sampling experiment alone can exceed the limit.
    check_bad_scene(d, "samples.toml",
                    grid_lines + variant_lines +
                        "[sampling]\nfamilies = [\"ggx\", \"beckmann\"]\nalpha = { log = [1e-3, 1.0], n = 10 "
                        "}\nsamples = 100000000\n",
                    "(Lambda 6, references 6, G2 0, samples 6e+09)");

    // The estimate is exact for a small scene: 2 alpha x 3 mu x 1 NDF x 1 variant = 6 Lambdas and 6 references.
    // Below it, refused; at it, the report runs (and says the estimate).
    write(d / "small.toml", grid_lines + variant_lines + "[timing]\nmin_time = 0.01\n");
    const Run below = run(report_args(d, "small.toml", "never") + " --max-work 11");
    CHECK(below.rc == 2);
    CHECK_THAT(below.err,
               Catch::Contains("estimated at 12 evaluations") && Catch::Contains("above the limit of 11 evaluations"));
    CHECK_FALSE(fs::exists(d / "never"));
    const Run at_limit = run(report_args(d, "small.toml", "rep") + " --max-work 12");
    INFO(at_limit.err);
    CHECK(at_limit.rc == 0);
    CHECK_THAT(at_limit.err,
               Catch::Contains("work estimated at 12 evaluations (Lambda 6, references 6, G2 0, samples 0)"));
    CHECK_THAT(slurp(d / "rep" / "variants.csv"), Catch::Contains("schlick-ggx,6,"));

    // A limit that is not a positive number is refused.
    for (const char* bad : {"0", "-5", "nan", "many"}) {
        const Run r = run(report_args(d, "small.toml", "never") + " --max-work " + bad);
        INFO(bad << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("--max-work"));
    }
}

TEST_CASE(
    "scenes: a grid mu outside the quadrature's domain is refused before any work where a quadrature would meet it",
    "[scenes]") {
    const fs::path d = fresh_dir("domain");
    // closed-form is checked against Boost 1D quadrature, which takes mu in [1e-12, 1e12]: mu = 1e154 is refused
    // up front, naming the mu, the NDF and the variant, before anything runs or is written.
    const std::string grid = "[grid]\nalpha = [0.2, 0.6]\nmu = [1e154, 0.5]\n[[ndf]]\nfamily = \"ggx\"\n";
    const std::string err = check_bad_scene(
        d, "closed.toml", grid + "[variants]\ninclude = [\"closed-form\"]\n",
        "scene: grid.mu = 1e+154 for ggx(alpha=0.2) (variant closed-form): mu must be in [1e-12, 1e12]");
    // A quadrature variant itself, at a tiny mu below 1e-12 x the slope scale alpha.
    check_bad_scene(
        d, "q1d.toml",
        "[grid]\nalpha = [0.2]\nmu = [1e-13]\n[[ndf]]\nfamily = \"beckmann\"\n[variants]\ninclude = "
        "[\"q1d-gsl-1e-8\"]\n",
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
    const Run r = run("report --output '" + (d / "never").string() + "' --max-work 1");
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err,
               Catch::Contains("<default scene>: the scene's work is estimated at 1.2") &&
                   Catch::Contains("e+07 evaluations"));
    CHECK_FALSE(fs::exists(d / "never"));
    CHECK_THAT(run("report --help").out, Catch::Contains("--max-work"));
}

TEST_CASE("scenes: a scene naming a directory, a missing or an unreadable file is refused naming it", "[scenes]") {
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
        CHECK_THAT(r.err,
                   Catch::Contains("cannot open scene file '" + (d / "locked.toml").string() + "': Permission denied"));
    }
    CHECK_FALSE(fs::exists(d / "never"));
}

// ---- the walk section ------------------------------------------------------------------------------------

namespace {

// The report's [walk] after a quick scene (lines 1-9); its lines are numbered as the messages name them.
const std::string quick_lines = grid_lines + variant_lines + "[timing]\nmin_time = 0.01\n";  // 1-9
const std::vector<std::string> walk_lines = {
    "[walk]",                                           // 10
    "materials = [\"mirror\", \"lambert(albedo=1)\"]",  // 11
    "alpha = [0.2, 1.0]",                               // 12
    "theta_i = [0.0, 60.0]",                            // 13
    "walks = 2000",                                     // 14
    "seed = 3",                                         // 15
    "[[walk.ndf]]",                                     // 16
    "family = \"ggx\"",                                 // 17
    "[[walk.ndf]]",                                     // 18
    "family = \"gtr\"",                                 // 19
    "gamma = [1.5]",                                    // 20
};

// The quick scene with its [walk]; line `line` (10..20) replaced by `text` ("" drops it), or extra lines appended.
std::string walk_scene(int line = 0, const std::string& text = "", const std::string& extra = "") {
    std::string s = quick_lines;
    for (int k = 10; k < 10 + static_cast<int>(walk_lines.size()); ++k)
        if (k != line) s += walk_lines[static_cast<std::size_t>(k - 10)] + "\n";
        else if (!text.empty()) s += text + "\n";
    return s + extra;
}

struct WalkRow {
    std::string ndf, family, gamma, material, theta_i, order;
    double alpha, albedo, stderr_;
};

std::vector<WalkRow> walk_rows(const fs::path& csv, std::string& header) {
    std::ifstream in(csv);
    const std::vector<smithlab::CsvRecord> records = smithlab::read_csv(in);
    std::vector<WalkRow> out;
    REQUIRE_FALSE(records.empty());
    for (const std::string& f : records[0].fields) header += (header.empty() ? "" : ",") + f;
    for (std::size_t i = 1; i < records.size(); ++i) {
        const std::vector<std::string>& f = records[i].fields;
        REQUIRE(records[i].error.empty());
        REQUIRE(f.size() == 11);
        CHECK(f[9] == "2000");
        CHECK(f[10] == (f[1] == "gtr" ? "gtr (gamma 1.5)" : f[1]));
        out.push_back({f[0], f[1], f[2], f[4], f[5], f[6], std::stod(f[3]), std::stod(f[7]), std::stod(f[8])});
    }
    return out;
}

}  // namespace

TEST_CASE("scenes: [walk] writes albedo by scattering order per NDF x material x alpha x theta_i", "[scenes][walk]") {
    const fs::path d = fresh_dir("walk");
    const Run r = run_scene(d, "walk.toml", walk_scene(), "rep");
    INFO(r.err);
    REQUIRE(r.rc == 0);
    // 2 NDFs x 2 alpha x 2 materials x 2 theta_i x 2000 walks, counted in the work estimate.
    CHECK_THAT(r.err, Catch::Contains("(Lambda 6, references 6, G2 0, samples 0, walks 3.2e+04)"));
    CHECK_THAT(r.err, Catch::Contains("report: walk section, 16 cells of 2000 walks"));

    std::string header;
    const std::vector<WalkRow> rows = walk_rows(d / "rep" / "walk_albedo.csv", header);
    CHECK(header == "ndf,family,gamma,alpha,material,theta_i,order,albedo,stderr,walks,label");
    REQUIRE(rows.size() == 16 * 6);
    std::map<std::string, std::map<std::string, WalkRow>> cells;  // cell -> order -> row
    for (const WalkRow& w : rows) {
        INFO(w.ndf << " " << w.material << " " << w.theta_i << " order " << w.order);
        CHECK(w.albedo >= 0.0);
        CHECK(w.albedo <= 1.0);
        CHECK(w.stderr_ >= 0.0);
        CHECK(w.stderr_ < 0.05);
        CHECK(w.ndf ==
              (w.family == "ggx" ? "ggx(alpha=" + smithlab::format_shortest(w.alpha) + ")"
                                 : "gtr(alpha=" + smithlab::format_shortest(w.alpha) + ", gamma=1.5)"));
        CHECK((w.family == "gtr" ? w.gamma == "1.5" : w.gamma.empty()));
        cells[w.ndf + "|" + w.material + "|" + w.theta_i][w.order] = w;
    }
    REQUIRE(cells.size() == 16);
    for (const auto& [cell, by] : cells) {
        INFO(cell);
        REQUIRE(by.size() == 6);
        // Neither facet absorbs: every walk leaves with its energy (none capped), in exactly one order.
        CHECK(by.at("all").albedo == Approx(1.0).margin(1e-12));
        CHECK(by.at("all").stderr_ == Approx(0.0).margin(1e-9));
        const double sum = by.at("1").albedo + by.at("2").albedo + by.at("3").albedo + by.at("4+").albedo;
        CHECK(sum == Approx(1.0).margin(1e-12));
        CHECK(by.at("2+").albedo == Approx(1.0 - by.at("1").albedo).margin(1e-12));
        CHECK(by.at("2+").stderr_ == Approx(by.at("1").stderr_).epsilon(1e-9));
    }
    // Order 1 of GGX mirror facets is the single-scattering BRDF's albedo (Walter et al. 2007 eq. 20, height-correlated
    // G2), integrated here by the midpoint rule over (cos theta_o, phi_o): the right NDF, alpha and theta_i were
    // traced.
    for (double alpha : {0.2, 1.0})
        for (double theta : {0.0, 60.0}) {
            const smithlab::Ggx ggx = smithlab::ggx(alpha);
            const smithlab::Vec3 wi = smithlab::direction_from_deg(theta, 0.0);
            const int n = 600;
            double want = 0.0;
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < 2 * n; ++j) {
                    const double c = (i + 0.5) / n, s = std::sqrt(1.0 - c * c), phi = std::numbers::pi * (j + 0.5) / n;
                    want += smithlab::single_scattering_reflection(ggx, wi, {s * std::cos(phi), s * std::sin(phi), c},
                                                                   [](double) { return 1.0; });
                }
            want *= (1.0 / n) * (std::numbers::pi / n);
            const WalkRow& got = cells
                                     .at("ggx(alpha=" + smithlab::format_shortest(alpha) + ")|mirror|" +
                                         smithlab::format_shortest(theta))
                                     .at("1");
            INFO("alpha " << alpha << ", theta_i " << theta << ": walk " << got.albedo << " +- " << got.stderr_
                          << ", quadrature " << want);
            CHECK(std::abs(got.albedo - want) < 4.0 * got.stderr_ + 1e-4);
        }
    // Rougher surfaces lose more to single scattering: mirror facets at alpha 1 against 0.2, for both NDFs.
    for (const std::string& ndf : {std::string("ggx(alpha=%)"), std::string("gtr(alpha=%, gamma=1.5)")}) {
        const auto lost = [&](const std::string& a) {
            std::string spec = ndf;
            spec.replace(spec.find('%'), 1, a);
            return cells.at(spec + "|mirror|60").at("2+");
        };
        INFO(ndf);
        const WalkRow smooth = lost("0.2"), rough = lost("1");
        CHECK(rough.albedo - smooth.albedo > 5.0 * std::hypot(rough.stderr_, smooth.stderr_));
    }
    // The section in report.md: a row per cell, with the figure (or the note that it was not drawn).
    const std::string md = slurp(d / "rep" / "report.md");
    CHECK_THAT(
        md,
        Catch::Contains("## Multiple scattering: albedo by scattering order (path-traced)") &&
            Catch::Contains(
                "| ndf | material | alpha | theta_i | order 1 | order 2 | order 3 | order 4+ | lost (2+) | all |") &&
            Catch::Contains("| gtr (gamma 1.5) | lambert(albedo=1) | 1 | 60 | ") &&
            Catch::Contains("![](walk_albedo.png)"));
    std::size_t walk_table_rows = 0;
    for (std::size_t at = md.find("\n| ggx |"); at != std::string::npos; at = md.find("\n| ggx |", at + 1))
        ++walk_table_rows;
    for (std::size_t at = md.find("\n| gtr (gamma 1.5) |"); at != std::string::npos;
         at = md.find("\n| gtr (gamma 1.5) |", at + 1))
        ++walk_table_rows;
    CHECK(walk_table_rows == 16);
    CHECK(
        (fs::exists(d / "rep" / "walk_albedo.png") || md.find("**The figures were not drawn**") != std::string::npos));

    // The seed and the cell's place key the walks: the same scene gives the same bits, another seed other values.
    REQUIRE(run_scene(d, "walk.toml", walk_scene(), "again").rc == 0);
    CHECK(slurp(d / "again" / "walk_albedo.csv") == slurp(d / "rep" / "walk_albedo.csv"));
    REQUIRE(run_scene(d, "seed.toml", walk_scene(15, "seed = 4"), "seed4").rc == 0);
    CHECK(slurp(d / "seed4" / "walk_albedo.csv") != slurp(d / "rep" / "walk_albedo.csv"));
}

TEST_CASE("scenes: a scene without [walk] traces no walk", "[scenes][walk]") {
    const fs::path d = fresh_dir("no_walk");
    const Run r = run_scene(d, "quick.toml", quick_lines, "rep");
    INFO(r.err);
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.err, Catch::Contains("(Lambda 6, references 6, G2 0, samples 0)"));
    CHECK(r.err.find("walk section") == std::string::npos);
    CHECK_FALSE(fs::exists(d / "rep" / "walk_albedo.csv"));
    CHECK_FALSE(fs::exists(d / "rep" / "walk_albedo.png"));
    CHECK(slurp(d / "rep" / "report.md").find("Multiple scattering") == std::string::npos);
    CHECK(fs::exists(d / "rep" / "variants.csv"));
}

TEST_CASE("scenes: a malformed [walk] is refused naming FILE:LINE and the key, before any walk", "[scenes][walk]") {
    const fs::path d = fresh_dir("bad_walk");
    const auto bad = [&](const std::string& name, const std::string& text, int line, const std::string& expected) {
        const std::string err = check_bad_scene(d, name, text, expected);
        CHECK_THAT(err, Catch::Contains(at(d, name, line)));
        CHECK(err.find("walk section") == std::string::npos);  // nothing traced
        return err;
    };
    // Keys and sections misspelt.
    bad("wlaks.toml", walk_scene(14, "wlaks = 2000"), 14, "unknown key 'walk.wlaks' (did you mean 'walk.walks'?)");
    bad("gama.toml", walk_scene(20, "gama = [1.5]"), 20,
        "unknown key 'walk.ndf.gama' (did you mean 'walk.ndf.gamma'?)");
    bad("wlak.toml", quick_lines + "[wlak]\nwalks = 100\n", 10, "unknown section 'wlak' (did you mean 'walk'?)");
    // Values of the wrong type or out of bounds.
    bad("walks_real.toml", walk_scene(14, "walks = 2000.5"), 14,
        "walk.walks must be an integer in [100, 1000000000], got a real (2000.5)");
    bad("walks_few.toml", walk_scene(14, "walks = 10"), 14,
        "walk.walks must be an integer in [100, 1000000000], got 10");
    bad("seed.toml", walk_scene(15, "seed = -1"), 15,
        "walk.seed must be an integer in [0, 9223372036854775807], got -1");
    bad("materials.toml", walk_scene(11, "materials = \"mirror\""), 11,
        "walk.materials must be a list of strings, got a string");
    bad("no_material.toml", walk_scene(11, "materials = []"), 11, "walk.materials is an empty list");
    bad("theta.toml", walk_scene(13, "theta_i = [45.0, 90.0]"), 13,
        "walk.theta_i must be in [0, 90) degrees (light from above), got 90");
    bad("theta_axis.toml", walk_scene(13, "theta_i = { lin = [0.0, 60.0] }"), 13, "walk.theta_i.n is missing");
    bad("alpha_type.toml", walk_scene(12, "alpha = [0.2, \"rough\"]"), 12,
        "walk.alpha must be a list of numbers, got a string (\"rough\") in it");
    bad("alpha_nan.toml", walk_scene(12, "alpha = [nan]"), 12, "walk.alpha must be finite, got nan");
    // Missing: alpha (the section's own line), every [[walk.ndf]].
    bad("no_alpha.toml", walk_scene(12, ""), 10, "walk.alpha is missing");
    std::string no_ndf = quick_lines;
    for (std::size_t k = 0; k < 6; ++k) no_ndf += walk_lines[k] + "\n";
    bad("no_ndf.toml", no_ndf, 10, "walk.ndf is missing: no [[walk.ndf]] table names an NDF family");
    bad("ndf_table.toml", no_ndf + "[walk.ndf]\nfamily = \"ggx\"\n", 16,
        "walk.ndf must be tables, each opened by [[walk.ndf]], got a table");
    // Materials through their parser: an unknown one, a parameter out of its range, one it does not take.
    std::string err = bad("mirorr.toml", walk_scene(11, "materials = [\"mirror\", \"mirorr\"]"), 11,
                          "walk.materials holds \"mirorr\": ");
    CHECK_THAT(err, Catch::Contains("mirorr") && Catch::Contains("lambert"));
    bad("albedo.toml", walk_scene(11, "materials = [\"lambert(albedo=2)\"]"), 11,
        "walk.materials holds \"lambert(albedo=2)\": material 'lambert': albedo");
    bad("param.toml", walk_scene(11, "materials = [\"mirror(eta=1.5)\"]"), 11,
        "material 'mirror': unknown parameter 'eta'");
    // NDFs through the registry, checked before the first walk: the second family's refusal stops the run.
    err = bad("family.toml", walk_scene(19, "family = \"nosuch\""), 19,
              "walk.ndf.family names an unknown ndf family 'nosuch' (known: ");
    CHECK_THAT(err, Catch::Contains("ggx") && Catch::Contains("gtr"));
    // A parameter of another family: refused naming the family's own.
    bad("ggx_gamma.toml", walk_scene(17, "family = \"ggx\"\ngamma = [2.0]"), 18,
        "walk.ndf.gamma is not a parameter of 'ggx' (its parameters: alpha)");
    bad("blinn_alpha.toml", walk_scene(17, "family = \"blinn\"\nalpha = [0.3]"), 18,
        "walk.ndf.alpha is not a parameter of 'blinn' (its parameters: n)");
    bad("gamma.toml", walk_scene(20, "gamma = [-1.0]"), 19, "walk.ndf.family 'gtr' at gtr(alpha=0.2, gamma=-1): ");
    bad("alpha_range.toml", walk_scene(12, "alpha = [0.2, 1e-60]"), 17,
        "walk.ndf.family 'ggx' at ggx(alpha=1e-60): ggx: alpha must be in [1e-50, 1e50]");
    bad("blinn.toml", walk_scene(17, "family = \"blinn\"\nn = [-3]"), 17,
        "walk.ndf.family 'blinn' at blinn(n=-3): blinn: n must be");
    // The walks count in the work estimate: 16 cells of 1e9 walks are far above the default limit.
    err = check_bad_scene(d, "work.toml", walk_scene(14, "walks = 1000000000"), "walks 1.6e+10)");
    CHECK_THAT(err, Catch::Contains("above the limit of 1e+08 evaluations") && Catch::Contains("nothing was computed"));
    // Above alpha = 1 a walk counts alpha (its length grows like alpha): 8 cells of 2000 walks at alpha 1e5.
    check_bad_scene(d, "rough.toml", walk_scene(12, "alpha = [1e5]"), "walks 1.6e+09)");
}
