// The tabulated Lambda (lambda_table.hpp), the fast evaluator for any real gamma: against routes it is not built
// from (the nested 2D quadrature, the closed forms, the 50-digit reference), and its error estimate against the
// error measured.
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <random>
#include <smithlab/gtr.hpp>

#include "grid.hpp"
#include "reference.hpp"

using namespace smithlab;

namespace {

struct Worst {
    double rel = 0.0, dG1 = 0.0;
    void add(double got, double want) {
        rel = std::max(rel, std::abs(got - want) / want);
        dG1 = std::max(dG1, std::abs(1.0 / (1.0 + got) - 1.0 / (1.0 + want)));
    }
};

}  // namespace

TEST_CASE("table: the fast-evaluator target over alpha in [1e-4, 1], mu in [1e-4, 1e4], any real gamma in [0, 20]",
          "[table]") {
    // Random (alpha, gamma), the stiff corners among them; 12 random mu per table against the nested 2D route.
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> log_alpha(std::log(1e-4), 0.0), gamma_u(0.0, 20.0),
        log_mu(std::log(1e-4), std::log(1e4));
    std::vector<std::pair<double, double>> cases = {{1e-4, 0.0}, {1e-4, 0.5},  {1e-4, 1.0 - 1e-9}, {1e-4, 1.0 + 1e-9},
                                                    {1e-4, 1.5}, {1e-4, 19.7}, {1.0, 0.3},         {0.999999, 7.5},
                                                    {0.3, 1.25}, {1e-3, 20.0}};
    for (int k = 0; k < 14; ++k) cases.emplace_back(std::exp(log_alpha(rng)), gamma_u(rng));
    Worst all;
    for (const auto& [alpha, gamma] : cases) {
        const Gtr ndf = gtr(alpha, gamma);
        const LambdaTable table = tabulate_Lambda(ndf);
        Worst w;
        for (int i = 0; i < 12; ++i) {
            const double mu = std::exp(log_mu(rng));
            w.add(table.Lambda(mu), Lambda_2d(ndf, mu, {Backend::gsl, 1e-11}));
        }
        for (double mu : {1e-4, 1e4}) w.add(table.Lambda(mu), Lambda_2d(ndf, mu, {Backend::gsl, 1e-11}));
        INFO("gtr(" << alpha << ", " << gamma << "): worst relative dLambda " << w.rel << ", estimate "
                    << table.error_estimate() << ", |dG1| " << w.dG1 << ", " << table.knots() << " knots");
        CHECK(w.rel <= table.error_estimate());  // the estimate holds
        CHECK(table.error_estimate() <= 1e-6);
        all.rel = std::max(all.rel, w.rel);
        all.dG1 = std::max(all.dG1, w.dG1);
    }
    WARN("table: worst relative dLambda " << all.rel << ", worst |dG1| " << all.dG1);
    CHECK(all.rel <= 1e-5);  // the table's stated accuracy
    CHECK(all.dG1 <= 1e-6);
    CHECK(all.rel > 1e-10);  // a table, not the exact route in disguise
}

TEST_CASE("table: against the 50-digit reference at the stiff corners and the generated closed forms", "[table]") {
    for (const auto& [alpha, gamma, mu] : {std::tuple{1e-4, 0.5, 1e-4}, std::tuple{1e-4, 1.0 + 1e-9, 3e-3},
                                           std::tuple{0.02, 13.3, 0.05}, std::tuple{0.9, 0.1, 1e4}}) {
        const double got = tabulate_Lambda(gtr(alpha, gamma)).Lambda(mu);
        INFO("gtr(" << alpha << ", " << gamma << ") mu=" << mu);
        CHECK(ref::close(got, ref::Lambda(ref::gtr(alpha, gamma), mu), 1e-6));
    }
    for (int gamma : {0, 2, 5, 10, 20}) {
        const Gtr ndf = gtr(0.01, gamma);
        const LambdaTable table = tabulate_Lambda(ndf, {.exact = {.method = Method::quadrature}});
        for (double mu : grid::logspace(1e-4, 1e4, 33)) {
            INFO("gamma=" << gamma << " mu=" << mu);
            CHECK(std::abs(table.Lambda(mu) / ndf.Lambda(mu) - 1.0) <= table.error_estimate());
        }
    }
}

// ---- every mu: the three pieces (lambda_table.hpp), against references the table is not built from ----------------

