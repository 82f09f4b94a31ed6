// The Student's t-distribution of slopes (Ribardiere, Bringier, Meneveaux, Simonot 2017): its special cases (GGX at
// gamma = 2, Beckmann as gamma -> inf), its normalization, the closed-form Lambda against the 50-digit reference (the
// r-form quadrature of the slope law as printed, reference.hpp) and against smithlab's 1D quadrature, its asymptotes
// and the seams between its forms, its D cos survival function and inverse, and bad parameters.
// Relative error of Lambda throughout: G1 near 1 hides everything.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <limits>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <string>
#include <vector>

#include "grid.hpp"
#include "reference.hpp"

using smithlab::student;
using smithlab::StudentT;

namespace {

double rel(double got, double want) { return got == want ? 0.0 : std::abs(got - want) / std::abs(want); }

// E[q+] / alpha for the STD's slope marginal: q = (alpha / sqrt 2) T, T Student's t with n = 2 gamma - 2 degrees of
// freedom, E[T+] = sqrt(n) Gamma((n - 1)/2) / (2 sqrt(pi) Gamma(n/2)) -- the limit of mu Lambda as mu -> 0 (Walter 2007
// eq. 48: mu Lambda = E[(q - mu)+]).
double mean_positive_slope(double gamma) {
    const double g = gamma - 1.0;
    return std::sqrt(g) * std::exp(std::lgamma(gamma - 1.5) - std::lgamma(g)) / (2.0 * std::sqrt(std::numbers::pi));
}

}  // namespace

TEST_CASE("student: gamma = 2 is GGX of the same alpha (D, P22, Lambda, D cos law)", "[student]") {
    double worst_D = 0.0, worst_L = 0.0;
    for (double a : {1e-4, 0.01, 0.3, 1.0, 1e10}) {
        const StudentT s = student(a, 2.0);
        const smithlab::Ggx g = smithlab::ggx(a);
        CHECK(s.ggx_alpha() == a);
        for (double c : {1.0, 1.0 - 1e-12, 0.99, 0.5, 0.1, 1e-3, 1e-30}) {
            INFO("alpha=" << a << " cos=" << c);
            worst_D = std::max(worst_D, rel(s.D(c), g.D(c)));
            CHECK(rel(s.D(c), g.D(c)) < 2e-14);
        }
        for (double r2 : {0.0, 1e-20, 1e-8, 0.09, 1.0, 1e6, 1e100}) {
            INFO("alpha=" << a << " r2=" << r2);
            CHECK(rel(s.slope_density(r2), g.slope_density(r2)) < 2e-14);
            CHECK(rel(s.Dcos_sf(r2), g.Dcos_sf(r2)) < 2e-14);
        }
        for (double v : {1e-300, 1e-16, 0.1, 0.5, 1.0 - 1e-12, 1.0}) {
            INFO("alpha=" << a << " v=" << v);
            CHECK(rel(s.Dcos_r2(v), g.Dcos_r2(v)) < 2e-14);
        }
        for (double z : grid::logspace(1e-8, 1e8, 65)) {
            INFO("alpha=" << a << " z=" << z);
            const double mu = z * a;
            worst_L = std::max(worst_L, rel(s.Lambda(mu), g.Lambda(mu)));
            CHECK(rel(s.Lambda(mu), g.Lambda(mu)) < 5e-15);
        }
    }
    WARN("gamma = 2 against GGX: worst relative D " << worst_D << ", Lambda " << worst_L);
    CHECK(std::isnan(student(0.3, 2.0 + 1e-12).ggx_alpha()));
    CHECK(std::isnan(student(0.3, 3.0).ggx_alpha()));
    // ... and the registry's GGX capability follows it: the closed-form visible normals apply at gamma = 2 only.
    const smithlab::NdfRegistry r = smithlab::builtin_registry();
    CHECK(smithlab::ggx_alpha(r.make("student(alpha=0.3, gamma=2)")) == 0.3);
    CHECK(std::isnan(smithlab::ggx_alpha(r.make("student(alpha=0.3, gamma=2.5)"))));
}

