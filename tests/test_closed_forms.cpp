// Closed forms in double against Dimov's printed forms (and the textbook Beckmann form) at 50 digits.
// Relative error of Lambda, not G1 (G1 near 1 hides everything). Target: 1e-13 everywhere.
#include <catch2/catch.hpp>
#include <cfloat>
#include <smithlab/gtr.hpp>

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

TEST_CASE("generated closed forms for integer gamma: equal to Dimov's printed forms at gamma = 2, 3, 4",
          "[closed][generated]") {
    for (int gamma = 2; gamma <= 4; ++gamma)
        for (double alpha : grid::alphas)
            for (double mu : grid::mus) {
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                check_value(smithlab::Lambda_gtr_integer_sum(alpha, gamma, mu),
                            ref::Lambda_dimov(alpha == 1.0 ? 0 : gamma, alpha, mu), 1e-13);
            }
}

TEST_CASE("generated closed forms for integer gamma up to 31 against the 50-digit quadrature",
          "[closed][generated][slow]") {
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

// G1 directly (one division fewer than through Lambda), and Lambda and G1 from c = cos(theta) rather than
// mu = cot(theta), against the same 50-digit references. The reference is taken at mu = c / sqrt((1 - c)(1 + c))
// rounded to double (a few ulp off the exact cot; Lambda's relative sensitivity to mu is at most 2, so the reference
// moves by ~1e-15, far inside 1e-13). The stiff corners: c -> 0 (grazing, Lambda -> inf), c -> 1 (normal, s2 -> 0),
// the smallest alpha of the grid (1e-4) and alpha = 1.
namespace {
const std::vector<double> cosines = {1e-300,
                                     1e-120,
                                     1e-100,
                                     1e-30,
                                     1e-8,
                                     1e-4,
                                     1e-2,
                                     0.1,
                                     0.3,
                                     0.5,
                                     0.7,
                                     0.9,
                                     0.999,
                                     1.0 - 1e-6,
                                     1.0 - 1e-9,
                                     1.0 - 1e-12,
                                     1.0 - 1.1102230246251565e-16};
double mu_of(double c) { return c / std::sqrt((1.0 - c) * (1.0 + c)); }
}  // namespace

TEST_CASE("G1 of the closed forms, from mu, at 50 digits (GGX, GTR gamma = 0..4)", "[closed][g1]") {
    double worst = 0.0;
    for (int gamma = 0; gamma <= 4; ++gamma)
        for (double alpha : grid::alphas)
            for (double mu : grid::mus) {
                const ref::real L = ref::Lambda_dimov(alpha == 1.0 ? 0 : gamma, alpha, mu), want = 1 / (1 + L);
                INFO("gamma=" << gamma << " alpha=" << alpha << " mu=" << mu);
                const double got = smithlab::G1_gtr_closed(alpha, gamma, mu);
                check_value(got, want, 1e-13);
                worst = std::max(worst, ref::rel_err(got, want));
                if (gamma == 2) check_value(smithlab::ggx(alpha).G1(mu), want, 1e-13);
            }
    WARN("worst relative error of G1 from mu, gamma = 0..4: " << worst);
    CHECK(smithlab::ggx(0.3).G1(INFINITY) == 1.0);
    CHECK(smithlab::ggx(0.3).G1(1e200) == 1.0);
}

TEST_CASE("Lambda and G1 from cos(theta): GGX and GTR gamma = 0..4 at 50 digits, c -> 0 and c -> 1 included",
          "[closed][cos]") {
    double worst_L = 0.0, worst_G = 0.0;
    for (int gamma = 0; gamma <= 4; ++gamma)
        for (double alpha : grid::alphas)
            for (double c : cosines) {
                const double mu = mu_of(c);
                const ref::real L = ref::Lambda_dimov(alpha == 1.0 ? 0 : gamma, alpha, mu), G = 1 / (1 + L);
                const smithlab::Gtr ndf = smithlab::gtr(alpha, gamma);
                INFO("gamma=" << gamma << " alpha=" << alpha << " c=" << c << " mu=" << mu);
                const double got_L = smithlab::Lambda_from_cos(ndf, c), got_G = smithlab::G1_from_cos(ndf, c);
                check_value(got_L, L, 1e-13);
                check_value(got_G, G, 1e-13);
                worst_L = std::max(worst_L, ref::rel_err(got_L, L));
                worst_G = std::max(worst_G, ref::rel_err(got_G, G));
                if (gamma == 2) {
                    const smithlab::Ggx ggx = smithlab::ggx(alpha);
                    check_value(smithlab::Lambda_from_cos(ggx, c), L, 1e-13);
                    check_value(smithlab::G1_from_cos(ggx, c), G, 1e-13);
                }
            }
    WARN("worst relative error from cos: Lambda " << worst_L << ", G1 " << worst_G);
}

TEST_CASE("Lambda and G1 from cos(theta): the ends, the sign, and every other NDF through mu", "[closed][cos]") {
    const smithlab::Ggx ggx = smithlab::ggx(0.2);
    for (int gamma = 0; gamma <= 5; ++gamma) {
        const smithlab::Gtr ndf = smithlab::gtr(0.2, gamma);
        INFO("gamma=" << gamma);
        CHECK(smithlab::Lambda_from_cos(ndf, 1.0) == 0.0);
        CHECK(smithlab::G1_from_cos(ndf, 1.0) == 1.0);
        CHECK(smithlab::Lambda_from_cos(ndf, 0.0) == INFINITY);
        CHECK(smithlab::G1_from_cos(ndf, 0.0) == 0.0);
        CHECK(smithlab::Lambda_from_cos(ndf, 1.0 + 1e-15) == 0.0);  // rounding above 1 reads as 1
        // Below the surface: G1 takes |c| (Walter 2007 eq. 44), Lambda is Smith's -1 - Lambda(|c|), as for mu.
        CHECK(smithlab::G1_from_cos(ndf, -0.4) == smithlab::G1_from_cos(ndf, 0.4));
        CHECK(smithlab::Lambda_from_cos(ndf, -0.4) == Approx(smithlab::Lambda(ndf, -mu_of(0.4))).epsilon(1e-15));
        CHECK(smithlab::Lambda_from_cos(ndf, -0.4) ==
              Approx(-1.0 - smithlab::Lambda_from_cos(ndf, 0.4)).epsilon(1e-15));
    }
    CHECK(smithlab::Lambda_from_cos(ggx, 1.0) == 0.0);
    CHECK(smithlab::G1_from_cos(ggx, 1.0) == 1.0);
    CHECK(smithlab::Lambda_from_cos(ggx, 0.0) == INFINITY);
    CHECK(smithlab::G1_from_cos(ggx, 0.0) == 0.0);
    CHECK(smithlab::G1_from_cos(ggx, -0.4) == smithlab::G1_from_cos(ggx, 0.4));
    CHECK(smithlab::Lambda_from_cos(ggx, -0.4) == -1.0 - smithlab::Lambda_from_cos(ggx, 0.4));
    // NaN in, NaN out, never a throw (the hot path), on both routes.
    for (int gamma : {3, 7}) {
        CHECK(std::isnan(smithlab::Lambda_from_cos(smithlab::gtr(0.2, gamma), NAN)));
        CHECK(std::isnan(smithlab::G1_from_cos(smithlab::gtr(0.2, gamma), NAN)));
    }
    CHECK(std::isnan(smithlab::Lambda_from_cos(ggx, NAN)));
    CHECK(std::isnan(smithlab::G1_from_cos(ggx, NAN)));
    // NDFs without a form in c: exactly the mu route at mu_of_cos(c) (generated forms, Beckmann, quadrature).
    for (double c : {1e-120, 1e-3, 0.5, 0.999999}) {
        INFO("c=" << c);
        const double mu = smithlab::mu_of_cos(c);
        const smithlab::Gtr g7 = smithlab::gtr(0.2, 7), g15 = smithlab::gtr(0.2, 1.5);
        const smithlab::Beckmann b = smithlab::beckmann(0.2);
        CHECK(smithlab::Lambda_from_cos(g7, c) == smithlab::Lambda(g7, mu));
        CHECK(smithlab::G1_from_cos(g7, c) == smithlab::G1(g7, mu));
        CHECK(smithlab::Lambda_from_cos(b, c) == smithlab::Lambda(b, mu));
        CHECK(smithlab::G1_from_cos(b, c) == smithlab::G1(b, mu));
        if (c >= 1e-3) CHECK(smithlab::Lambda_from_cos(g15, c) == smithlab::Lambda(g15, mu));
    }
}
