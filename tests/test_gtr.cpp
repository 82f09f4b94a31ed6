// GTR: normalization constant limits, D against Burley's printed form, Dimov's spline against GSL's natural spline.
#include <gsl/gsl_interp.h>

#include <catch2/catch.hpp>
#include <smithlab/gtr.hpp>

#include "closed_forms_plain.hpp"  // the straightforward evaluation of the closed forms and the spline
#include "reference.hpp"

TEST_CASE("GTR D matches Burley/Dimov's printed D at 50 digits, gamma -> 1 and alpha -> 1 included", "[gtr]") {
    for (double a : {1e-4, 0.1, 0.5, 0.999999, 1.0})
        for (double g : {0.0, 0.5, 1.0 - 1e-10, 1.0, 1.0 + 1e-10, 2.0, 3.7, 10.0})
            for (double c : {1.0, 0.99999999, 0.9, 0.5, 0.1, 0.0}) {
                const ref::real want = ref::gtr_D(a, g, c);
                const double got = smithlab::gtr(a, g).D(c);
                INFO("alpha=" << a << " gamma=" << g << " cos=" << c);
                CHECK(ref::rel_err(got, want) <= 1e-13);
            }
}

TEST_CASE("GTR normalization constant is continuous through gamma = 1 and tends to 1/pi at alpha = 1", "[gtr]") {
    const double pi = 3.14159265358979323846;
    for (double a : {1e-4, 0.3, 0.9}) {
        const double k1 = smithlab::gtr_K(a, 1.0);
        CHECK(smithlab::gtr_K(a, 1.0 + 1e-12) == Approx(k1).epsilon(1e-11));
        CHECK(smithlab::gtr_K(a, 1.0 - 1e-12) == Approx(k1).epsilon(1e-11));
    }
    for (double g : {0.0, 1.0, 2.0, 7.0}) CHECK(smithlab::gtr_K(1.0 - 1e-12, g) * pi == Approx(1.0).epsilon(1e-11));
    CHECK(smithlab::gtr_K(1.0, 3.0) * pi == 1.0);
}

TEST_CASE("Dimov's spline is GSL's natural cubic spline through the closed-form G1 at gamma = 0..4", "[gtr][spline]") {
    const double knots_x[5] = {0, 1, 2, 3, 4};
    gsl_interp* interp = gsl_interp_alloc(gsl_interp_cspline, 5);  // natural boundary conditions
    gsl_interp_accel* acc = gsl_interp_accel_alloc();
    for (double a : {0.05, 0.3, 0.8})
        for (double mu : {0.05, 0.5, 3.0}) {
            double y[5];
            for (int k = 0; k < 5; ++k) y[k] = 1.0 / (1.0 + smithlab::gtr(a, k).Lambda(mu));
            gsl_interp_init(interp, knots_x, y, 5);
            for (double g = 0.0; g <= 4.0; g += 0.125) {
                INFO("alpha=" << a << " mu=" << mu << " gamma=" << g);
                CHECK(smithlab::G1_gtr_dimov_spline(a, g, mu) ==
                      Approx(gsl_interp_eval(interp, knots_x, y, g, acc)).epsilon(1e-14).margin(1e-15));
            }
            // Dimov 2015 sec. 6: clamped to gamma = 4 above.
            CHECK(smithlab::G1_gtr_dimov_spline(a, 9.5, mu) == smithlab::G1_gtr_dimov_spline(a, 4.0, mu));
        }
    gsl_interp_accel_free(acc);
    gsl_interp_free(interp);
}

TEST_CASE("Dimov's spline is a baseline, not the truth: its error away from the knots is visible", "[gtr][spline]") {
    // At gamma = 0.5 and 2.5 the spline is off the quadrature G1 by more than 1e-6 somewhere; at the knots it is exact.
    double max_off = 0.0;
    for (double a : {0.1, 0.5})
        for (double mu : {0.1, 1.0}) {
            for (double g : {0.5, 2.5}) {
                const auto ndf = smithlab::gtr(a, g);
                smithlab::LambdaOptions spline{.method = smithlab::Method::spline};
                max_off = std::max(max_off, std::abs(smithlab::G1(ndf, mu, spline) - smithlab::G1(ndf, mu)));
            }
            // At a knot the spline is G1 itself, to rounding. (Its Lambda = (1 - G1)/G1 then loses digits where
            // G1 is near 1: interpolating G1 rather than Lambda is the baseline's weakness, measured in the report.)
            const auto knot = smithlab::gtr(a, 3.0);
            CHECK(smithlab::G1_gtr_dimov_spline(a, 3.0, mu) == Approx(1.0 / (1.0 + knot.Lambda(mu))).epsilon(1e-15));
        }
    CHECK(max_off > 1e-6);
    WARN("Dimov spline max |dG1| on the test points: " << max_off);
}