namespace {

// Far outside the old range [1e-5, 1e5], on both sides, and points inside it that are no knots.
const std::vector<double> extreme_mus = {DBL_TRUE_MIN, 1e-300, 1e-100, 1e-20, 1e-12, 1e-8,  1e-7,  3.3e-3,
                                         0.71,         1e7,    1e12,   1e50,  1e100, 1e200, 1e300, DBL_MAX};

// The rule of the header: relative error within the table's estimate where Lambda >= 1e-290; below, an answer in
// [0, 1e-290] (the truth underflowed); above DBL_MAX, +inf.
void check_Lambda(const LambdaTable& t, double mu, double want, const std::string& what, Worst& w) {
    const double got = t.Lambda(mu);
    INFO(what << " mu=" << mu << " got=" << got << " want=" << want << " estimate=" << t.error_estimate());
    if (!(want <= DBL_MAX)) {
        CHECK(got == INFINITY);
    } else if (want < 1e-290) {
        CHECK((got >= 0.0 && got <= 1e-290 * (1.0 + t.error_estimate())));
    } else {
        REQUIRE(std::isfinite(got));
        CHECK(std::abs(got - want) <= t.error_estimate() * want);
        w.add(got, want);
    }
}

// E[q+] = int_0^inf q P2(q) dq = 2 int_0^inf r^2 P22(r^2) dr (P22 over the half plane q > 0 in polar coordinates):
// the limit of mu Lambda as mu -> 0, for GTR on Dimov's printed density in long double, split at alpha and 1, cut at
// r = 1e60 as ref::Lambda is. (The same integral at 50 digits agrees to 5e-17, at 100x the cost.)
double mean_positive_slope_gtr(double alpha, double gamma) {
    const long double c = static_cast<long double>(ref::gtr_c(alpha, gamma)),
                      a2 = static_cast<long double>(alpha) * alpha;
    const long double g = gamma, a = alpha, tol = 1e-17L;
    auto h = [&](long double r) {
        if (r > 1e60L) return 0.0L;
        const long double r2 = r * r;
        return r2 * c * std::pow(r2 + 1, g - 2) / std::pow(r2 + a2, g);
    };
    boost::math::quadrature::tanh_sinh<long double> ts;
    boost::math::quadrature::exp_sinh<long double> es;
    long double I = es.integrate(h, 1.0L, static_cast<long double>(INFINITY), tol);
    I += alpha < 1.0 ? ts.integrate(h, 0.0L, a, tol) + ts.integrate(h, a, 1.0L, tol) : ts.integrate(h, 0.0L, 1.0L, tol);
    return static_cast<double>(2 * I);
}

}  // namespace

TEST_CASE("table: every mu, GGX and Beckmann (closed forms), through Beckmann's underflow", "[table]") {
    Worst w;
    for (double alpha : {1e-50, 1e-4, 0.3, 1.0, 1e50}) {
        const Ggx g = ggx(alpha);
        const LambdaTable t = tabulate_Lambda(g);
        CHECK(t.error_estimate() <= 1e-6);
        CHECK(!t.underflows());
        for (double mu : extreme_mus) check_Lambda(t, mu, g.Lambda(mu), "ggx(" + std::to_string(alpha) + ")", w);
        for (double mu : grid::logspace(1e-6 * alpha, 1e6 * alpha, 29))
            check_Lambda(t, mu, g.Lambda(mu), "ggx(" + std::to_string(alpha) + ")", w);
    }
    for (double alpha : {1e-50, 1e-4, 0.3, 1.0}) {
        const Beckmann b = beckmann(alpha);
        const LambdaTable t = tabulate_Lambda(b);
        const std::string what = "beckmann(" + std::to_string(alpha) + ")";
        CHECK(t.error_estimate() <= 1e-6);
        // Lambda ~ exp(-a^2), a = mu/alpha, crosses 1e-290 near a = 25.8 and underflows near a = 27.3
        CHECK(t.underflows());
        CHECK(t.mu_max() > 25.0 * alpha);
        CHECK(t.mu_max() < 26.5 * alpha);
        for (double mu : extreme_mus) check_Lambda(t, mu, b.Lambda(mu), what, w);
        for (double mu : grid::logspace(1e-6 * alpha, 1e6 * alpha, 29)) check_Lambda(t, mu, b.Lambda(mu), what, w);
        for (int i = 0; i <= 40; ++i) {  // through the crossing and the underflow, a in [20, 28]
            const double mu = alpha * (20.0 + 0.2 * i);
            check_Lambda(t, mu, b.Lambda(mu), what, w);
        }
        CHECK(t.Lambda(28.0 * alpha) == 0.0);
    }
    // Beckmann(1e-50) underflows from mu ~ 3e-49: the whole spline lies below the default [1e-5, 1e5].
    CHECK(tabulate_Lambda(beckmann(1e-50)).mu_max() < 1e-48);
    WARN("table at every mu, GGX and Beckmann: worst relative dLambda " << w.rel);
    CHECK(w.rel <= 1e-6);
    CHECK(w.rel > 1e-10);  // a table, not the closed form in disguise
}

