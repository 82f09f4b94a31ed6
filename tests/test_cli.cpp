// The smithlab executable, driven as a user would: good runs, bad input (exit 2, the offending item named,
// no output file), the CSV contract.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <smithlab/csv.hpp>
#include <smithlab/material_registry.hpp>
#include <sstream>
#include <string>
#include <vector>
#include "cli_run.hpp"

using namespace smithlab_test;

namespace {

// The largest value of the last column of a CSV file with a header.
double max_of_last_column(std::istream& in) {
    std::string line;
    std::getline(in, line);
    double worst = -1.0;
    while (std::getline(in, line)) worst = std::max(worst, std::stod(line.substr(line.rfind(',') + 1)));
    return worst;
}

}  // namespace

TEST_CASE("eval prints lambda and g1", "[cli]") {
    const Run r = run("eval --ndf 'ggx(alpha=0.5)' --mu 1");
    REQUIRE(r.rc == 0);
    // GGX: Lambda = (sqrt(1 + alpha^2/mu^2) - 1)/2 = 0.0590169943749474...
    CHECK_THAT(r.out, Catch::Contains("lambda  0.05901699437494") && Catch::Contains("g1"));
    CHECK(run("eval --ndf 'blinn(n=20)' --mu 0.5 --method quadrature2d --backend gsl").rc == 0);
    CHECK(run("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 0.5 --method spline").rc == 0);
    // A variant by name: Hammon's approximation for GGX is alpha times the gamma = 0 Lambda: 0.3/(2 (1 + sqrt 2)).
    CHECK_THAT(run("eval --ndf 'ggx(alpha=0.3)' --mu 1 --method schlick-ggx").out,
               Catch::Contains("lambda  0.0621320343559642"));
    CHECK(run("eval --ndf 'gtr(alpha=0.3, gamma=1)' --mu inf").out.find("g1      1\n") != std::string::npos);
    // Below the surface: Smith's Lambda(-mu) = -1 - Lambda(mu), G1 of |mu|; GGX Lambda(0.5) at alpha = 0.5 is
    // (sqrt(2) - 1)/2 = 0.20710678118654752.
    const Run down = run("eval --ndf 'ggx(alpha=0.5)' --mu -0.5");
    CHECK_THAT(down.out, Catch::Contains("lambda  -1.207106781186547") && Catch::Contains("g1      0.828427124746190"));
    CHECK_THAT(run("eval --ndf 'ggx(alpha=0.5)' --mu -0.5 --downward hammon").out,
               Catch::Contains("lambda  -0.207106781186547"));
    // A subnormal mu is a number (it was refused as "not a number"): GGX's Lambda ~ alpha / (2 mu) there, 2.5e309
    // overflows to inf and G1 underflows to 0 exactly as the closed form says.
    const Run tiny = run("eval --ndf 'ggx(alpha=0.5)' --mu 1e-310");
    CHECK(tiny.rc == 0);
    CHECK_THAT(tiny.out, Catch::Contains("g1      "));
    CHECK_THAT(run("eval --ndf 'ggx(alpha=1e-10)' --mu 1e-310").out,
               Catch::Contains("lambda  5.00000000000001") && Catch::Contains("e+299"));
}

TEST_CASE("bad input exits 2 and names the offending item", "[cli]") {
    struct Case {
        const char* args;
        const char* named;
    };
    for (const Case& c :
         {Case{"eval --ndf 'ggx(alpha=-1)' --mu 1", "alpha"}, Case{"eval --ndf 'ggx(alpha=nan)' --mu 1", "alpha"},
          Case{"eval --ndf 'gtr(alpha=0.3, gamma=-1)' --mu 1", "gamma"},
          Case{"eval --ndf 'phong(n=2)' --mu 1", "phong"}, Case{"eval --ndf 'ggx(alpha=0.3)' --mu nan", "mu"},
          Case{"eval --ndf 'ggx(alpha=0.3)' --mu abc", "mu"},
          Case{"eval --ndf 'ggx(alpha=0.3)' --mu 1e-400", "smallest double"},
          Case{"eval --ndf 'ggx(alpha=0.3)' --mu 1e400", "largest double"},
          Case{"eval --ndf 'ggx(alpha=1e999)' --mu 1", "largest double"},
          Case{"eval --ndf 'blinn(n=4)' --mu 1 --method closed", "closed"},
          Case{"eval --ndf 'ggx(alpha=0.3)' --mu 1 --method magic", "magic"},
          Case{"eval --ndf 'ggx(alpha=0.3)' --mu 1 --method dimov-spline", "dimov-spline"},
          Case{"eval --input /nonexistent/points.csv", "/nonexistent/points.csv"},
          Case{"check --ndf 'gtr(alpha=0, gamma=2)'", "alpha"}}) {
        const Run r = run(c.args);
        INFO(c.args << "\nstderr: " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains(c.named));
        CHECK_THAT(r.out, !Catch::Contains("nan"));
    }
}

TEST_CASE("CSV: columns pass through, one per NDF parameter follows, lambda and g1 appended with 17 digits",
          "[cli][csv]") {
    const fs::path d = scratch();
    write(d / "in.csv", "id,ndf,mu\nA,\"ggx(alpha=0.5)\",1\nB,\"gtr(alpha=0.3, gamma=1.5)\",0.25\n");
    const Run r = run("eval --input '" + (d / "in.csv").string() + "' -o '" + (d / "res.csv").string() + "'");
    REQUIRE(r.rc == 0);
    const std::string res = slurp(d / "res.csv");
    // GGX has no gamma: its cell is empty.
    CHECK_THAT(res, Catch::StartsWith("id,ndf,mu,alpha,gamma,lambda,g1\nA,ggx(alpha=0.5),1,0.5,,0.059016994374947"));
    CHECK_THAT(res, Catch::Contains("B,\"gtr(alpha=0.3, gamma=1.5)\",0.25,0.3,1.5,"));
    // 17 significant digits: the lambda of row A is "0.0" and 17 digits.
    const std::string a_row = "A,ggx(alpha=0.5),1,0.5,,";
    const auto a = res.find(a_row) + a_row.size();
    CHECK(res.substr(a, res.find(',', a) - a).size() == 20);
    // A parameter the input has already is not repeated.
    write(d / "alpha.csv", "alpha,ndf,mu\n0.5,\"ggx(alpha=0.5)\",1\n");
    CHECK_THAT(run("eval --input '" + (d / "alpha.csv").string() + "'").out,
               Catch::StartsWith("alpha,ndf,mu,lambda,g1\n0.5,ggx(alpha=0.5),1,0.059016994374947"));
}

