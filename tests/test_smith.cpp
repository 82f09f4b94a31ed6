// The Smith engine's conventions: limits of mu, downward directions, G1, G2 forms, method selection.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/gtr.hpp>

using namespace smithlab;

TEST_CASE("limits mu = 0 and mu = inf, for every method", "[smith]") {
    const auto ndf = gtr(0.3, 1.5);
    for (Method m : {Method::automatic, Method::spline, Method::quadrature, Method::quadrature2d, Method::fixed}) {
        const LambdaOptions o{.method = m};
        CHECK(Lambda(ndf, 0.0, o) == INFINITY);
        CHECK(G1(ndf, 0.0, o) == 0.0);
        CHECK(Lambda(ndf, INFINITY, o) == 0.0);
        CHECK(G1(ndf, INFINITY, o) == 1.0);
    }
}

TEST_CASE("downward directions: Smith's Lambda(-mu) = -1 - Lambda(mu), Hammon's symmetric -Lambda(mu)", "[smith]") {
    const auto ndf = ggx(0.4);
    const double up = ndf.Lambda(0.7);
    CHECK(Lambda(ndf, -0.7) == -1.0 - up);
    CHECK(Lambda(ndf, -0.7, {.downward = Downward::hammon_symmetric}) == -up);
    // G1 uses |cot theta| (Walter 2007 eq. 44).
    CHECK(G1(ndf, -0.7) == G1(ndf, 0.7));
}

TEST_CASE("G1 = 1/(1 + Lambda) and the two G2 forms", "[smith]") {
    const auto ndf = beckmann(0.35);
    const double li = ndf.Lambda(0.2), lo = ndf.Lambda(0.5);
    REQUIRE(li > 0.1);
    REQUIRE(lo > 1e-3);
    CHECK(G1(ndf, 0.2) == Approx(1.0 / (1.0 + li)).epsilon(1e-15));
    CHECK(G2(ndf, 0.2, 0.5) == Approx(1.0 / (1.0 + li + lo)).epsilon(1e-15));
    CHECK(G2(ndf, 0.2, 0.5, G2Form::uncorrelated) == Approx(G1(ndf, 0.2) * G1(ndf, 0.5)).epsilon(1e-15));
    // Hammon 2017, "Smith: Correlated vs Uncorrelated": correlated > uncorrelated, equal when one Lambda is 0.
    CHECK(G2(ndf, 0.2, 0.5) > G2(ndf, 0.2, 0.5, G2Form::uncorrelated));
    CHECK(G2(ndf, 0.2, INFINITY) == Approx(G2(ndf, 0.2, INFINITY, G2Form::uncorrelated)).epsilon(1e-15));
    // Transmission (opposite sides): integral_0^1 u^li (1-u)^lo du, here checked by midpoint rule.
    double beta = 0.0;
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
        const double u = (k + 0.5) / n;
        beta += std::pow(u, li) * std::pow(1.0 - u, lo) / n;
    }
    CHECK(G2(ndf, 0.2, -0.5) == Approx(beta).epsilon(1e-6));
}

TEST_CASE("method selection: closed where it exists, errors where it does not", "[smith]") {
    const auto gg = ggx(0.2);
    const auto bl = blinn(30.0);
    CHECK(Lambda(gg, 1.0) == gg.Lambda(1.0));                              // auto takes the closed form
    CHECK(Lambda(bl, 1.0) == Lambda(bl, 1.0, {.method = Method::fixed}));  // else the fixed rule
    CHECK(Lambda(bl, 1.0) == Approx(Lambda(bl, 1.0, {.method = Method::quadrature})).epsilon(1e-12));
    CHECK_THROWS_AS(Lambda(bl, 1.0, {.method = Method::closed}), input_error);
    CHECK_THROWS_AS(Lambda(gg, 1.0, {.method = Method::spline}), input_error);
    CHECK_THROWS_AS(Lambda(gtr(0.3, 1.5), 1.0, {.method = Method::closed}), input_error);
    CHECK_THROWS_AS(gtr(0.3, 1.5).Lambda(1.0), input_error);  // the member, called directly, refuses too
    CHECK_THROWS_AS(Lambda(gg, NAN), input_error);
    CHECK(has_closed_Lambda(gtr(0.3, 3.0)));
    CHECK_FALSE(has_closed_Lambda(gtr(0.3, 3.5)));
}

TEST_CASE("methods, backends and downward conventions by name: one table each, parsed and printed from it", "[smith]") {
    for (const auto& m : method_names) CHECK(to_string(parse_method(m.name)) == m.name);
    for (const auto& b : backend_names) CHECK(to_string(parse_backend(b.name)) == b.name);
    CHECK(parse_method("auto") == Method::automatic);
    CHECK(parse_downward("smith") == Downward::smith);
    CHECK(parse_downward("hammon") == Downward::hammon_symmetric);
    CHECK_THROWS_WITH(
        parse_method("q1d"),
        Catch::Contains("unknown method 'q1d' (expected auto, closed, spline, quadrature, quadrature2d or fixed)"));
    CHECK_THROWS_WITH(parse_backend("qags"),
                      Catch::Contains("unknown quadrature backend 'qags' (expected boost or gsl)"));
    CHECK_THROWS_WITH(parse_downward("up"), Catch::Contains("'up' (expected smith or hammon)"));
}

TEST_CASE("the same answers through the type-erased AnyNdf", "[smith]") {
    const auto reg = builtin_registry();
    const AnyNdf any = reg.make("gtr(alpha=0.25, gamma=3)");
    const auto direct = gtr(0.25, 3.0);
    for (double mu : {0.01, 1.0, 100.0}) {
        CHECK(Lambda(any, mu) == direct.Lambda(mu));
        CHECK(Lambda(any, mu, {.method = Method::quadrature}) == Lambda(direct, mu, {.method = Method::quadrature}));
        CHECK(Lambda(any, mu, {.method = Method::spline}) == direct.Lambda_spline(mu));
    }
    CHECK_THROWS_AS(Lambda(reg.make("blinn(n=3)"), 1.0, {.method = Method::closed}), input_error);
}

TEST_CASE("no NaN or Inf for finite mu in the domain, and none at the domain's edges", "[smith]") {
    const auto reg = builtin_registry();
    for (const auto* info : reg.list())
        for (const auto& spec : info->examples) {
            const AnyNdf ndf = reg.make(spec);
            for (double mu : {1e-4, 1e-2, 1.0, 1e2, 1e4}) {
                const double l = Lambda(ndf, mu, {.method = Method::quadrature});
                INFO(spec << " mu=" << mu);
                CHECK(std::isfinite(l));
                CHECK(l >= 0.0);
            }
        }
}

TEST_CASE("a user D that returns NaN is reported, not integrated", "[smith]") {
    struct Bad {
        double D(double c) const { return c < 0.5 ? NAN : 1.0 / 3.141592653589793; }
    };
    try {
        Lambda(Bad{}, 0.3);
        FAIL("no error");
    } catch (const input_error& e) {
        CHECK_THAT(e.what(), Catch::Contains("D(cos_theta_m = ") && Catch::Contains("nan"));
    }
}