TEST_CASE("student: as gamma grows, P22 and Lambda tend to Beckmann's, the gap shrinking as 1/gamma", "[student]") {
    // P22 / P22_Beckmann - 1 = (x^2 / 2 - x) / (gamma - 1) + O(gamma^-2) at x = r^2 / alpha^2 (log1p's series).
    double previous = INFINITY;
    for (double gm : {1e3, 1e4, 1e5, 1e6}) {
        const double a = 0.3;
        const StudentT s = student(a, gm);
        const smithlab::Beckmann b = smithlab::beckmann(a);
        for (double x : {0.25, 1.0, 4.0}) {
            const double want = (x * x / 2 - x) / (gm - 1.0);
            INFO("gamma=" << gm << " x=" << x);
            CHECK(s.slope_density(x * a * a) / b.slope_density(x * a * a) - 1.0 == Approx(want).epsilon(10.0 / gm));
        }
        double gap = 0.0;
        for (double z : grid::logspace(0.05, 4.0, 30)) gap = std::max(gap, rel(s.Lambda(z * a), b.Lambda(z * a)));
        INFO("gamma=" << gm << ": max relative gap to Beckmann's Lambda over z in [0.05, 4]: " << gap);
        CHECK(gap < 200.0 / gm);  // measured ~150 / gamma, at z = 4 (Beckmann's e^-16 tail against the t's)
        CHECK(gap < previous / 5.0);
        previous = gap;
    }
}

TEST_CASE("student: normalized, its D cos law sums to 1, and D is P22 / cos^4", "[student]") {
    for (double a : {1e-3, 0.3, 1.0, 3.0})
        for (double gm : {1.65, 2.5, 10.0, 1e3, 1e6}) {
            const StudentT s = student(a, gm);
            INFO("alpha=" << a << " gamma=" << gm);
            CHECK(smithlab::projected_area(s) == Approx(1.0).epsilon(1e-9));
            CHECK(s.Dcos_sf(0.0) == 1.0);
            CHECK(s.Dcos_r2(1.0) == 0.0);
            for (double c : {1.0, 0.9, 0.5, 0.2, 0.01}) {
                const double r2 = (1.0 - c) * (1.0 + c) / (c * c);
                CHECK(s.D(c) == Approx(s.slope_density(r2) / std::pow(c, 4)).epsilon(1e-13).margin(1e-300));
            }
        }
    // D at and beyond the horizon; finite (growing like cos^(2 gamma - 4)) for gamma < 2, 0 in the limit for gamma > 2.
    const StudentT heavy = student(0.3, 1.65), light = student(0.3, 30.0);
    for (double c : {1e-10, 1e-100, 1e-200, 1e-300}) {
        INFO("cos=" << c);
        CHECK(std::isfinite(heavy.D(c)));
        CHECK(heavy.D(c) > heavy.D(0.5));
        CHECK(std::isfinite(light.D(c)));
        CHECK(light.D(c) >= 0.0);
    }
    CHECK(heavy.D(0.0) == 0.0);
    CHECK(heavy.D(-0.5) == 0.0);
    CHECK(heavy.slope_density(INFINITY) == 0.0);
    CHECK(heavy.slope_density(DBL_MAX) >= 0.0);
    CHECK(heavy.Dcos_sf(INFINITY) == 0.0);
    CHECK(heavy.Dcos_r2(1e-300) > 1e300);  // the inverse of a heavy tail: a slope of 1e800 would overflow, 5e-300 is ok
    CHECK(std::isfinite(heavy.Dcos_r2(5e-300)) == (heavy.Dcos_r2(5e-300) < INFINITY));
}