TEST_CASE("sample: CSV of unit normals and their pdfs, reproducible by seed, bad input exits 2 with no file",
          "[cli][sample]") {
    const fs::path d = scratch();
    const std::string args =
        "sample --ndf 'gtr(alpha=0.2, gamma=1.5)' --sampler vndf --theta-i 70 --n 500 --seed 9 --output '";
    REQUIRE(run(args + (d / "a.csv").string() + "'").rc == 0);
    REQUIRE(run(args + (d / "b.csv").string() + "'").rc == 0);
    const std::string a = slurp(d / "a.csv");
    CHECK(a == slurp(d / "b.csv"));
    std::istringstream rows(a);
    std::string line;
    std::getline(rows, line);
    CHECK(line == "x,y,z,pdf");
    int n = 0;
    while (std::getline(rows, line)) {
        double x, y, z, pdf;
        char c1, c2, c3;
        std::istringstream(line) >> x >> c1 >> y >> c2 >> z >> c3 >> pdf;
        CHECK(std::abs(x * x + y * y + z * z - 1.0) < 1e-14);
        CHECK(pdf > 0.0);
        // visible normals face wi = (sin 70, 0, cos 70)
        CHECK(x * std::sin(70 * M_PI / 180) + z * std::cos(70 * M_PI / 180) > 0.0);
        ++n;
    }
    CHECK(n == 500);
    CHECK_THAT(run("sample --list-samplers").out, Catch::Contains("vndf-ggx") && Catch::Contains("hammon"));
    // Visible normals of a direction below the horizon are drawn; --theta-i stays in [0, 180).
    const Run below = run("sample --ndf 'ggx(alpha=0.3)' --sampler vndf --theta-i 135 --n 3 --seed 1");
    CHECK(below.rc == 0);
    CHECK(std::count(below.out.begin(), below.out.end(), '\n') == 4);
    for (const char* bad : {"--sampler nope", "--sampler vndf --theta-i 180", "--sampler vndf --theta-i nan",
                            "--sampler vndf --n 0", "--sampler vndf-beckmann --theta-i 10"}) {
        const Run r =
            run(std::string("sample --ndf 'ggx(alpha=0.3)' ") + bad + " --output '" + (d / "never.csv").string() + "'");
        INFO(bad << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK_FALSE(fs::exists(d / "never.csv"));
    }
    CHECK_THAT(run("sample --ndf 'ggx(alpha=0.3)' --sampler nope --n 1").err, Catch::Contains("nope"));
    CHECK_THAT(run("sample --ndf 'ggx(alpha=0.3)' --sampler vndf --theta-i nan").err, Catch::Contains("--theta-i"));
}

TEST_CASE("CSV with --method table: one table per spec, within 1e-6 of the closed form", "[cli][csv]") {
    const fs::path d = scratch();
    // GGX at alpha = 0.5: Lambda = (sqrt(1 + 0.25/mu^2) - 1)/2; mu = 1.3: 0.035707241430158465, mu = 0.1:
    // 2.0495097567963922 (mu = 1 would be a knot, where the spline is exact).
    write(d / "t.csv", "ndf,mu\n\"ggx(alpha=0.5)\",1.3\n\"ggx(alpha=0.5)\",0.1\n\"ggx(alpha=0.5)\",-1.3\n");
    const Run r = run("eval --method table --input '" + (d / "t.csv").string() + "'");
    REQUIRE(r.rc == 0);
    std::istringstream rows(r.out);
    std::string line;
    std::getline(rows, line);
    REQUIRE(line == "ndf,mu,alpha,lambda,g1");
    for (double want : {0.035707241430158465, 2.0495097567963922, -1.0357072414301585}) {
        REQUIRE(std::getline(rows, line));
        const std::string lambda_g1 = line.substr(line.find(",0.5,") + 5);
        const double got = std::stod(lambda_g1.substr(0, lambda_g1.find(',')));
        INFO(line);
        CHECK(std::abs(got - want) <= 1e-6 * std::abs(want));
        CHECK(got != want);  // interpolated, not the closed form
    }
}

TEST_CASE("CSV: every bad row is reported by line, and no output file is written", "[cli][csv]") {
    const fs::path d = scratch();
    fs::remove(d / "never.csv");
    write(d / "bad.csv",
          "ndf,mu\n"
          "\"ggx(alpha=0.5)\",1\n"
          "\"ggx(alpha=0.5)\",1,extra\n"
          "\"nope(alpha=1)\",1\n"
          "\"gtr(alpha=0.3, gamma=2)\",nan\n"
          "\"ggx(alpha=-2)\",1\n"
          "ggx(alpha=0.1,2\n");
    const Run r = run("eval --input '" + (d / "bad.csv").string() + "' --output '" + (d / "never.csv").string() + "'");
    INFO(r.err);
    CHECK(r.rc == 2);
    for (const char* where : {"bad.csv:3:", "bad.csv:4:", "bad.csv:5:", "bad.csv:6:", "bad.csv:7:"})
        CHECK_THAT(r.err, Catch::Contains(where));
    CHECK_THAT(r.err, !Catch::Contains("bad.csv:2:"));
    CHECK_FALSE(fs::exists(d / "never.csv"));
    CHECK_FALSE(fs::exists(d / "never.csv.partial"));

    write(d / "closed.csv", "ndf,mu\n\"blinn(n=10)\",1\n");
    const Run c = run("eval --method closed --input '" + (d / "closed.csv").string() + "'");
    CHECK(c.rc == 2);
    CHECK_THAT(c.err, Catch::Contains("closed.csv:2:") && Catch::Contains("blinn"));
    CHECK(c.out.empty());

    write(d / "nohead.csv", "spec,mu\nggx,1\n");
    CHECK(run("eval --input '" + (d / "nohead.csv").string() + "'").rc == 2);
}

TEST_CASE("every registered material is listed where a user looks: list, trace --help, the default trace scene",
          "[cli]") {
    const Run list = run("list"), help = run("trace --help"), scene = run("trace --print-scene");
    REQUIRE(list.rc == 0);
    REQUIRE(help.rc == 0);
    REQUIRE(scene.rc == 0);
    const smithlab::MaterialRegistry materials;
    for (const smithlab::walk::MaterialInfo* m : materials.list()) {
        INFO(m->spec());
        CHECK_THAT(list.out, Catch::Contains(m->spec() + "\n    " + m->description));
        CHECK_THAT(help.out, Catch::Contains(m->spec()));
        CHECK_THAT(scene.out, Catch::Contains(m->parameters.empty() ? m->name : m->name + "("));
    }
}

TEST_CASE("check prints a table and passes for a healthy NDF, and --help explains", "[cli]") {
    const Run r = run("check --ndf 'gtr(alpha=0.2, gamma=2.5)' --no-2d");
    INFO(r.out << r.err);
    CHECK(r.rc == 0);
    CHECK_THAT(r.out, Catch::Contains("integral D cos dm = 1") && Catch::Contains("0 failed"));
    const Run h = run("--help");
    CHECK(h.rc == 0);
    CHECK_THAT(h.out, Catch::Contains("eval") && Catch::Contains("check"));
    CHECK_THAT(run("eval --help").out, Catch::Contains("--method"));
    const Run m = run("eval --list-methods");
    CHECK(m.rc == 0);
    CHECK_THAT(m.out,
               Catch::Contains("dimov-spline") && Catch::Contains("schlick-ggx") && Catch::Contains("q1d-gsl-1e-8"));
}

TEST_CASE("report: a scene computes what it names, caches its references, and rejects a malformed scene",
          "[cli][report]") {
    const fs::path d = scratch();
    fs::remove_all(d / "rep");
    write(d / "small.toml",
          "title = \"small\"\n"
          "[grid]\nalpha = [0.1, 0.5]\nmu = { log = [0.01, 100.0], n = 3 }\n"
          "[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5, 3.0]\n"
          "[variants]\ninclude = [\"dimov-spline\", \"schlick-ggx\"]\n"
          "[g2]\ninclude = [\"g2-hammon-lerp\"]\nmu = [0.5, 2.0]\n"
          "[timing]\nmin_time = 0.01\n");
    const std::string args = report_args(d, "small.toml", "rep");
    const Run r = run(args);
    INFO(r.err);
    REQUIRE(r.rc == 0);
    const std::string csv = slurp(d / "rep" / "variants.csv");
    // dimov-spline on 2 alpha x 2 gamma x 3 mu; schlick-ggx applies to no NDF of this scene (GGX-like only): 0 points.
    CHECK_THAT(csv, Catch::Contains("dimov-spline,12,") && Catch::Contains("schlick-ggx,0,"));
    CHECK_THAT(slurp(d / "rep" / "report.md"), Catch::Contains("| dimov-spline | 12 |"));
    CHECK(fs::exists(d / "rep" / "bench.json"));
    CHECK_FALSE(fs::exists(d / "rep" / "sampling.csv"));  // not named, not computed
    // G2: Hammon's lerp on ggx at 2 alpha x 2 mu x 2 mu.
    CHECK_THAT(slurp(d / "rep" / "g2_variants.csv"), Catch::Contains("g2-hammon-lerp,8,"));
    // References only for what was asked: 12 for dimov-spline (the gamma = 3 points by the closed form, gamma = 1.5
    // by quadrature), 4 GGX Lambdas for the G2 table (2 alpha x 2 mu).
    const std::string cache = slurp(d / "rep" / "cache" / "references.csv");
    CHECK(std::count(cache.begin(), cache.end(), '\n') == 17);
    CHECK_THAT(r.err, Catch::Contains("0 reused from the cache, 16 computed"));
    CHECK_THAT(run(args).err, Catch::Contains("16 reused from the cache, 0 computed"));

    CHECK_THAT(check_bad_scene(d, "bad.toml", "[grid]\nalpha = [0.1]\nmu = \"many\"\n", "grid.mu"),
               Catch::Contains("bad.toml"));
    check_bad_scene(d, "g2gtr.toml",
                    "[grid]\nalpha = [0.1]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"*\"]\n"
                    "[g2]\ninclude = [\"*\"]\nfamilies = [\"gtr\"]\nmu = [1.0]\n",
                    "gamma");
    check_bad_scene(
        d, "none.toml",
        "[grid]\nalpha = [0.1]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"nothing*\"]\n",
        "pattern 'nothing*' matches no name");
}

TEST_CASE("report: the sampling experiment, the blog's point measured", "[cli][report][sampling]") {
    const fs::path d = scratch();
    fs::remove_all(d / "smp");
    const Run r = run_scene(
        d, "smp.toml",
        "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"schlick-ggx\"]\n"
        "[timing]\nmin_time = 0.01\n"
        "[sampling]\nfamilies = [\"ggx\", \"beckmann\"]\nalpha = [0.01, 0.5]\ntheta_o = 30\nsamples = 40000\nseed = "
        "3\n",
        "smp");
    INFO(r.err);
    REQUIRE(r.rc == 0);
    CHECK(fs::exists(d / "smp" / "sampling_efficiency.png"));
    CHECK_THAT(slurp(d / "smp" / "report.md"),
               Catch::Contains("Sampling efficiency") && Catch::Contains("| ggx(0.01) | vndf |"));
    // Per (family, alpha): the three strategies estimate the same albedo (within 5 standard errors), and at
    // alpha = 0.01 the variance falls from cosine to D cos to visible normals.
    std::istringstream rows(slurp(d / "smp" / "sampling.csv"));
    std::string line;
    std::getline(rows, line);
    std::map<std::string, std::map<std::string, std::pair<double, double>>> est;  // ndf -> strategy -> (mean, stderr)
    std::map<std::string, std::map<std::string, double>> var;
    int n = 0;
    while (std::getline(rows, line)) {
        std::vector<std::string> f;
        std::istringstream fields(line);
        for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
        REQUIRE(f.size() == 9);
        const std::string key = f[0] + "(" + f[1] + ")";
        est[key][f[2]] = {std::stod(f[4]), std::stod(f[5])};
        var[key][f[2]] = std::stod(f[6]);
        CHECK(std::stod(f[7]) > 0.0);  // ns per sample, from Google Benchmark
        ++n;
    }
    CHECK(n == 12);
    for (const auto& [key, by] : est)
        for (const auto& [a, ea] : by)
            for (const auto& [b, eb] : by) {
                INFO(key << ": " << a << " " << ea.first << " +- " << ea.second << " vs " << b << " " << eb.first
                         << " +- " << eb.second);
                CHECK(std::abs(ea.first - eb.first) <= 5.0 * std::hypot(ea.second, eb.second) + 1e-12);
            }
    for (const char* key : {"ggx(0.01)", "beckmann(0.01)"}) {
        INFO(key);
        CHECK(var[key]["cosine"] > 100.0 * var[key]["dcos"]);
        CHECK(var[key]["dcos"] > var[key]["vndf"]);
    }
    check_bad_scene(d, "bad_smp.toml",
                    "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"*\"]\n"
                    "[sampling]\nfamilies = [\"blinn\"]\nalpha = [0.1]\n",
                    "sampling.families");
}

TEST_CASE("report: Dimov 2015's figures reproduce, and are drawn", "[cli][report]") {
    const fs::path d = scratch();
    fs::remove_all(d / "dimov");
    const Run r = run_scene(
        d, "dimov.toml",
        "[grid]\nalpha = [0.3]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"schlick-ggx\"]\n"
        "[timing]\nmin_time = 0.01\n[figures]\ndimov_gamma4_vs_10 = true\ndimov_spline_mean = true\n",
        "dimov");
    INFO(r.err);
    REQUIRE(r.rc == 0);
    // Sec. 6: "up to 0.3" for |G1(gamma = 4) - G1(gamma = 10)| over alpha in (0, 1), mu in (0, 2).
    std::ifstream in(d / "dimov" / "dimov" / "gamma4_vs_10.csv");
    const double worst = max_of_last_column(in);
    CHECK(worst > 0.25);
    CHECK(worst < 0.32);
    // Sec. 5: the spline's mean difference, published as about 0.001: same order measured.
    const std::string md = slurp(d / "dimov" / "report.md");
    const auto at = md.find("mean |dG1| = ");
    REQUIRE(at != std::string::npos);
    const double mean = std::stod(md.substr(at + 13));
    CHECK(mean > 1e-4);
    CHECK(mean < 3e-3);
    CHECK(fs::exists(d / "dimov" / "gamma4_vs_10.png"));  // .ci/deps installs python3-matplotlib
    CHECK_FALSE(fs::exists(d / "dimov" / "pareto.png"));  // not asked for, not drawn
}

TEST_CASE(
    "trace: albedo.csv and meta.json, the same bits for any --threads, and bad input exits 2 with nothing written",
    "[cli][walk]") {
    const fs::path d = scratch();
    const std::string cell =
        "--ndf 'gtr(alpha=0.4, gamma=1.5)' --material 'lambert(albedo=0.8)' --theta-i 60 --walks 20000";
    std::string first;
    for (int threads : {1, 2, 3}) {
        const fs::path out = d / ("trace" + std::to_string(threads));
        const Run r =
            run("trace " + cell + " --threads " + std::to_string(threads) + " --output '" + out.string() + "'");
        REQUIRE(r.rc == 0);
        const std::string csv = slurp(out / "albedo.csv");
        CHECK(csv.rfind("ndf,alpha,gamma,material,theta_i,phi_i,hemisphere,order,component,albedo,stderr,walks\n", 0) ==
              0);
        CHECK(csv.find("\"gtr(alpha=0.4, gamma=1.5)\",0.4,1.5,lambert(albedo=0.8),60,0,all,all,all,") !=
              std::string::npos);
        CHECK(slurp(out / "meta.json").find("\"walks\": 20000") != std::string::npos);
        if (first.empty()) first = csv;
        CHECK(csv == first);
    }
    for (const std::string bad : {"--material velvet", "--material 'lambert(albedo=2)'", "--walks 0", "--theta-i 90",
                                  "--ndf 'ggx(alpha=-1)'", "--seed -1", "--downward up"}) {
        const fs::path out = d / "refused";
        const Run r = run("trace " + bad + " --output '" + out.string() + "'");
        INFO(bad << ": " << r.err);
        CHECK(r.rc == 2);
        CHECK(r.err.find("error") != std::string::npos);
        CHECK(!fs::exists(out));
    }
}

TEST_CASE("brdf: the eval estimator's value, its orders and the analytic single scattering", "[cli][walk]") {
    const Run r = run("brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 60,180 --walks 100000 --seed 3");
    REQUIRE(r.rc == 0);
    double order1 = 0, err1 = 0, single = 0;
    std::istringstream in(r.out);
    for (std::string key; in >> key;) {
        if (key == "order_1") in >> order1 >> err1;
        else if (key == "single_analytic") in >> single;
        else in.ignore(1000, '\n');
    }
    REQUIRE(single > 0.0);
    CHECK(std::abs(order1 - single) < 4.0 * err1);
    CHECK(run("brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 120,0 --wo 60,180").rc == 2);
    // Light from below is for the dielectric only: f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2 across the surface.
    const Run below =
        run("brdf --ndf 'ggx(alpha=0.5)' --material 'dielectric(eta=1.5)' --wi 150,180 --wo 40,0 --walks 20000");
    REQUIRE(below.rc == 0);
    CHECK_THAT(below.out, Catch::Contains("value ") && !Catch::Contains("single_analytic"));
    CHECK_THAT(
        run("brdf --ndf 'ggx(alpha=0.5)' --material 'dielectric(eta=1.5)' --wi 40,0 --wo 150,180 --walks 20000").out,
        Catch::Contains("single_analytic "));
    CHECK(run("brdf --ndf 'ggx(alpha=0.5)' --material 'dielectric(eta=1.5)' --wi 90,0 --wo 150,180").rc == 2);
}

TEST_CASE("brdf --estimator: every estimator agrees with the default within its errors", "[cli][walk]") {
    // value and stderr of one run, from its first two lines.
    const auto value = [](const std::string& estimator) {
        const Run r =
            run("brdf --ndf 'gtr(alpha=0.6, gamma=1.5)' --material 'lambert(albedo=0.9)' --wi 30,0 --wo 70,120 "
                "--walks 40000 --seed 5 --estimator " +
                estimator);
        INFO(estimator << ": " << r.err);
        REQUIRE(r.rc == 0);
        std::istringstream in(r.out);
        std::string key;
        double v = 0.0, e = 0.0;
        in >> key >> v >> key >> e;
        return std::pair{v, e};
    };
    const auto [v0, e0] = value("next_event");
    for (const char* e : {"expected_first", "reciprocal", "position_free"}) {
        const auto [v, err] = value(e);
        INFO(e << ": " << v << " +- " << err << " against next_event " << v0 << " +- " << e0);
        CHECK(std::abs(v - v0) < 4.5 * std::hypot(err, e0));
    }
    const Run bad = run("brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 45,180 --estimator nope");
    CHECK(bad.rc == 2);
    CHECK_THAT(bad.err, Catch::Contains("--estimator") && Catch::Contains("position_free"));
}

namespace {

// Each record of a CSV file (header first), through smithlab's reader.
std::vector<std::vector<std::string>> records(const fs::path& p) {
    std::ifstream in(p);
    std::vector<std::vector<std::string>> out;
    for (smithlab::CsvRecord& r : smithlab::read_csv(in)) out.push_back(std::move(r.fields));
    return out;
}

// The records after the header, each as its fields by column name (trace's tables have a column per NDF parameter
// after the ndf column: the others' places depend on the scene's NDFs).
std::vector<std::map<std::string, std::string>> by_name(const std::vector<std::vector<std::string>>& records) {
    std::vector<std::map<std::string, std::string>> out;
    for (std::size_t i = 1; i < records.size(); ++i) {
        std::map<std::string, std::string>& row = out.emplace_back();
        for (std::size_t k = 0; k < records[0].size() && k < records[i].size(); ++k) row[records[0][k]] = records[i][k];
    }
    return out;
}

const char* trace_scene_text = R"toml(title = "a small sweep"
materials = ["mirror", "lambert(albedo=0.7)"]
[walks]
n = 3000
seed = 5
[grid]
alpha = [0.3]
theta_i = [30, 70]
[[ndf]]
family = "gtr"
gamma = [1.5]
[[ndf]]
spec = "beckmann(alpha=0.5)"
[brdf]
theta_bins = 4
phi_bins = 6
)toml";

std::string trace_args(const fs::path& scene, const fs::path& out, int threads) {
    return "trace '" + scene.string() + "' --output '" + out.string() + "' --threads " + std::to_string(threads);
}

}  // namespace

