// The per-distribution checks, run for every registered NDF at each of its example points (stiff ones included).
// A user who registers an NDF with examples gets these for free.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/gtr.hpp>

TEST_CASE("every registered NDF passes the per-distribution checks at its example points", "[checks]") {
    const smithlab::NdfRegistry registry = smithlab::builtin_registry();
    REQUIRE(registry.list().size() >= 4);
    for (const smithlab::NdfInfo* info : registry.list()) {
        // An NDF read from a file has no example a spec can name anywhere: test_tabulated checks it on its tables.
        if (!info->text_parameters.empty()) continue;
        REQUIRE(info->examples.size() >= 3);
        for (const std::string& spec : info->examples) {
            const smithlab::AnyNdf ndf = registry.make(spec);
            for (const auto& r : smithlab::run_checks(ndf)) {
                INFO(spec << ": " << r.name << " " << r.where << " value=" << r.value << " expected=" << r.expected);
                CHECK(r.residual() <= r.tolerance);
            }
        }
    }
}

TEST_CASE("the checks catch a broken NDF", "[checks]") {
    // D is GGX scaled by 1.001: not normalized. Every identity that involves D must fail.
    struct Broken {
        double D(double c) const { return 1.001 * smithlab::ggx(0.3).D(c); }
    };
    int failed = 0;
    for (const auto& r : smithlab::run_checks(Broken{}, {.with_2d = false})) failed += !r.passed();
    CHECK(failed >= 5);
}

TEST_CASE("the checks catch an analytic D cos sampler that inverts the wrong law", "[checks][sampling]") {
    // GGX whose sampler uses the blog's Beckmann inversion: D is right, the sampler is not.
    struct WrongSampler {
        double D(double c) const { return smithlab::ggx(0.3).D(c); }
        double Dcos_sf(double r2) const { return std::exp(-r2 / 0.09); }
        double Dcos_r2(double v) const { return -0.09 * std::log(v); }
    };
    int failed = 0, sampler_checks = 0;
    for (const auto& r : smithlab::run_checks(WrongSampler{}, {.with_2d = false})) {
        if (r.name.find("sampler") == std::string::npos) {
            CHECK(r.passed());
            continue;
        }
        ++sampler_checks;
        failed += !r.passed();
    }
    CHECK(sampler_checks == 4);
    CHECK(failed == 4);
}

TEST_CASE("the checks run on the GSL backend too", "[checks]") {
    const auto ndf = smithlab::gtr(0.2, 1.5);
    for (const auto& r : smithlab::run_checks(ndf, {.backend = smithlab::Backend::gsl})) {
        INFO(r.name << " " << r.where);
        CHECK(r.passed());
    }
}
