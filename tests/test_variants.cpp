// The Lambda variants: every one runs on every NDF it applies to; the exact ones are exact to their tolerance; the
// approximations are the published formulas; the interpolants are exact at their knots and better with more knots.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/gtr.hpp>

using namespace smithlab;

TEST_CASE("every variant gives a non-negative Lambda, never NaN, on every example NDF it applies to", "[variants]") {
    const NdfRegistry ndfs = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    REQUIRE(variants.list().size() >= 27);
    for (const LambdaVariant& v : variants.list()) {
        int applied = 0;
        for (const NdfInfo* info : ndfs.list())
            for (const std::string& spec : info->examples) {
                const AnyNdf ndf = ndfs.make(spec);
                if (!v.applies(ndf)) {
                    CHECK_THROWS_AS(Lambda(v, ndf, 1.0), input_error);
                    continue;
                }
                ++applied;
                for (double mu : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
                    const double l = Lambda(v, ndf, mu);
                    INFO(v.name << " on " << spec << " mu=" << mu << " Lambda=" << l);
                    CHECK(l >= 0.0);  // false for NaN
                    // Only an interpolated G1, clamped to [0, 1], may reach Lambda = inf at a finite mu.
                    if (v.name.find("-g1-") == std::string::npos && v.name != "dimov-spline") CHECK(std::isfinite(l));
                }
                CHECK(Lambda(v, ndf, 0.0) == INFINITY);
                CHECK(Lambda(v, ndf, INFINITY) == 0.0);
            }
        INFO(v.name);
        CHECK(applied > 0);
    }
}

TEST_CASE("every variant carries the route it computes by", "[variants]") {
    const NdfRegistry ndfs = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    const AnyNdf ggx = ndfs.make("ggx(alpha=0.3)"), blinn = ndfs.make("blinn(n=20)");
    for (const LambdaVariant& v : variants.list()) {
        INFO(v.name);
        const auto starts = [&](const char* prefix) { return v.name.rfind(prefix, 0) == 0; };
        const LambdaRoute want = starts("q1d-boost-") ? LambdaRoute::q1d_boost
            : starts("q2d-boost-")                    ? LambdaRoute::q2d_boost
            : starts("q1d-gsl-")                      ? LambdaRoute::q1d_gsl
            : starts("q2d-gsl-")                      ? LambdaRoute::q2d_gsl
            : v.name == "closed-form"                 ? LambdaRoute::closed
            : v.name == "table"                       ? LambdaRoute::table
                                                      : LambdaRoute::other;
        CHECK(v.route == want);
        CHECK(is_quadrature(v.route) == (starts("q1d-") || starts("q2d-")));
    }
    // The table takes the exact route it is built from: the closed form where the NDF has one, else Boost 1D.
    CHECK(route_on(variants.at("table"), ggx) == LambdaRoute::closed);
    CHECK(route_on(variants.at("table"), blinn) == LambdaRoute::q1d_boost);
    CHECK(route_on(variants.at("q2d-gsl-1e-6"), ggx) == LambdaRoute::q2d_gsl);
}

TEST_CASE("quadrature variants meet their relative tolerance against the closed forms", "[variants]") {
    const NdfRegistry ndfs = builtin_registry();
    const VariantRegistry variants = builtin_variants();
    for (const char* spec :
         {"ggx(alpha=0.01)", "gtr(alpha=0.3, gamma=1)", "gtr(alpha=0.05, gamma=10)", "beckmann(alpha=0.5)"}) {
        const AnyNdf ndf = ndfs.make(spec);
        for (const LambdaVariant& v : variants.list()) {
            if (v.name.rfind("q1d-", 0) != 0 && v.name.rfind("q2d-", 0) != 0) continue;
            const double tol = std::stod(v.name.substr(v.name.rfind('-') + 1));
            for (double mu : {1e-2, 1.0, 1e2}) {
                const double want = ndf.Lambda(mu);
                INFO(v.name << " on " << spec << " mu=" << mu);
                CHECK(std::abs(Lambda(v, ndf, mu) - want) <= tol * want);
            }
        }
    }
}