TEST_CASE(
    "trace: a scene file -- albedo.csv and brdf.csv for every cell, the same bits for any --threads, a rerun "
    "traces nothing, brdf.csv holds the reflected energy",
    "[cli][walk][scene]") {
    const fs::path d = scratch() / "trace_scene";
    fs::remove_all(d);
    fs::create_directories(d);
    write(d / "scene.toml", trace_scene_text);
    Run r = run(trace_args(d / "scene.toml", d / "a", 1));
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.out, Catch::Contains("cells 8\ntraced 8\nreused 0\n"));
    const auto albedo = records(d / "a" / "albedo.csv"), brdf = records(d / "a" / "brdf.csv");
    REQUIRE(albedo.size() == 1 + 8 * 45);  // 2 NDFs x 2 materials x 2 angles; 3 hemispheres x 5 orders x 3 components
    REQUIRE(brdf.size() == 1 + 8 * 4 * 6 * 5 * 3);
    CHECK(albedo[1][0] == "gtr(alpha=0.3, gamma=1.5)");
    CHECK(albedo.back()[0] == "beckmann(alpha=0.5)");
    // Every walk's weight lands in one bin: the bins' value x solid angle sum to the cell's reflection albedo.
    std::map<std::string, double> reflected, binned;
    for (const auto& f : by_name(albedo))
        if (f.at("hemisphere") == "reflection" && f.at("order") == "all" && f.at("component") == "all")
            reflected[f.at("ndf") + f.at("material") + f.at("theta_i")] = std::stod(f.at("albedo"));
    const double omega = 2.0 * M_PI / (4 * 6);
    for (const auto& f : by_name(brdf))
        if (f.at("order") == "all" && f.at("component") == "all")
            binned[f.at("ndf") + f.at("material") + f.at("theta_i")] += std::stod(f.at("value")) * omega;
    REQUIRE(reflected.size() == 8);
    for (const auto& [cell, a] : reflected) {
        INFO(cell);
        CHECK(binned[cell] == Approx(a).epsilon(1e-12));
    }
    CHECK(reflected.at("beckmann(alpha=0.5)mirror30") == 1.0);  // mirror facets: every walk leaves, energy 1
    // Light from below into a dielectric: both hemispheres in brdf.csv, and the cell's energy all leaves.
    write(d / "glass.toml",
          "materials = [\"dielectric(eta=1.5)\"]\n[walks]\nn = 2000\n[grid]\ntheta_i = [150]\n"
          "[[ndf]]\nspec = \"ggx(alpha=0.4)\"\n[brdf]\ntheta_bins = 2\nphi_bins = 3\n");
    REQUIRE(run(trace_args(d / "glass.toml", d / "glass", 1)).rc == 0);
    CHECK(records(d / "glass" / "brdf.csv").size() == 1 + 2 * 2 * 3 * 5 * 3);
    for (const auto& f : by_name(records(d / "glass" / "albedo.csv")))
        if (f.at("hemisphere") == "all" && f.at("order") == "all" && f.at("component") == "all")
            CHECK(f.at("albedo") == "1");

    // The same bits for 3 threads, and a rerun reuses every cell.
    REQUIRE(run(trace_args(d / "scene.toml", d / "b", 3)).rc == 0);
    CHECK(slurp(d / "b" / "albedo.csv") == slurp(d / "a" / "albedo.csv"));
    CHECK(slurp(d / "b" / "brdf.csv") == slurp(d / "a" / "brdf.csv"));
    r = run(trace_args(d / "scene.toml", d / "a", 2));
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.out, Catch::Contains("traced 0\nreused 8\n"));
    CHECK(slurp(d / "b" / "albedo.csv") == slurp(d / "a" / "albedo.csv"));
    // A scene that changes what a cell is (its walks) traces every cell again.
    std::string more = trace_scene_text;
    more.replace(more.find("n = 3000"), 8, "n = 3001");
    write(d / "more.toml", more);
    CHECK_THAT(run(trace_args(d / "more.toml", d / "a", 2)).out, Catch::Contains("traced 8\nreused 0\n"));
}