TEST_CASE("table: every mu, GTR at real gamma, against asymptotes with integrated constants and the other backend",
          "[table]") {
    Worst w;
    for (double gamma : {0.5, 1.5, 7.3})
        for (double alpha : {1e-4, 0.3, 1.0}) {
            const Gtr ndf = gtr(alpha, gamma);
            const LambdaTable t = tabulate_Lambda(ndf);  // from the 1D quadrature, Boost tanh-sinh
            const std::string what = "gtr(" + std::to_string(alpha) + ", " + std::to_string(gamma) + ")";
            CHECK(t.error_estimate() <= 1e-6);
            // mu -> 0: Lambda = E[q+]/mu - 1/2 + O(P2(0) mu), the remainder below 1e-16 relative at mu <= 1e-13.
            const double c0 = mean_positive_slope_gtr(alpha, gamma);
            for (double mu : {DBL_TRUE_MIN, 1e-300, 1e-100, 1e-20, 1e-13}) check_Lambda(t, mu, c0 / mu - 0.5, what, w);
            // mu -> inf: P22 ~ c r^-4 (Dimov's printed c), Lambda = (2/mu) int_mu^inf c r^-3 (sqrt(r^2 - mu^2) -
            // mu acos(mu/r)) dr (1 + O(gamma/mu^2)) = pi c / (4 mu^2) (1 + O(gamma/mu^2)).
            const double c = static_cast<double>(ref::gtr_c(alpha, gamma));
            for (double mu : {1e13, 1e50, 1e100, 1e140, 1e200, DBL_MAX})
                check_Lambda(t, mu, std::numbers::pi * c / 4.0 / mu / mu, what, w);
            // Between, the quadrature by the other backend (GSL), at points that are no knots.
            for (double mu : {1e-12, 3.1e-9, 1e-6, 0.013, 1.7, 1e5, 3.3e7, 1e12})
                check_Lambda(t, mu, Lambda_1d(ndf, mu, {Backend::gsl, 1e-12}), what, w);
            CHECK(t.Lambda(0.0) == INFINITY);
            CHECK(t.Lambda(INFINITY) == 0.0);
        }
    WARN("table at every mu, GTR gamma = 0.5, 1.5, 7.3: worst relative dLambda " << w.rel);
    CHECK(w.rel <= 1e-6);
    CHECK(w.rel > 1e-10);
}

TEST_CASE("table: every mu, Blinn-Phong: a power tail other than r^-4, continued with its own slope", "[table]") {
    // P22 = K (1 + r^2)^-(n+4)/2 ~ K r^-(n+4), K = (n+2)/(2 pi): with r = mu s, s = sec t,
    // Lambda = 2 mu^2 int_1^inf P22(mu^2 s^2) s (sqrt(s^2 - 1) - acos(1/s)) ds ~ 2 K J mu^-(n+2),
    // J = int_0^{pi/2} (cos^n t sin^2 t - t cos^(n+1) t sin t) dt = (B((n+1)/2, 3/2) - B((n+3)/2, 1/2)/(n+2)) / 2,
    // with a relative correction O(n/mu^2).
    Worst w;
    for (double n : {1.0, 20.0}) {
        const BlinnPhong ndf = blinn(n);
        const LambdaTable t = tabulate_Lambda(ndf);
        const std::string what = "blinn(" + std::to_string(n) + ")";
        CHECK(t.error_estimate() <= 1e-6);
        const double K = (n + 2.0) / (2.0 * std::numbers::pi);
        const double J = 0.5 * (std::beta((n + 1.0) / 2.0, 1.5) - std::beta((n + 3.0) / 2.0, 0.5) / (n + 2.0));
        for (double mu : {1e9, 1e12, 1e13, 1e20, 1e50, 1e100})
            check_Lambda(t, mu, 2.0 * K * J * std::pow(mu, -(n + 2.0)), what, w);
        for (double mu : {0.7, 1e3, 1e7, 1e12}) check_Lambda(t, mu, Lambda_1d(ndf, mu, {Backend::gsl, 1e-12}), what, w);
    }
    WARN("table at every mu, Blinn-Phong n = 1, 20: worst relative dLambda " << w.rel);
    CHECK(w.rel > 1e-12);
}

