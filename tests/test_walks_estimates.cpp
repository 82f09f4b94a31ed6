// What the walking commands print is an estimate or nothing: `brdf` refuses the Dirac delta of an index-matched
// dielectric (naming --wo) and prints no non-finite number for any material and direction pair; `brdf`, `trace` and
// the report's walk section refuse results whose walks were cut short at the event cap (the energy missing could
// exceed the standard error), saying how many walks of how many and the cap.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"

using smithlab_test::Run;
using smithlab_test::run;

namespace {

// Every number on every line of brdf's answer ("NAME X [Y]") is finite.
bool all_finite(const std::string& out) {
    std::istringstream lines(out);
    std::string line;
    int numbers = 0;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        std::string name, x;
        fields >> name;
        while (fields >> x) {
            ++numbers;
            if (!std::isfinite(std::strtod(x.c_str(), nullptr))) return false;
        }
    }
    return numbers > 0;
}

// Whether "THETA,PHI" a and b (degrees) are opposite directions: the straight-through pair.
bool opposite(const std::string& a, const std::string& b) {
    const auto unit = [](const std::string& d) {
        const double deg = std::acos(-1.0) / 180.0, t = std::stod(d) * deg,
                     p = std::stod(d.substr(d.find(',') + 1)) * deg;
        return std::array<double, 3>{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
    };
    const std::array<double, 3> u = unit(a), v = unit(b);
    return std::hypot(u[0] + v[0], u[1] + v[1], u[2] + v[2]) < 1e-9;
}

std::string brdf(const std::string& material, const std::string& wi, const std::string& wo, int walks = 200) {
    return "brdf --ndf 'ggx(alpha=0.5)' --material '" + material + "' --wi " + wi + " --wo " + wo + " --walks " +
        std::to_string(walks) + " --threads 1";
}

}  // namespace

TEST_CASE("brdf refuses the straight-through pair of an index-matched dielectric as a Dirac delta", "[walks]") {
    for (const auto& [wi, wo] :
         {std::pair{"45,0", "135,180"}, std::pair{"0,0", "180,0"}, std::pair{"135,180", "45,0"}}) {
        const Run r = run(brdf("dielectric(eta=1)", wi, wo, 1000));
        INFO(wi << " -> " << wo << ": " << r.out << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err,
                   Catch::Contains(std::string("--wo ") + wo) && Catch::Contains("Dirac delta") &&
                       Catch::Contains("smithlab: error:"));
        CHECK(r.out.empty());
    }
}

TEST_CASE("brdf prints a finite estimate for every material and direction pair, or refuses the pair",
          "[walks][sweep]") {
    const std::vector<std::string> materials = {"mirror",
                                                "conductor(eta=0.2, k=3)",
                                                "lambert(albedo=1)",
                                                "fresnel-diffuse(f0=0.04, albedo=0.8)",
                                                "dielectric(eta=1.5)",
                                                "dielectric(eta=1)",
                                                "dielectric(eta=0.7)"};
    // wo: the poles, grazing, either side of it, both azimuths; and each wi's mirror and straight-through directions.
    std::vector<std::string> wos;
    for (const char* theta : {"0", "45", "89.99", "90", "90.01", "135", "180"})
        for (const char* phi : {"0", "180"}) wos.push_back(std::string(theta) + "," + phi);
    struct Light {
        std::string wi, mirror, through;
    };
    const std::vector<Light> from_above = {
        {"0,0", "0,180", "180,0"}, {"45,0", "45,180", "135,180"}, {"89.9,30", "89.9,210", "90.1,210"}};
    const std::vector<Light> from_below = {{"135,180", "135,0", "45,0"}, {"180,0", "180,180", "0,0"}};
    for (const std::string& m : materials) {
        std::vector<Light> lights = from_above;
        if (m.rfind("dielectric", 0) == 0) lights.insert(lights.end(), from_below.begin(), from_below.end());
        for (const Light& l : lights) {
            std::vector<std::string> to = wos;
            to.push_back(l.mirror);
            to.push_back(l.through);
            for (const std::string& wo : to) {
                const Run r = run(brdf(m, l.wi, wo));
                INFO(m << ": " << l.wi << " -> " << wo << ": rc " << r.rc << "\n" << r.out << r.err);
                const bool dirac = m == "dielectric(eta=1)" && opposite(l.wi, wo);
                if (dirac) {
                    CHECK(r.rc == 2);
                    CHECK_THAT(r.err, Catch::Contains("Dirac delta"));
                } else {
                    CHECK(r.rc == 0);
                    CHECK(all_finite(r.out));
                }
            }
        }
    }
}

// ggx(alpha=1e6): walks on a surface that rough end at the cap of a million facet events, every one (a few walks:
// each is a million events).
TEST_CASE("brdf refuses an estimate whose walks were cut at the event cap", "[walks]") {
    const Run r = run("brdf --ndf 'ggx(alpha=1e6)' --material mirror --wi 45,0 --wo 45,180 --walks 2 --threads 1");
    INFO(r.out << r.err);
    CHECK(r.rc == 2);
    CHECK_THAT(r.err,
               Catch::Contains("2 of 2 walks were cut short") && Catch::Contains("1000000 facet events") &&
                   Catch::Contains("--ndf 'ggx(alpha=1e6)'"));
    CHECK(r.out.empty());
}

TEST_CASE("trace refuses a cell whose capped walks could carry more than its standard error", "[walks]") {
    const fs::path d = smithlab_test::scratch() / "walks_capped";
    fs::remove_all(d);
    const std::string args =
        "trace --ndf 'ggx(alpha=1e6)' --material mirror --theta-i 45 --walks 2 --threads 1 -o '" + d.string() + "'";
    for (int pass = 0; pass < 2; ++pass) {  // traced, then again from the kept cell file
        const Run r = run(args);
        INFO("pass " << pass << ": " << r.out << r.err);
        CHECK(r.rc == 2);
        CHECK_THAT(r.err,
                   Catch::Contains("cell 0 (ggx(alpha=1e+06), mirror, theta_i 45, phi_i 0)") &&
                       Catch::Contains("2 of 2 walks were cut short") && Catch::Contains("1000000 facet events") &&
                       Catch::Contains("standard error"));
        CHECK_FALSE(fs::exists(d / "albedo.csv"));
        CHECK_FALSE(fs::exists(d / "meta.json"));
        CHECK(r.out.empty());
    }
    CHECK(fs::exists(d / "cells" / "cell-000000.csv"));
    fs::remove_all(d);
}