TEST_CASE("trace: max_order = 1 ends every walk at its first hit -- fewer bounces, nothing beyond order 1",
          "[cli][walk][scene]") {
    const fs::path d = scratch() / "trace_order";
    fs::remove_all(d);
    fs::create_directories(d);
    const std::string base =
        "materials = [\"lambert(albedo=1)\"]\n[grid]\nalpha = [0.8]\ntheta_i = [60]\n[[ndf]]\nfamily = \"ggx\"\n";
    write(d / "all.toml", base + "[walks]\nn = 4000\n");
    write(d / "one.toml", base + "[walks]\nn = 4000\nmax_order = 1\n");
    REQUIRE(run(trace_args(d / "all.toml", d / "all", 1)).rc == 0);
    REQUIRE(run(trace_args(d / "one.toml", d / "one", 1)).rc == 0);
    auto bounces = [&](const char* dir) {
        const std::string meta = slurp(d / dir / "meta.json");
        const std::size_t at = meta.rfind("\"bounces\": ");
        return std::stoll(meta.substr(at + 11));
    };
    // Hammon's hit normals (D cos facing the ray) instead of visible normals: another law, every walk still leaves.
    write(d / "hammon.toml", base + "[walks]\nn = 4000\nhit_normal = \"hammon\"\n");
    REQUIRE(run(trace_args(d / "hammon.toml", d / "hammon", 1)).rc == 0);
    for (const auto& f : by_name(records(d / "hammon" / "albedo.csv")))
        if (f.at("hemisphere") == "all" && f.at("order") == "all" && f.at("component") == "all")
            CHECK(f.at("albedo") == "1");
    CHECK_THAT(slurp(d / "hammon" / "meta.json"), Catch::Contains("\"hit_normal\": \"hammon\""));
    CHECK(slurp(d / "hammon" / "albedo.csv") != slurp(d / "all" / "albedo.csv"));
    CHECK(run("trace --ndf 'ggx(alpha=0.5)' --hit-normal sideways --output '" + (d / "never").string() + "'").rc == 2);
    CHECK(bounces("one") <= 4000);
    CHECK(bounces("all") > 4000 + 4000 / 5);  // lambert(1) at alpha 0.8: ~1.6 hits per walk
    for (const auto& f : by_name(records(d / "one" / "albedo.csv")))
        if (f.at("order") == "2" || f.at("order") == "3" || f.at("order") == "4+") CHECK(f.at("albedo") == "0");
}