TEST_CASE("Dimov's spline gives the values of its straightforward evaluation to a few ulp", "[gtr][spline]") {
    // Against the straightforward evaluation (closed_forms_plain.hpp), at random (alpha, gamma, mu)
    // over alpha in [1e-4, 1], gamma in [0, 6] (the clamp above 4 included), mu in [1e-6, 1e6], and at the stiff
    // corners: mu at 1e-300, 1e-100, 1e50 .. 1e300 (the asymptotes), alpha = 1e-4 and 1, the knots themselves.
    // G1 is compared in absolute terms (it lies in about [-0.1, 1.1]), in units of 2^-53.
    std::mt19937_64 rng(14);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::array<double, 3>> points;
    for (int i = 0; i < 20000; ++i)
        points.push_back({std::pow(10.0, -4.0 * u(rng)), 6.0 * u(rng), std::pow(10.0, 12.0 * u(rng) - 6.0)});
    for (double a : {1e-4, 0.3, 0.999999, 1.0})
        for (double g : {0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 9.0})
            for (double mu : {1e-300, 1e-100, 1e-50, 1e-8, 1e-4, 1.0, 1e4, 1e8, 1e50, 1e60, 1e100, 1e200, 1e300})
                points.push_back({a, g, mu});
    double worst = 0.0;
    for (const auto& [a, g, mu] : points) {
        const double now = smithlab::G1_gtr_dimov_spline(a, g, mu),
                     plain = smithlab_plain::G1_gtr_dimov_spline(a, g, mu);
        INFO("alpha=" << a << " gamma=" << g << " mu=" << mu << " now " << now << " plain " << plain);
        const double ulps = std::abs(now - plain) / 0x1p-53;
        CHECK(ulps <= 16.0);
        worst = std::max(worst, ulps);
    }
    WARN("Dimov's spline, largest change in G1: " << worst << " x 2^-53");
}

TEST_CASE("the generated integer-gamma forms give the incomplete-beta route's Lambda", "[gtr][closed]") {
    // gamma = 5..31 (Lambda_gtr_integer_sum) against closed_forms_plain.hpp's brackets from the incomplete beta
    // function, at random (alpha, mu) over alpha in [1e-4, 1], mu in [1e-6, 1e6] and at the corners. The plain route
    // cancels by up to a factor 2k + 2 where mu >> alpha: a relative 1e-13 bounds both.
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::array<double, 2>> points;
    for (int i = 0; i < 400; ++i)
        points.push_back({std::pow(10.0, -4.0 * u(rng)), std::pow(10.0, 12.0 * u(rng) - 6.0)});
    for (double a : {1e-4, 0.3, 0.999999, 1.0})
        for (double mu : {1e-90, 1e-8, 1e-4, 0.3, 1.0, 1e4, 1e8, 1e90}) points.push_back({a, mu});
    double worst = 0.0;
    for (int g = 5; g <= smithlab::gtr_max_closed_gamma; ++g)
        for (const auto& [a, mu] : points) {
            const double now = smithlab::Lambda_gtr_closed(a, g, mu),
                         plain = smithlab_plain::Lambda_gtr_closed(a, g, mu);
            INFO("alpha=" << a << " gamma=" << g << " mu=" << mu << " now " << now << " plain " << plain);
            // Where Lambda is below the normal range (alpha = 1e-4, gamma = 20, mu = 1e90: K mu^-2 ~ 1e-332) both
            // round to the same few subnormal bits or to 0; a relative comparison needs normal numbers.
            if (plain < 0x1p-970) {
                CHECK(now < 0x1p-970);
                continue;
            }
            const double rel = std::abs(now - plain) / plain;
            CHECK(rel <= 1e-13);
            worst = std::max(worst, rel);
        }
    WARN("gamma 5..31 against the incomplete-beta route: largest relative difference in Lambda " << worst);
}