TEST_CASE("student: closed-form Lambda against the 50-digit reference, z = mu / alpha from 1e-8 to 1e200",
          "[student][slow]") {
    // The reference integrates the slope law as printed in the r-form, to infinity (Lambda_uncut: the r^(-2 gamma) tail
    // at gamma = 1.65 leaves 1e-18 beyond the usual cut, 1e-12 at 1.6); no double-precision route of smithlab takes
    // part.
    double worst = 0.0;
    std::string worst_at;
    auto check = [&](double a, double gm, double z) {
        const double mu = z * a;
        const ref::real want = ref::Lambda_uncut(ref::student_t(a, gm), mu);
        const double got = student(a, gm).Lambda(mu);
        INFO("alpha=" << a << " gamma=" << gm << " mu=" << mu << " z=" << z << ": got " << got << ", want "
                      << static_cast<double>(want));
        CHECK(ref::close(got, want, 1e-14));
        if (want >= DBL_MIN && ref::rel_err(got, want) > worst) {
            worst = ref::rel_err(got, want);
            worst_at = "alpha=" + std::to_string(a) + " gamma=" + std::to_string(gm) + " z=" + std::to_string(z);
        }
    };
    const std::vector<double> zs = {1e-8, 1e-3, 0.1, 0.5, 0.69, 0.7, 0.71, 1.0, 1.5, 3.0, 8.0, 40.0, 1e3, 1e6};
    for (double a : {1e-4, 0.3, 1.0})
        for (double gm : {1.65, 1.75, 2.5, 4.0, 10.0, 30.0, 100.0, 1e4, 1e6})
            for (double z : zs) check(a, gm, z);
    // The extremes of alpha (Lambda depends on z alone, but mu / alpha is carried to double-double from the inputs).
    for (double a : {1e-50, 1e50})
        for (double z : {1e-3, 0.5, 2.0, 1e3}) check(a, 3.3, z);
    // Past z = 1e100 (the far-tail form that never squares z): the heavy tails, where Lambda ~ z^(2 - 2 gamma) is still
    // above DBL_MIN; and 1.2e154, where z^2 overflows.
    for (double gm : {1.65, 1.75, 2.0})
        for (double z : {1e99, 1.0000001e100, 1.2e154, 1e200}) check(1e-4, gm, z);
    WARN("closed-form Lambda against the 50-digit reference: worst relative error " << worst << " at " << worst_at);
}

TEST_CASE("student: closed-form Lambda against smithlab's 1D quadrature at random points", "[student]") {
    smithlab::Rng g = smithlab::make_rng(1417);
    auto log_uniform = [&](double lo, double hi) {
        return std::exp(std::log(lo) + (std::log(hi) - std::log(lo)) * smithlab::uniform01(g));
    };
    double worst = 0.0;
    for (int i = 0; i < 1500; ++i) {
        const double a = log_uniform(1e-4, 1.0);
        const double gm = i % 2 ? 1.65 + 8.35 * smithlab::uniform01(g) : log_uniform(1.65, 1e4);
        const double mu = a * log_uniform(1e-6, 1e6);
        const StudentT s = student(a, gm);
        const double q = smithlab::Lambda_1d(s, mu, {smithlab::Backend::boost, 1e-13});
        INFO("alpha=" << a << " gamma=" << gm << " mu=" << mu << ": " << s.Lambda(mu) << " against " << q);
        if (q < 1e-290) {  // (nearly) denormal: both are (nearly) 0
            CHECK(s.Lambda(mu) < 1e-289);
            continue;
        }
        CHECK(rel(s.Lambda(mu), q) < 1e-11);
        worst = std::max(worst, rel(s.Lambda(mu), q));
    }
    WARN("closed form against Boost 1D quadrature at 1e-13: worst relative difference " << worst);
}