TEST_CASE("trace: the default sweep, and a malformed scene exits 2 naming the key, with nothing written",
          "[cli][walk][scene]") {
    const fs::path d = scratch() / "trace_default";
    fs::remove_all(d);
    fs::create_directories(d);
    // The embedded default scene, with fewer walks: 2 NDFs x 4 alphas x 2 materials x 3 angles.
    std::string def = run("trace --print-scene").out;
    REQUIRE(def.find("n = 200000") != std::string::npos);
    def.replace(def.find("n = 200000"), 10, "n = 600");
    write(d / "default.toml", def);
    const Run r = run(trace_args(d / "default.toml", d / "out", 2));
    REQUIRE(r.rc == 0);
    CHECK_THAT(r.out, Catch::Contains("cells 48\n"));
    for (const auto& f : by_name(records(d / "out" / "albedo.csv")))
        if (f.at("material") == "mirror" && f.at("hemisphere") == "all" && f.at("order") == "all" &&
            f.at("component") == "all")
            CHECK(f.at("albedo") == "1");

    struct Bad {
        std::string text, named;
    };
    const std::string grid = "[grid]\nalpha = [0.5]\ntheta_i = [45]\n";
    const std::string ndf = "[[ndf]]\nfamily = \"ggx\"\n";
    for (const Bad& b :
         {Bad{"materials = [\"velvet\"]\n" + grid + ndf, "velvet"},
          Bad{"materials = [\"mirror\"]\n[grid]\nalpha = [0.5]\ntheta_i = [90]\n" + ndf, "theta_i"},
          Bad{"materials = [\"dielectric\", \"mirror\"]\n[grid]\nalpha = [0.5]\ntheta_i = [120]\n" + ndf, "from below"},
          Bad{"materials = [\"mirror\"]\n[walks]\nn = 0\n" + grid + ndf, "walks.n"},
          Bad{"materials = [\"mirror\"]\n[walks]\nm = 3\n" + grid + ndf, "did you mean"},
          Bad{"materials = [\"mirror\"]\n" + ndf, "grid"},
          Bad{"materials = [\"mirror\"]\n" + grid + "[[ndf]]\nspec = \"ggx(alpha=-1)\"\n", "alpha"},
          Bad{"materials = [\"mirror\"]\n" + grid + "[[ndf]]\nspec = \"ggx(alpha=1)\"\nfamily = \"ggx\"\n",
              "exactly one"},
          Bad{"materials = [\"mirror\"]\n" + grid + ndf + "[walks]\ndownward = \"up\"\n", "downward"},
          Bad{"materials = [\"mirror\"]\n" + grid + ndf + "[walks]\nhit_normal = \"dcos\"\n", "hit_normal"},
          Bad{"materials = [\"mirror\"]\n" + grid + ndf + "[brdf]\ntheta_bins = 0\nphi_bins = 4\n", "theta_bins"},
          Bad{"materials = [\"mirror\"\n", "malformed"}}) {
        write(d / "bad.toml", b.text);
        const Run bad = run(trace_args(d / "bad.toml", d / "never", 1));
        INFO(b.text << "\n-> " << bad.err);
        CHECK(bad.rc == 2);
        CHECK_THAT(bad.err, Catch::Contains(b.named));
        CHECK_FALSE(fs::exists(d / "never"));
    }
    CHECK(run("trace '" + (d / "default.toml").string() + "' --ndf 'ggx(alpha=0.5)'").rc == 2);  // a scene or flags
    CHECK(run("trace '" + (d / "missing.toml").string() + "' --output '" + (d / "never").string() + "'").rc == 2);
}

