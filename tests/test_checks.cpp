// The per-distribution checks, run for every registered NDF at each of its example points (stiff ones included).
// A user who registers an NDF with examples gets these for free.
#include <catch2/catch.hpp>
#include <smithlab/smithlab.hpp>

TEST_CASE("every registered NDF passes the per-distribution checks at its example points", "[checks]") {
    const smithlab::NdfRegistry registry = smithlab::builtin_registry();
    REQUIRE(registry.list().size() >= 4);
    for (const smithlab::NdfInfo* info : registry.list()) {
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

TEST_CASE("the checks run on the GSL backend too", "[checks]") {
    const auto ndf = smithlab::gtr(0.2, 1.5);
    for (const auto& r : smithlab::run_checks(ndf, {.backend = smithlab::Backend::gsl})) {
        INFO(r.name << " " << r.where);
        CHECK(r.passed());
    }
}