TEST_CASE("the approximations are the published formulas", "[variants]") {
    for (double alpha : {0.05, 0.5, 1.0})
        for (double mu : {0.01, 0.3, 1.0, 5.0}) {
            const double NdotV = mu / std::sqrt(1.0 + mu * mu);
            // Hammon 2017: G1 ~ 2 NdotV / (NdotV (2 - alpha) + alpha); Unreal: NdotV / (NdotV (1 - k) + k), k =
            // alpha/2.
            const double hammon = 2.0 * NdotV / (NdotV * (2.0 - alpha) + alpha);
            const double k = alpha / 2.0, unreal = NdotV / (NdotV * (1.0 - k) + k);
            CHECK(1.0 / (1.0 + Lambda_schlick_ggx(alpha, mu)) == Approx(hammon).epsilon(1e-14));
            CHECK(hammon == Approx(unreal).epsilon(1e-14));
            // Walter 2007 eq. 27.
            const double a = mu / alpha;
            const double walter = a < 1.6 ? (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a) : 1.0;
            CHECK(1.0 / (1.0 + Lambda_beckmann_rational(alpha, mu)) == Approx(walter).epsilon(1e-14));
        }
}

TEST_CASE("interpolants across gamma: exact at the knots, and beyond gamma = 4 far better than Dimov's clamp",
          "[variants]") {
    using K = GammaInterpolant::Kind;
    using Q = GammaInterpolant::Quantity;
    for (double alpha : {0.01, 0.3, 0.9})
        for (double mu : {0.05, 1.0, 20.0}) {
            for (const GammaInterpolant how :
                 {GammaInterpolant{K::akima, Q::G1, 4}, GammaInterpolant{K::steffen, Q::log_Lambda, 10},
                  GammaInterpolant{K::cspline, Q::log_Lambda, 20}}) {
                const double exact = gtr(alpha, 3.0).Lambda(mu);
                INFO(name_of(how) << " alpha=" << alpha << " mu=" << mu);
                if (how.quantity == Q::G1)
                    CHECK(1.0 / (1.0 + Lambda_gtr_interpolated(alpha, 3.0, mu, how)) ==
                          Approx(1.0 / (1.0 + exact)).epsilon(1e-15));
                else CHECK(Lambda_gtr_interpolated(alpha, 3.0, mu, how) == Approx(exact).epsilon(1e-13));
            }
            // Above gamma = 4, against 1D quadrature: Dimov clamps to 4; log Lambda through knots 0..20 follows gamma.
            // (Between 0 and 4 the knots are as far apart for every variant, and none is uniformly better: the
            // report measures that.)
            double worst_dimov = 0.0, worst_k20 = 0.0;
            for (double g : {5.5, 7.5, 12.5}) {
                const double exact = Lambda(gtr(alpha, g), mu, {.method = Method::quadrature});
                const double dimov = (1.0 - G1_gtr_dimov_spline(alpha, g, mu)) / G1_gtr_dimov_spline(alpha, g, mu);
                const double k20 = Lambda_gtr_interpolated(alpha, g, mu, {K::cspline, Q::log_Lambda, 20});
                worst_dimov = std::max(worst_dimov, std::abs(dimov - exact) / exact);
                worst_k20 = std::max(worst_k20, std::abs(k20 - exact) / exact);
            }
            INFO("alpha=" << alpha << " mu=" << mu << " dimov " << worst_dimov << " k20 " << worst_k20);
            CHECK(worst_k20 < 1e-2 * worst_dimov);
        }
}

TEST_CASE("G2 variants: Hammon's lerp is his published formula, and exact where he says it is", "[variants][g2]") {
    const auto reg = builtin_registry();
    const auto variants = builtin_G2_variants();
    REQUIRE(variants.size() == 3);
    for (double alpha : {0.1, 0.5, 1.0})
        for (double mi : {0.2, 1.0, 5.0})
            for (double mo : {0.3, 2.0}) {
                const double nl = mi / std::sqrt(1 + mi * mi), nv = mo / std::sqrt(1 + mo * mo);
                const double lerp = 2 * nl * nv + alpha * ((nl + nv) - 2 * nl * nv);
                CHECK(G2_hammon_lerp(alpha, mi, mo) == Approx(2 * nl * nv / lerp).epsilon(1e-14));
            }
    // Solving Hammon's G1 for Lambda and building the height-correlated G2 gives his lerp exactly ("Smith: Approximate
    // GGX G2"): 1/(1 + L_i + L_o) with L = alpha (1 - N.X)/(2 N.X).
    for (double alpha : {0.1, 0.8})
        for (double mi : {0.2, 3.0}) {
            const double mo = 0.7;
            CHECK(G2_hammon_lerp(alpha, mi, mo) ==
                  Approx(1.0 / (1.0 + Lambda_schlick_ggx(alpha, mi) + Lambda_schlick_ggx(alpha, mo))).epsilon(1e-13));
        }
    // Uncorrelated is below correlated (Hammon 2017, "Correlated vs Uncorrelated").
    const AnyNdf g = reg.make("ggx(alpha=0.6)");
    CHECK(variants[0].G2(g, 0.3, 0.5) < G2(g, 0.3, 0.5));
}