namespace {

// `smithlab tables SCENE --output D/never OPTIONS`, in a fresh directory D of the test's own.
struct TablesRuns {
    fs::path d = scratch() / "tables_bad", never = d / "never";
    TablesRuns() {
        fs::remove_all(d);
        fs::create_directories(d);
    }
    Run operator()(const std::string& scene, const std::string& options) const {
        return run("tables '" + scene + "' --output '" + never.string() + "' " + options);
    }
};
const std::string tables_ndf = "[[ndf]]\nfamily = \"ggx\"\n";
const std::string tables_small = "[compensation]\nalpha = [0.5, 1.0]\ncosines = 4\nrefine = 2\n";

}  // namespace

TEST_CASE("tables: --help and the default scene, and a bad scene refused naming the item, with nothing written",
          "[cli][tables][scene]") {
    const TablesRuns tables;
    const fs::path& d = tables.d;
    const fs::path& never = tables.never;
    const Run help = run("tables --help");
    CHECK(help.rc == 0);
    CHECK_THAT(help.out,
               Catch::Contains("-o,--output") && Catch::Contains("--print-scene") && Catch::Contains("--scale") &&
                   Catch::Contains("--max-walks") && Catch::Contains("compensation/") &&
                   Catch::Contains("smithlab fit"));
    const Run def = run("tables --print-scene");
    CHECK(def.rc == 0);
    CHECK_THAT(def.out, Catch::Contains("[[ndf]]") && Catch::Contains("[compensation]"));

    struct Bad {
        std::string text, named;
    };
    const std::string& ndf = tables_ndf;
    const std::string& small = tables_small;
    for (const Bad& b :
         {Bad{"titel = \"x\"\n" + ndf + small, "bad.toml:1: unknown key 'titel' (did you mean 'title'?)"},
          Bad{ndf, "compensation is missing: a tables scene tabulates what its [compensation] table asks for"},
          Bad{small, "ndf is missing"}, Bad{"[[ndf]]\nfamily = \"ggz\"\n" + small, "ggz"},
          Bad{"[[ndf]]\nfamily = \"ggx\"\nalpha = [0.5]\n" + small,
              "'ggx' is given its roughness here: the tables sweep alpha over compensation.alpha"},
          Bad{ndf + "[compensation]\nalpha = [0.5]\n", "compensation.alpha needs 2 values"},
          Bad{ndf + small + "g2 = [\"smith\"]\n", "compensation.g2 must name height-correlated or separable"},
          Bad{ndf + small + "conductors = [\"mirror\"]\n", "compensation.conductors must name conductor"},
          Bad{ndf + small + "[training]\nwalks = 400\n", "unknown section 'training'"},
          Bad{"seed = -1\n" + ndf + small, "bad.toml:1: seed"},
          Bad{ndf + "[compensation]\ncosines = 4096\nrefine = 100\n",
              "compensation.refine with alpha, cosines, dielectric_cosines, g2 and eta makes the tables"},
          Bad{ndf + "[compensation\n", "malformed"}}) {
        write(d / "bad.toml", b.text);
        const Run bad = tables((d / "bad.toml").string(), "");
        INFO(b.text << "\n-> " << bad.err);
        CHECK(bad.rc == 2);
        CHECK_THAT(bad.err, Catch::StartsWith("smithlab: error: ") && Catch::Contains(b.named));
        CHECK_FALSE(fs::exists(never));
    }
}

TEST_CASE("tables: a size past --max-walks, bad options and paths refused, with nothing written", "[cli][tables]") {
    const TablesRuns tables;
    const fs::path& d = tables.d;
    const fs::path& never = tables.never;
    const std::string& ndf = tables_ndf;
    const std::string& small = tables_small;
    // The tables' size without a fit's walks beside them, against --max-walks: 3 x 7 values a table at 1000 walks a
    // value, two G2 forms (42 000), and the furnace's default 5 x 5 cells of mirror facets at 200 000 walks (5e6).
    write(d / "small.toml", ndf + small);
    const Run over = tables((d / "small.toml").string(), "--max-walks 5041999");
    CHECK(over.rc == 2);
    CHECK_THAT(over.err,
               Catch::Contains("the work of 42000 walks; with the furnace's 5e+06 and the scattering "
                               "orders' 0, more than --max-walks 5041999"));
    CHECK_FALSE(fs::exists(never));
    // Options and paths: each refused naming it, before any work.
    write(d / "a_file", "x");
    for (const Run& r :
         {tables((d / "small.toml").string(), "--threads -1"), tables((d / "small.toml").string(), "--scale 0"),
          tables((d / "small.toml").string(), "--max-walks x"), tables((d / "small.toml").string(), "--max-cells 10"),
          tables((d / "missing.toml").string(), ""),
          run("tables '" + (d / "small.toml").string() + "' -o '" + (d / "a_file").string() + "'")}) {
        INFO(r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::StartsWith("smithlab: error: "));
        CHECK_FALSE(fs::exists(never));
    }
    CHECK_THAT(tables((d / "missing.toml").string(), "").err, Catch::Contains("missing.toml"));
    CHECK_THAT(run("tables '" + (d / "small.toml").string() + "' -o '" + (d / "a_file").string() + "'").err,
               Catch::Contains("a_file' exists and is not a directory"));
    CHECK(slurp(d / "a_file") == "x");
}

