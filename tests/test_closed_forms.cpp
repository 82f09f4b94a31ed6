// Closed forms in double against Dimov's printed forms (and the textbook Beckmann form) at 50 digits.
// Relative error of Lambda, not G1 (G1 near 1 hides everything). Target: 1e-13 everywhere.
#include <catch2/catch.hpp>
#include <cfloat>
#include <smithlab/smithlab.hpp>

#include "grid.hpp"
#include "reference.hpp"

namespace {
void check_value(double got, const ref::real& want, double tol) {
    INFO("got " << got << ", want " << static_cast<double>(want));
    CHECK(ref::close(got, want, tol));
}
}  // namespace

TEST_CASE("GTR closed forms, gamma = 0..4, agree with Dimov's printed forms at 50 digits", "[closed]") {
    double worst = 0.0;
    for (int gamma = 0; gamma <= 4; ++gamma)
        for (double alpha : grid::alphas)
            for (double mu : grid::mus) {
                const smithlab::Gtr ndf = smithlab::gtr(alpha, gamma);
                // At alpha = 1 every gamma is the uniform D (gamma = 1's printed form is 0/0 there).
                const ref::real want = ref::Lambda_dimov(alpha == 1.0 ? 0 : gamma, alpha, mu);
                const double got = ndf.Lambda(mu);
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                check_value(got, want, 1e-13);
                worst = std::max(worst, ref::rel_err(got, want));
            }
    WARN("worst relative error of the GTR closed forms: " << worst);
}

TEST_CASE("GTR closed forms hold near the removable singularities gamma -> 1, alpha -> 1", "[closed]") {
    for (double alpha : {0.9999, 0.99999999, 1.0 - 1e-13})
        for (double mu : {1e-3, 1.0, 1e3}) {
            INFO("alpha=" << alpha << " mu=" << mu);
            check_value(smithlab::gtr(alpha, 1).Lambda(mu), ref::Lambda_dimov(1, alpha, mu), 1e-13);
            check_value(smithlab::gtr(alpha, 3).Lambda(mu), ref::Lambda_dimov(3, alpha, mu), 1e-13);
        }
}

TEST_CASE("GGX closed form equals GTR gamma = 2 at 50 digits", "[closed]") {
    for (double alpha : grid::alphas)
        for (double mu : grid::mus) {
            INFO("alpha=" << alpha << " mu=" << mu);
            check_value(smithlab::ggx(alpha).Lambda(mu), ref::Lambda_dimov(2, alpha, mu), 1e-13);
        }
}

TEST_CASE("Beckmann closed form against the textbook form at 50 digits, through its underflow", "[closed]") {
    double worst = 0.0;
    for (double alpha : grid::alphas)
        for (double mu : grid::mus) {
            const ref::real want = ref::Lambda_beckmann(alpha, mu);
            const double got = smithlab::beckmann(alpha).Lambda(mu);
            INFO("alpha=" << alpha << " mu=" << mu);
            check_value(got, want, 1e-13);
            if (want >= DBL_MIN) worst = std::max(worst, ref::rel_err(got, want));
        }
    // a = mu/alpha across the switch to the asymptotic series (a = 6) and up to the underflow of exp(-a^2).
    for (double a = 0.5; a < 27.0; a += 0.37) {
        const double alpha = 0.1, mu = a * alpha;
        INFO("a=" << a);
        check_value(smithlab::beckmann(alpha).Lambda(mu), ref::Lambda_beckmann(alpha, mu), 1e-13);
    }
    WARN("worst relative error of the Beckmann closed form: " << worst);
}

TEST_CASE("generated closed forms for integer gamma: equal to Dimov's printed forms at gamma = 2, 3, 4", "[closed][generated]") {
    for (int gamma = 2; gamma <= 4; ++gamma)
        for (double alpha : grid::alphas)
            for (double mu : grid::mus) {
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                check_value(smithlab::Lambda_gtr_integer_sum(alpha, gamma, mu),
                            ref::Lambda_dimov(alpha == 1.0 ? 0 : gamma, alpha, mu), 1e-13);
            }
}

TEST_CASE("generated closed forms for integer gamma up to 31 against the 50-digit quadrature", "[closed][generated][slow]") {
    double worst = 0.0;
    for (int gamma : {5, 7, 10, 20, 31})
        for (double alpha : {1e-4, 0.01, 0.1, 0.3, 0.999999, 1.0})
            for (double mu : {1e-4, 1e-2, 0.031622776601683798, 1.0, 1e2, 1e4}) {  // 0.0316: the report's worst
                const ref::real want = ref::Lambda(ref::gtr(alpha, gamma), mu);
                const double got = smithlab::gtr(alpha, gamma).Lambda(mu);
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                check_value(got, want, 1e-13);
                if (want >= DBL_MIN) worst = std::max(worst, ref::rel_err(got, want));
            }
    WARN("worst relative error of the generated closed forms: " << worst);
    CHECK(smithlab::gtr_has_closed_form(31.0));
    CHECK_FALSE(smithlab::gtr_has_closed_form(32.0));
    CHECK_THROWS_AS(smithlab::Lambda_gtr_integer_sum(0.3, 32, 1.0), smithlab::input_error);
}