TEST_CASE("student: Lambda's asymptotes, its seams, and its order in mu and gamma", "[student]") {
    for (double gm : {1.65, 2.0, 3.7, 20.0, 1e4}) {
        const double a = 0.05;
        const StudentT s = student(a, gm);
        INFO("gamma=" << gm);
        // mu -> 0: mu Lambda + mu / 2 -> E[q+] (the mean positive slope), with an error ~ mu^2 / alpha.
        const double c0 = mean_positive_slope(gm) * a;
        for (double z : {1e-6, 1e-9, 1e-12}) CHECK(rel(z * a * s.Lambda(z * a) + z * a / 2, c0) < 1e-12 + 10 * z);
        // mu -> inf: Lambda ~ C mu^(2 - 2 gamma) (P2 ~ q^(1 - 2 gamma)), checked as the slope of ln Lambda, across
        // the seam at z = 1e100 where the far-tail form takes over. Where Lambda underflows it is 0.
        for (double z : {1e30, 1e60, 1e95, 1e110}) {
            const double l1 = s.Lambda(z * a), l2 = s.Lambda(1.5 * z * a);
            if (l2 < 1e-280) {
                CHECK(l2 >= 0.0);
                continue;
            }
            CHECK(std::log(l2 / l1) / std::log(1.5) == Approx(2.0 - 2.0 * gm).epsilon(1e-10));
        }
        // The seams between the forms (X up to z = 0.7, Y beyond, the far tail past 1e100): one ulp in mu moves
        // Lambda by its sensitivity times 1e-16, nothing more.
        for (double z : {0.7, 1e100}) {
            const double mu = z * a, below = std::nextafter(mu, 0.0), above = std::nextafter(mu, INFINITY);
            const double sens = 2.0 * gm;  // |d ln Lambda / d ln mu| <= 2 gamma - 1
            CHECK(rel(s.Lambda(below), s.Lambda(mu)) < sens * 4e-16 + 2e-15);
            CHECK(rel(s.Lambda(above), s.Lambda(mu)) < sens * 4e-16 + 2e-15);
        }
        // decreasing in mu
        double previous = INFINITY;
        for (double z : grid::logspace(1e-6, 1e6, 241)) {
            const double l = s.Lambda(z * a);
            CHECK((l < previous || l == 0.0));  // until it underflows
            previous = l;
        }
    }
    // At fixed z, Lambda decreases with gamma towards Beckmann's (the seam at z = 0.7 relies on Lambda >= 0.0857).
    for (double z : {0.1, 0.3, 0.5, 0.7, 1.0, 2.0, 5.0}) {
        double previous = INFINITY;
        for (double gm : {1.65, 2.0, 3.0, 5.0, 10.0, 100.0, 1e4, 1e6}) {
            const double l = student(1.0, gm).Lambda(z);
            INFO("z=" << z << " gamma=" << gm);
            CHECK(l < previous);
            CHECK(l > smithlab::beckmann(1.0).Lambda(z));
            previous = l;
        }
    }
    CHECK(student(1.0, 1e6).Lambda(0.7) > 0.0857);
    CHECK(smithlab::beckmann(1.0).Lambda(0.7) > 0.0857);
    // The ends of double: no NaN; +inf where Lambda ~ 1/z overflows, 0 where it underflows.
    for (double a : {1e-50, 1e-4, 1.0, 1e50})
        for (double gm : {1.65, 4.0, 1e6})
            for (double mu : {DBL_TRUE_MIN, DBL_MIN, 1e-300, 1.0, 1e300, DBL_MAX}) {
                const double l = student(a, gm).Lambda(mu);
                INFO("alpha=" << a << " gamma=" << gm << " mu=" << mu << ": " << l);
                CHECK(l >= 0.0);  // NaN fails too
            }
    CHECK(student(1e50, 3.0).Lambda(1e-300) == INFINITY);  // z = 1e-350 underflows: Lambda = 1e350 c0 overflows
    CHECK(student(1e-4, 3.0).Lambda(DBL_MAX) == 0.0);
    // G1 and Lambda through the generic engine take the closed form (method auto), 0 and inf included
    const StudentT s = student(0.3, 3.0);
    CHECK(smithlab::Lambda(s, 0.0) == INFINITY);
    CHECK(smithlab::Lambda(s, INFINITY) == 0.0);
    CHECK(smithlab::G1(s, 0.5) == 1.0 / (1.0 + s.Lambda(0.5)));
}

TEST_CASE("student: bad parameters are refused, naming them", "[student]") {
    CHECK_THROWS_WITH(student(0.0, 2.0), Catch::Contains("student: alpha"));
    CHECK_THROWS_WITH(student(2e50, 2.0), Catch::Contains("student: alpha"));
    CHECK_THROWS_WITH(student(NAN, 2.0), Catch::Contains("student: alpha"));
    CHECK_THROWS_WITH(student(0.3, 1.5), Catch::Contains("student: gamma"));
    CHECK_THROWS_WITH(student(0.3, 1.64), Catch::Contains("student: gamma") && Catch::Contains("[1.65, 1e6]"));
    CHECK_THROWS_WITH(student(0.3, 1.1e6), Catch::Contains("student: gamma"));
    CHECK_THROWS_WITH(student(0.3, NAN), Catch::Contains("student: gamma"));
    CHECK_NOTHROW(student(1e-50, 1.65));
    CHECK_NOTHROW(student(1e50, 1e6));
    const smithlab::NdfRegistry r = smithlab::builtin_registry();
    CHECK_THROWS_WITH(r.make("student(alpha=0.3)"), Catch::Contains("missing parameter 'gamma'"));
    CHECK_THROWS_WITH(r.make("student(alpha=0.3, gamma=1)"), Catch::Contains("student: gamma"));
    CHECK(r.make("student(gamma=3, alpha=0.3)").spec() == "student(alpha=0.3, gamma=3)");
}