// ---- the command line's conventions, its self-description, eval by angle and by range -----------------------------

namespace {

// The records of CSV text, header first.
std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::vector<std::string>> out;
    for (smithlab::CsvRecord& r : smithlab::read_csv(in)) out.push_back(std::move(r.fields));
    return out;
}

// The value of a "key  value" line of eval's one-point output.
std::string line_value(const std::string& out, const std::string& key) {
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        const auto gap = line.find(' ');
        if (line.substr(0, gap) == key) return line.substr(line.find_first_not_of(' ', gap));
    }
    return "";
}

}  // namespace

TEST_CASE("smithlab --version prints the project's version, and --help opens with it and names every registered NDF",
          "[cli]") {
    const Run v = run("--version");
    REQUIRE(v.rc == 0);
    std::smatch m;
    REQUIRE(std::regex_match(v.out, m, std::regex("smithlab ([0-9]+\\.[0-9]+\\.[0-9]+)\n")));
    const Run h = run("--help");
    REQUIRE(h.rc == 0);
    CHECK_THAT(h.out, Catch::StartsWith("smithlab " + m[1].str() + ": "));
    CHECK_THAT(h.out, Catch::Contains("--version"));
    for (const char* ndf : {"ggx", "beckmann", "blinn", "student", "tabulated", "abc", "gtr"})
        CHECK_THAT(h.out, Catch::Contains(ndf));
}

TEST_CASE("the texts say what the code does: list's GTR closed forms, eval's methods and its method line", "[cli]") {
    // list says up to which gamma GTR has a closed form; --method closed works there and is refused one above.
    const Run l = run("list");
    REQUIRE(l.rc == 0);
    const std::string at = "closed-form Lambda at integer gamma = 0..";
    const auto p = l.out.find(at);
    REQUIRE(p != std::string::npos);
    const int top = std::stoi(l.out.substr(p + at.size()));
    CHECK(top >= 4);
    CHECK(run("eval --ndf 'gtr(alpha=0.3, gamma=" + std::to_string(top) + ")' --mu 0.5 --method closed").rc == 0);
    const Run above =
        run("eval --ndf 'gtr(alpha=0.3, gamma=" + std::to_string(top + 1) + ")' --mu 0.5 --method closed");
    CHECK(above.rc == 2);
    CHECK_THAT(above.err, Catch::Contains("gamma"));
    CHECK_THAT(l.out, !Catch::Contains("e.g.\n"));  // a family without examples prints no empty list
    // eval's help lists every method with what --list-methods says of it.
    const Run methods = run("eval --list-methods"), help = run("eval --help");
    std::map<std::string, std::string> listed;  // "%-28s %s": name, description
    std::istringstream lines(methods.out);
    for (std::string line; std::getline(lines, line);) listed[line.substr(0, line.find(' '))] = line.substr(29);
    for (const char* name : {"auto", "closed", "spline", "quadrature", "quadrature2d", "fixed"}) {
        REQUIRE(listed.count(name) == 1);
        INFO(name << ": " << listed[name]);
        CHECK_THAT(help.out, Catch::Contains("  " + std::string(name) + ": " + listed[name] + "\n"));
    }
    // The method line says the route taken: auto is the closed form where there is one, else the fixed rule.
    CHECK_THAT(run("eval --ndf 'ggx(alpha=0.5)' --mu 1").out, Catch::Contains("method  auto (closed form)\n"));
    CHECK_THAT(run("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 0.5").out,
               Catch::Contains(
                   "method  auto (fixed rule, relative tolerance 1e-12; boost where its error estimate misses it)\n"));
    CHECK_THAT(run("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu 0.5 --method quadrature --backend gsl").out,
               Catch::Contains("method  quadrature (gsl, relative tolerance 1e-12)\n"));
}

TEST_CASE("eval --theta: degrees from the normal, the same values as --mu = cot(theta)", "[cli]") {
    struct Case {
        const char* theta;
        const char* mu;
    };
    // 45 degrees is mu = 1 exactly; 0 the normal, 90 grazing, above 90 below the surface.
    for (const Case c : {Case{"45", "1"}, Case{"0", "inf"}, Case{"90", "0"}, Case{"135", "-1"}, Case{"180", "-inf"}}) {
        const Run t = run(std::string("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --theta ") + c.theta);
        const Run m = run(std::string("eval --ndf 'gtr(alpha=0.3, gamma=1.5)' --mu ") + c.mu);
        INFO(c.theta << " " << t.err);
        REQUIRE(t.rc == 0);
        CHECK(line_value(t.out, "theta") == c.theta);
        CHECK(line_value(t.out, "mu") == c.mu);
        CHECK(line_value(t.out, "lambda") == line_value(m.out, "lambda"));
        CHECK(line_value(t.out, "g1") == line_value(m.out, "g1"));
    }
    // 60 degrees: mu = 1/sqrt(3) = 0.57735026918962576451 within half an ulp (5.55e-17 there), and 30: sqrt(3).
    const double mu60 = std::stod(line_value(run("eval --ndf 'ggx(alpha=0.5)' --theta 60").out, "mu"));
    CHECK(std::abs(static_cast<long double>(mu60) - 0.57735026918962576451L) <= 0.56e-16L);
    const double mu30 = std::stod(line_value(run("eval --ndf 'ggx(alpha=0.5)' --theta 30").out, "mu"));
    CHECK(std::abs(static_cast<long double>(mu30) - 1.7320508075688772935L) <= 1.12e-16L);
}

TEST_CASE("eval --mu-range and --theta-range: one CSV row per point, each the values of that point given alone",
          "[cli][csv]") {
    const fs::path d = scratch();
    const std::string ndf = "--ndf 'gtr(alpha=0.3, gamma=1.5)'";
    const Run r = run("eval " + ndf + " --mu-range log:0.01:100:5 -o '" + (d / "mu.csv").string() + "'");
    REQUIRE(r.rc == 0);
    const auto rows = csv_rows(slurp(d / "mu.csv"));
    REQUIRE(rows.size() == 6);
    CHECK(rows[0] == std::vector<std::string>{"ndf", "alpha", "gamma", "mu", "lambda", "g1"});
    const double want_mu[] = {0.01, 0.1, 1.0, 10.0, 100.0};
    for (std::size_t i = 1; i < rows.size(); ++i) {
        INFO(i);
        CHECK(rows[i][0] == "gtr(alpha=0.3, gamma=1.5)");
        CHECK(rows[i][1] == "0.3");
        CHECK(rows[i][2] == "1.5");
        CHECK(std::stod(rows[i][3]) == Approx(want_mu[i - 1]).epsilon(1e-14));
        const Run one = run("eval " + ndf + " --mu " + rows[i][3]);
        CHECK(line_value(one.out, "lambda") == rows[i][4]);
        CHECK(line_value(one.out, "g1") == rows[i][5]);
    }
    // Linear spacing, by angle: theta and its mu in each row, equal to --theta alone.
    const Run t = run("eval " + ndf + " --theta-range 0:120:5 --method quadrature");
    REQUIRE(t.rc == 0);
    const auto trows = csv_rows(t.out);
    REQUIRE(trows.size() == 6);
    CHECK(trows[0] == std::vector<std::string>{"ndf", "alpha", "gamma", "theta", "mu", "lambda", "g1"});
    const char* want_theta[] = {"0", "30", "60", "90", "120"};
    for (std::size_t i = 1; i < trows.size(); ++i) {
        INFO(i);
        CHECK(trows[i][3] == want_theta[i - 1]);
        const Run one = run("eval " + ndf + " --theta " + trows[i][3] + " --method quadrature");
        CHECK(line_value(one.out, "mu") == trows[i][4]);
        CHECK(line_value(one.out, "lambda") == trows[i][5]);
        CHECK(line_value(one.out, "g1") == trows[i][6]);
    }
    CHECK(trows[1][4] == "inf");
    CHECK(trows[4][4] == "0");
    CHECK(trows[4][6] == "0");  // grazing: G1 = 0
}