TEST_CASE("table: every mu, a D-only NDF (the quadrature of D alone) against the GGX closed form", "[table]") {
    Worst w;
    for (double alpha : {0.01, 0.3}) {
        const Ggx g = ggx(alpha);
        const LambdaTable t = tabulate_Lambda(DOnly<Ggx>{g});
        CHECK(t.error_estimate() <= 1e-6);
        for (double mu : extreme_mus) check_Lambda(t, mu, g.Lambda(mu), "D-only ggx(" + std::to_string(alpha) + ")", w);
    }
    WARN("table at every mu, D-only GGX: worst relative dLambda " << w.rel);
    CHECK(w.rel > 1e-12);
}

TEST_CASE("table: never calls its exact route after construction, and answers 0, inf, NaN and mu < 0", "[table]") {
    int calls = 0;
    const Ggx g = ggx(0.2);
    const LambdaTable t(
        [&](double mu) {
            ++calls;
            return g.Lambda(mu);
        },
        {});
    const int built = calls;
    CHECK(built > 100);
    double sum = 0.0;
    for (double mu : std::vector<double>{0.0, DBL_TRUE_MIN, 1e-300, 1e-12, 1e-7, 0.5, 1e7, 1e12, 1e300, DBL_MAX,
                                         INFINITY, -1.0, NAN})
        sum += t.G1(mu);
    CHECK(std::isnan(sum));  // G1(NaN)
    CHECK(calls == built);
    CHECK(t.Lambda(0.0) == INFINITY);
    CHECK(t.Lambda(DBL_TRUE_MIN) == INFINITY);  // 0.1 / 5e-324 overflows, as the closed form does
    CHECK(t.Lambda(INFINITY) == 0.0);
    CHECK(t.Lambda(DBL_MAX) == 0.0);
    CHECK(t.G1(0.0) == 0.0);
    CHECK(t.G1(INFINITY) == 1.0);
    CHECK(std::isnan(t.Lambda(NAN)));
    CHECK(std::isnan(t.Lambda(-2.0)));  // Lambda is for mu >= 0; downward is the caller's convention
    CHECK(t.G1(-2.0) == t.G1(2.0));
    // The spline covers at least the requested range, extended until the asymptotes hold.
    CHECK(t.mu_min() <= 1e-5);
    CHECK(t.mu_max() >= 1e5);
}

TEST_CASE("table: bad options and a bad exact route are errors that name the item", "[table]") {
    const Ggx g = ggx(0.3);
    auto message = [&](const LambdaTableOptions& o) {
        try {
            tabulate_Lambda(g, o);
        } catch (const input_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(message({.mu_min = 0.0}), Catch::Contains("mu_min"));
    CHECK_THAT(message({.mu_min = NAN}), Catch::Contains("mu_min"));
    CHECK_THAT(message({.mu_max = 1e-6}), Catch::Contains("mu_max"));
    CHECK_THAT(message({.tolerance = 0.0}), Catch::Contains("tolerance"));
    CHECK_THAT(message({.tolerance = 1e-16}), Catch::Contains("cannot tabulate"));
    CHECK_THROWS_WITH(LambdaTable([](double mu) { return mu > 10.0 ? NAN : 1.0 / mu; }, {}),
                      Catch::Contains("cannot tabulate") && Catch::Contains("mu = 1"));
    // Blinn-Phong n = 1e90 (slope scale 1.4e-45) by quadrature: Lambda underflows at every mu >= 1e-12 the
    // quadrature accepts, so its asymptote as mu -> 0 is out of reach. Refused, naming why.
    CHECK_THROWS_WITH(
        tabulate_Lambda(blinn(1e90)),
        Catch::Contains("cannot tabulate") && Catch::Contains("refuses mu") && Catch::Contains("mu -> 0"));
    // An exact route that refuses a mu the table needs, before an asymptote holds (GGX(1): mu Lambda is within 1e-7
    // of its limit below mu ~ 4e-4, and its slope settles near mu ~ 4e4).
    const Ggx one = ggx(1.0);
    auto refusing = [&](double lo, double hi) {
        return [&one, lo, hi](double mu) {
            if (mu < lo || mu > hi) throw input_error("mu out of range");
            return one.Lambda(mu);
        };
    };
    CHECK_THROWS_WITH(
        LambdaTable(refusing(1e-3, 1e10), {.mu_min = 0.01}),
        Catch::Contains("mu -> 0") && Catch::Contains("refuses mu") && Catch::Contains("mu out of range"));
    CHECK_THROWS_WITH(LambdaTable(refusing(1e-10, 1e3), {.mu_max = 10.0}),
                      Catch::Contains("mu -> inf") && Catch::Contains("refuses mu"));
    CHECK_THROWS_WITH(LambdaTable(refusing(1e-10, 1e3), {}), Catch::Contains("mu_min .. mu_max"));
    CHECK_NOTHROW(LambdaTable(refusing(1e-10, 1e10), {.mu_min = 0.01, .mu_max = 10.0}));
}
