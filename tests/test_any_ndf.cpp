// Any registered NDF through every command, driven as a user would (cli_run.hpp): the ABC NDF (a built-in added as
// one file) through eval, check, sample, brdf, trace, report and fit; scene [[ndf]] tables sweeping any declared
// parameter, and their refusals; a measured NDF from a CSV file (tabulated) against the analytic NDF it samples, keyed
// by its contents, and its refusals.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <numbers>
#include <smithlab/smithlab.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

using namespace smithlab_test;
using Catch::Contains;

namespace {

fs::path fresh(const std::string& name) {
    const fs::path d = scratch() / ("any_ndf_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// "key value" lines of eval and brdf: the value of `key`.
double field(const std::string& out, const std::string& key, int column = 1) {
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string k;
        words >> k;
        if (k != key) continue;
        double v = NAN;
        for (int c = 0; c < column; ++c) words >> v;
        return v;
    }
    FAIL("no line '" << key << "' in:\n" << out);
    return NAN;
}

struct Albedo {
    double value, stderr_;
};

// albedo.csv of a trace: (ndf, material, hemisphere, order, component) -> albedo, its columns found by name (the
// ndf spec may be quoted and hold commas; a column per NDF parameter follows it).
std::map<std::string, Albedo> albedos(const fs::path& csv) {
    std::map<std::string, Albedo> out;
    std::ifstream in(csv);
    const std::vector<smithlab::CsvRecord> records = smithlab::read_csv(in);
    REQUIRE(!records.empty());
    const std::vector<std::string>& names = records[0].fields;
    auto column = [&](const std::string& name) {
        const auto at = std::find(names.begin(), names.end(), name);
        REQUIRE(at != names.end());
        return static_cast<std::size_t>(at - names.begin());
    };
    const std::size_t ndf = column("ndf"), material = column("material"), hemisphere = column("hemisphere"),
                      order = column("order"), component = column("component"), albedo = column("albedo"),
                      stderr_ = column("stderr");
    for (std::size_t i = 1; i < records.size(); ++i) {
        const std::vector<std::string>& f = records[i].fields;
        REQUIRE(f.size() == names.size());
        out[f[ndf] + "|" + f[material] + "|" + f[hemisphere] + "|" + f[order] + "|" + f[component]] = {
            std::stod(f[albedo]), std::stod(f[stderr_])};
    }
    return out;
}

// GGX of alpha as a table of n rows at jittered angles over [0, 89] degrees (what a measurement would give).
std::string ggx_table(double alpha, int n, double factor = 1.0) {
    std::string t = "# GGX sampled at jittered angles\ntheta_deg,D,noise\n";
    for (int i = 0; i < n; ++i) {
        const double deg = std::min(89.0, 89.0 * (i + 0.35 * std::sin(7.3 * i) * (i > 0 && i + 1 < n)) / (n - 1));
        char row[96];
        std::snprintf(row, sizeof row, "%.10g,%.17g,0\n", deg,
                      factor * smithlab::ggx(alpha).D(std::cos(deg * std::numbers::pi / 180.0)));
        t += row;
    }
    return t;
}

}  // namespace

TEST_CASE("abc, a built-in added as one file, goes through eval, check, sample and brdf", "[any_ndf]") {
    // eval: the default route against the nested 2D quadrature by GSL (another integral, another library).
    const Run e = run("eval --ndf 'abc(b=30, c=2)' --mu 0.4");
    REQUIRE(e.rc == 0);
    const Run e2 = run("eval --ndf 'abc(b=30, c=2)' --mu 0.4 --method quadrature2d --backend gsl --tolerance 1e-11");
    REQUIRE(e2.rc == 0);
    CHECK(std::abs(field(e.out, "lambda") / field(e2.out, "lambda") - 1.0) < 1e-9);
    // check: every identity at two points, the sharp peak included.
    const Run c = run("check --ndf 'abc(b=30, c=2)' --ndf 'abc(b=1e6, c=0.5)' --no-2d");
    INFO(c.out << c.err);
    CHECK(c.rc == 0);
    CHECK_THAT(c.out, Contains("0 failed"));
    // sample: visible normals, a row per sample.
    const Run s = run("sample --ndf 'abc(b=30, c=2)' --sampler vndf --theta-i 60 --n 200 --seed 3");
    REQUIRE(s.rc == 0);
    CHECK(std::count(s.out.begin(), s.out.end(), '\n') == 201);
    // brdf: the walk's first order against the single-scattering BRDF in closed form (Walter 2007 eq. 20), a route
    // of its own (no walk), within 5 standard errors.
    const Run b = run("brdf --ndf 'abc(b=30, c=2)' --material mirror --wi 30,0 --wo 40,180 --walks 200000 --threads 2");
    REQUIRE(b.rc == 0);
    const double order1 = field(b.out, "order_1"), se = field(b.out, "order_1", 2),
                 single = field(b.out, "single_analytic");
    INFO("order 1 " << order1 << " +- " << se << ", single scattering " << single);
    CHECK(std::abs(order1 - single) < 5.0 * se);
    // Bad values are refused by its registration, naming them.
    const Run bad = run("eval --ndf 'abc(b=-1, c=2)' --mu 1");
    CHECK(bad.rc == 2);
    CHECK_THAT(bad.err, Contains("abc: b must be in [1e-8, 1e16], got -1"));
}

TEST_CASE("abc through trace, report and fit, swept over alpha by its registered roughness", "[any_ndf]") {
    const fs::path d = fresh("abc");
    // trace: grid.alpha reaches abc through b = 2 / (c alpha^2); lambert(albedo=1) facets lose nothing, so every walk
    // that is not capped leaves with weight 1: the total albedo is 1 exactly.
    write(d / "trace.toml",
          "materials = [\"lambert(albedo=1)\"]\n[walks]\nn = 4000\n[grid]\nalpha = [0.5]\ntheta_i = [30]\n"
          "[[ndf]]\nfamily = \"abc\"\nc = [2, 8]\n");
    const Run t = run("trace " + q(d / "trace.toml") + " --output " + q(d / "trace") + " --threads 2");
    INFO(t.err);
    REQUIRE(t.rc == 0);
    const auto a = albedos(d / "trace" / "albedo.csv");
    CHECK(a.at("abc(b=4, c=2)|lambert(albedo=1)|all|all|all").value == 1.0);
    CHECK(a.at("abc(b=1, c=8)|lambert(albedo=1)|all|all|all").value == 1.0);
    // report: the table variant against the reference on abc's grid, and the walk section.
    write(d / "report.toml",
          "[grid]\nalpha = [0.3, 0.8]\nmu = [0.1, 1.0, 10.0]\n[[ndf]]\nfamily = \"abc\"\nc = [3]\n"
          "[variants]\ninclude = [\"table\"]\n[timing]\nmin_time = 0.001\n"
          "[walk]\nmaterials = [\"mirror\"]\nalpha = [0.5]\nwalks = 500\n[[walk.ndf]]\nfamily = \"abc\"\nc = [3]\n");
    const Run r = run("report " + q(d / "report.toml") + " --output " + q(d / "report"));
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const std::string variants = slurp(d / "report" / "variants.csv");
    CHECK_THAT(variants, Contains("table,6,"));
    CHECK_THAT(slurp(d / "report" / "walk_albedo.csv"), Contains("\"abc(b=2.6666666666666665, c=3)\",abc,,0.5,mirror"));
    // fit: one fit per c, and the constants' trend against c.
    write(d / "fit.toml",
          "material = \"lambert(albedo=1)\"\nalbedos = [0.5, 1.0]\nmodels = [\"lambert\", \"fujii\"]\n"
          "[[ndf]]\nfamily = \"abc\"\nc = [1.5, 3, 6]\n[training]\nalpha = [0.2, 0.8]\ntheta = [0.0, 40.0, 70.0]\n"
          "phi = [0.0, 180.0]\nwalks = 300\n[validation]\npoints = 4\nwalks = 300\nalbedo_theta = [0.0]\n"
          "albedo_walks = 300\n");
    const Run f = run("fit " + q(d / "fit.toml") + " --output " + q(d / "fit") + " --threads 2");
    INFO(f.err);
    REQUIRE(f.rc == 0);
    CHECK_THAT(slurp(d / "fit" / "constants.csv"), Contains("abc(c=1.5)") && Contains("abc(c=6)"));
    CHECK_THAT(slurp(d / "fit" / "abc_c_trends.csv"), Contains("fujii-fitted,sigma_scale,line"));
    CHECK_THAT(slurp(d / "fit" / "report.md"), Contains("## The fitted constants against abc's c"));
}

TEST_CASE("scene [[ndf]] tables sweep any declared parameter, and refuse one the family lacks", "[any_ndf][scenes]") {
    const fs::path d = fresh("sweep");
    const std::string head = "materials = [\"mirror\"]\n[walks]\nn = 200\n[grid]\ntheta_i = [45]\n";
    write(d / "ok.toml",
          head +
              "[[ndf]]\nfamily = \"blinn\"\nn = {log = [2, 200], n = 3}\n"
              "[[ndf]]\nfamily = \"student\"\nalpha = [0.1, 0.3]\ngamma = [2, 4]\n");
    const Run t = run("trace " + q(d / "ok.toml") + " --output " + q(d / "ok"));
    INFO(t.err);
    REQUIRE(t.rc == 0);
    // The cells in order: each entry's cross product, its first declared parameter outermost.
    std::vector<std::string> specs;
    for (const auto& [key, v] : albedos(d / "ok" / "albedo.csv")) specs.push_back(key.substr(0, key.find('|')));
    specs.erase(std::unique(specs.begin(), specs.end()), specs.end());
    CHECK(specs.size() == 7);
    const std::string cells = slurp(d / "ok" / "albedo.csv");
    const std::vector<std::string> order = {"blinn(n=2)",
                                            "blinn(n=20)",
                                            "blinn(n=200)",
                                            "student(alpha=0.1, gamma=2)",
                                            "student(alpha=0.1, gamma=4)",
                                            "student(alpha=0.3, gamma=2)",
                                            "student(alpha=0.3, gamma=4)"};
    std::size_t at = 0;
    for (const std::string& s : order) {
        const std::size_t found = cells.find(s, at);
        INFO(s);
        CHECK(found != std::string::npos);
        at = found;
    }
    auto refused = [&](const std::string& name, const std::string& body, const std::string& expected) {
        write(d / name, head + body);
        const Run r = run("trace " + q(d / name) + " --output " + q(d / "never"));
        INFO(name << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Contains(expected));
        CHECK_FALSE(fs::exists(d / "never"));
    };
    refused("gamma.toml", "[[ndf]]\nfamily = \"ggx\"\nalpha = [0.3]\ngamma = [2]\n",
            "gamma.toml:9: ndf.gamma is not a parameter of 'ggx' (its parameters: alpha)");
    refused("domain.toml", "[[ndf]]\nfamily = \"student\"\nalpha = [0.3]\ngamma = [1]\n",
            "domain.toml:7: ndf.family 'student' at student(alpha=0.3, gamma=1): student: gamma must be");
    refused("no_alpha.toml", "[[ndf]]\nfamily = \"ggx\"\n", "ndf.family is swept over grid.alpha, which is missing");
    refused("unknown.toml", "[[ndf]]\nfamily = \"ggx\"\nbeta = [1]\n", "unknown key 'ndf.beta'");
    // The fitter sweeps alpha itself: an entry that gives it is refused.
    write(d / "fit.toml",
          "[[ndf]]\nfamily = \"ggx\"\nalpha = [0.3]\n[training]\nalpha = [0.2]\ntheta = [0.0]\nphi = [0.0]\n");
    const Run f = run("fit " + q(d / "fit.toml") + " --output " + q(d / "never"));
    CHECK(f.rc == 2);
    CHECK_THAT(f.err,
               Contains("fit.toml:2: ndf.family 'ggx' is given its roughness here: the fit sweeps alpha over "
                        "training.alpha"));
}

TEST_CASE("tabulated: a GGX table through eval, check and trace, keyed by its contents", "[any_ndf][tabulated]") {
    const fs::path d = fresh("tabulated");
    fs::create_directories(d / "a dir, with (parens)");
    const fs::path file = d / "a dir, with (parens)" / "ggx.csv";
    write(file, ggx_table(0.5, 150));
    const std::string spec = "'tabulated(file=\"" + file.string() + "\")'";
    // eval: Lambda against GGX's closed form (the table's interpolation error: a few 1e-6 on 150 rows to 89 degrees).
    for (double mu : {0.2, 1.0, 5.0}) {
        const Run e = run("eval --ndf " + spec + " --mu " + std::to_string(mu));
        INFO(e.err);
        REQUIRE(e.rc == 0);
        CHECK(std::abs(field(e.out, "lambda") / smithlab::ggx(0.5).Lambda(mu) - 1.0) < 2e-5);
    }
    // The NDF names its quadrature (GSL): no --backend needed. The nested 2D route misses 1D by 1.9e-8 at mu = 0.1 on
    // the kinks of the C1 interpolant (the checks ask 1e-8): left out.
    const Run c = run("check --ndf " + spec + " --no-2d");
    INFO(c.out << c.err);
    CHECK(c.rc == 0);
    // trace: the table's albedo by order against GGX's own, within 5 combined standard errors.
    const Run t =
        run("trace --ndf " + spec + " --material mirror --theta-i 60 --walks 100000 --output " + q(d / "tab"));
    const Run g = run("trace --ndf 'ggx(alpha=0.5)' --material mirror --theta-i 60 --walks 100000 --seed 2 --output " +
                      q(d / "ggx"));
    REQUIRE(t.rc == 0);
    REQUIRE(g.rc == 0);
    const auto at = albedos(d / "tab" / "albedo.csv"), ag = albedos(d / "ggx" / "albedo.csv");
    const std::string tab_spec = "tabulated(file=\"" + file.string() + "\")";
    for (const std::string order : {"1", "2", "3", "4+"}) {
        const Albedo x = at.at(tab_spec + "|mirror|reflection|" + order + "|all"),
                     y = ag.at("ggx(alpha=0.5)|mirror|reflection|" + order + "|all");
        INFO("order " << order << ": table " << x.value << " +- " << x.stderr_ << ", ggx " << y.value << " +- "
                      << y.stderr_);
        CHECK(std::abs(x.value - y.value) < 5.0 * std::hypot(x.stderr_, y.stderr_));
    }
    // Its contents key the cells: moved, it is reused; one digit edited, it is traced again.
    const fs::path moved = d / "moved.csv";
    fs::copy_file(file, moved);
    const Run reuse = run("trace --ndf 'tabulated(file=" + moved.string() +
                          ")' --material mirror --theta-i 60 --walks 100000 --output " + q(d / "tab"));
    INFO(reuse.err);
    REQUIRE(reuse.rc == 0);
    CHECK_THAT(reuse.out, Contains("traced 0") && Contains("reused 1"));
    std::string text = slurp(moved);
    text.replace(text.find(",0\n", text.size() / 2) - 3, 1,
                 text[text.find(",0\n", text.size() / 2) - 3] == '1' ? "2" : "1");
    write(moved, text);
    const Run edited = run("trace --ndf 'tabulated(file=" + moved.string() +
                           ")' --material mirror --theta-i 60 --walks 100000 --output " + q(d / "tab"));
    INFO(edited.err);
    REQUIRE(edited.rc == 0);
    CHECK_THAT(edited.out, Contains("traced 1") && Contains("reused 0"));
    // Swept over alpha (its scale set so that its core slope scale is alpha), in a trace and in a fit.
    write(d / "sweep.toml",
          "materials = [\"mirror\"]\n[walks]\nn = 2000\n[grid]\nalpha = [0.25, 0.5]\ntheta_i = [30]\n"
          "[[ndf]]\nfamily = \"tabulated\"\nfile = \"" +
              file.string() + "\"\n");
    const Run sweep = run("trace " + q(d / "sweep.toml") + " --output " + q(d / "sweep"));
    INFO(sweep.err);
    REQUIRE(sweep.rc == 0);
    CHECK_THAT(slurp(d / "sweep" / "albedo.csv"),
               Contains("tabulated(scale=0.4999999") && Contains("tabulated(scale=0.9999999"));
    write(d / "fit.toml",
          "material = \"lambert(albedo=1)\"\nalbedos = [1.0]\nmodels = [\"fujii\"]\n[[ndf]]\n"
          "family = \"tabulated\"\nfile = \"" +
              file.string() +
              "\"\n[training]\nalpha = [0.3, 0.6]\n"
              "theta = [0.0, 60.0]\nphi = [0.0]\nwalks = 200\n[validation]\npoints = 2\nwalks = 200\n"
              "albedo_theta = [0.0]\nalbedo_walks = 200\n");
    const Run fit = run("fit " + q(d / "fit.toml") + " --output " + q(d / "fit"));
    INFO(fit.err);
    CHECK(fit.rc == 0);
    CHECK_THAT(slurp(d / "fit" / "constants.csv"), Contains("fujii-fitted,\"tabulated(file="));
}

TEST_CASE("tabulated: a bad file is refused naming it, its line and the value, before anything is written",
          "[any_ndf][tabulated]") {
    const fs::path d = fresh("tabulated_bad");
    auto refused = [&](const std::string& name, const std::string& csv, const std::string& expected) {
        write(d / name, csv);
        const Run r =
            run("trace --ndf 'tabulated(file=" + (d / name).string() + ")' --walks 100 --output " + q(d / "never"));
        INFO(name << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Contains((d / name).string()) && Contains(expected));
        CHECK_FALSE(fs::exists(d / "never"));
    };
    refused("negative.csv", "theta_deg,D\n0,1\n30,-0.3\n60,0.1\n", ":3: D must be finite and >= 0, got -0.3");
    refused("nan.csv", "theta_deg,D\n0,1\n30,nan\n60,0.1\n", ":3: D must be finite and >= 0, got nan");
    refused("order.csv", "theta_deg,D\n0,1\n30,0.5\n20,0.1\n", ":4:");
    refused("few.csv", "theta_deg,D\n0,1\n30,0.5\n", "3");
    refused("area.csv", ggx_table(0.5, 40, 3.0), ": the projected area of D");
    // With normalize=1 the same table is accepted, and the factor is said.
    const Run normalized = run("eval --ndf 'tabulated(file=" + (d / "area.csv").string() + ", normalize=1)' --mu 1");
    CHECK(normalized.rc == 0);
    CHECK_THAT(normalized.err, Contains("D multiplied by 0.33"));
    const Run missing = run("eval --ndf 'tabulated(file=" + (d / "nosuch.csv").string() + ")' --mu 1");
    CHECK(missing.rc == 2);
    CHECK_THAT(missing.err, Contains("nosuch.csv"));
}