TEST_CASE("eval: a bad angle or range is refused naming its option, exit 2, nothing written", "[cli]") {
    const fs::path d = scratch();
    const fs::path never = d / "never_eval.csv";
    fs::remove(never);
    struct Case {
        const char* args;
        const char* named;
    };
    for (const Case& c : {Case{"--theta nan", "--theta"},
                          Case{"--theta 180.5", "--theta"},
                          Case{"--theta -1", "--theta"},
                          Case{"--theta 1x", "--theta"},
                          Case{"--mu-range 1:2:1", "--mu-range"},
                          Case{"--mu-range 1:2:0", "--mu-range"},
                          Case{"--mu-range 1:2:-3", "--mu-range"},
                          Case{"--mu-range 1:2:3.5", "--mu-range"},
                          Case{"--mu-range 2:1:5", "--mu-range"},
                          Case{"--mu-range 1:2", "--mu-range"},
                          Case{"--mu-range 1:nan:3", "--mu-range"},
                          Case{"--mu-range 1:inf:3", "--mu-range"},
                          Case{"--mu-range log:0:1:5", "--mu-range"},
                          Case{"--mu-range lin:1:2:3", "--mu-range"},
                          Case{"--mu-range 1:2:99999999", "--mu-range"},
                          Case{"--theta-range 0:200:3", "--theta-range"},
                          Case{"--theta-range -10:20:3", "--theta-range"},
                          Case{"--mu 1 --theta 45", "--theta"},
                          Case{"--mu-range 1:2:3 --theta-range 1:2:3", "--theta-range"},
                          Case{"--mu 1", "--output"}}) {
        const Run r = run(std::string("eval --ndf 'ggx(alpha=0.3)' ") + c.args + " -o '" + never.string() + "'");
        INFO(c.args << "\nstderr: " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains(c.named));
        CHECK(r.out.empty());
        CHECK_FALSE(fs::exists(never));
    }
    // A bad NDF with a range: nothing written either.
    CHECK(run("eval --ndf 'ggx(alpha=-1)' --mu-range 1:2:3 -o '" + never.string() + "'").rc == 2);
    CHECK_FALSE(fs::exists(never));
    CHECK_THAT(run("eval --mu-range 1:2:3").err, Catch::Contains("--ndf"));
}

TEST_CASE("one convention: COMMAND [SCENE] -o PATH, shared options checked alike", "[cli]") {
    const fs::path d = scratch();
    // -o is --output for every command that writes.
    fs::remove(d / "s.csv");
    REQUIRE(run("sample --ndf 'ggx(alpha=0.3)' --sampler vndf --n 3 -o '" + (d / "s.csv").string() + "'").rc == 0);
    CHECK(csv_rows(slurp(d / "s.csv")).size() == 4);
    for (const char* command : {"eval", "sample", "trace", "fit", "tables", "report"}) {
        INFO(command);
        CHECK_THAT(run(std::string(command) + " --help").out, Catch::Contains("-o,--output"));
    }
    for (const char* command : {"trace", "fit", "tables", "report"}) {
        INFO(command);
        const std::string help = run(std::string(command) + " --help").out;
        CHECK_THAT(help, Catch::Contains("scene") && Catch::Contains("--print-scene"));
        CHECK(run(std::string(command) + " --print-scene").rc == 0);
    }
    // --threads, --walks, --seed and --downward: one rule each, in every command that takes them.
    const std::string brdf = "brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 45,180 ";
    const std::string to_never = " -o '" + (d / "never_dir").string() + "'";
    for (const std::string& bad :
         {brdf + "--threads -1", brdf + "--walks 0", brdf + "--seed x", brdf + "--downward up",
          "trace --ndf 'ggx(alpha=0.5)' --threads -1" + to_never, "fit --threads -1" + to_never,
          "trace --ndf 'ggx(alpha=0.5)' --downward up" + to_never,
          "trace --ndf 'ggx(alpha=0.5)' --seed x" + to_never}) {
        const Run r = run(bad);
        INFO(bad << "\nstderr: " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::StartsWith("smithlab: error: "));
        CHECK_FALSE(fs::exists(d / "never_dir"));
    }
}

TEST_CASE("scale: the same scene at a fraction of its walks, and a scale outside 0 < F <= 1000 refused", "[cli]") {
    const fs::path d = scratch();
    write(d / "scale.toml",
          "materials = [\"mirror\"]\n[walks]\nn = 1000\n[grid]\ntheta_i = [30]\n[[ndf]]\nspec = \"ggx(alpha=0.5)\"\n");
    const std::string trace = "trace '" + (d / "scale.toml").string() + "' -o '" + (d / "scaled").string() + "'";
    fs::remove_all(d / "scaled");
    const Run half = run(trace + " --scale 0.5");
    INFO(half.err);
    REQUIRE(half.rc == 0);
    CHECK_THAT(half.out, Catch::Contains("\nwalks 500\n"));
    // At least one walk a cell however small the scale; and the bound is checked on the scaled scene.
    fs::remove_all(d / "scaled");
    CHECK_THAT(run(trace + " --scale 1e-9").out, Catch::Contains("\nwalks 1\n"));
    const Run over = run(trace + " --scale 2 --max-walks 1500");
    CHECK(over.rc == 2);
    CHECK_THAT(over.err, Catch::Contains("makes the scene 2000 walks"));
    for (const std::string& bad : {trace + " --scale 0", trace + " --scale nan", trace + " --scale 1001",
                                   "fit --scale -1 -o '" + (d / "never_dir").string() + "'",
                                   "tables --scale -1 -o '" + (d / "never_dir").string() + "'",
                                   "report --scale 0 -o '" + (d / "never_dir").string() + "'"}) {
        const Run r = run(bad);
        INFO(bad << "\nstderr: " << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err, Catch::Contains("--scale"));
        CHECK_FALSE(fs::exists(d / "never_dir"));
    }
    const Run flags =
        run("trace --ndf 'ggx(alpha=0.5)' --walks 100 --scale 0.5 -o '" + (d / "never_dir").string() + "'");
    CHECK(flags.rc == 2);
    CHECK_THAT(flags.err, Catch::Contains("--scale goes with a scene; the cell flags give the walks"));
}
