// The walk's fast routes for an NDF without GGX's closed forms: the GGX mixture that bounds its slope density (its
// visible normals are drawn from the mixture and accepted with P22 / (K Q)) and the spline of Lambda indexed by the
// bits of tan^2. The bound checked on points of its own (not the fit's grid), the spline against the closed forms and
// the quadrature route, and the walk's acceptance against A(v) / (K A_Q(v)) by counting.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <smithlab/detail/tan2_spline.hpp>
#include <smithlab/detail/visible_normals_mixture.hpp>
#include <smithlab/gtr.hpp>
#include <string>
#include <vector>

#include "donly_registry.hpp"

using namespace smithlab;

namespace {

// Every family with a tail no heavier than GGX's, at stiff and ordinary parameters.
std::vector<std::string> bounded_specs() {
    return {"beckmann(alpha=0.5)",
            "beckmann(alpha=0.001)",
            "blinn(n=1)",
            "blinn(n=2000000)",
            "gtr(alpha=0.5, gamma=1.5)",
            "gtr(alpha=0.3, gamma=0.5)",
            "gtr(alpha=0.001, gamma=1)",
            "gtr(alpha=0.001, gamma=10)",
            "gtr(alpha=1, gamma=4)",
            "gtr(alpha=0.1, gamma=0.01)",
            "student(alpha=0.3, gamma=2)",
            "student(alpha=1, gamma=30)",
            "abc(b=30, c=2)",
            "donly_ggx(alpha=0.3)"};
}

// A plug-in whose tail, P22 ~ r^-3.5, is heavier than any GGX lobe's r^-4 (its mean slope is still finite).
struct HeavyTail {
    double D(double c) const {
        if (!(c > 0.0)) return 0.0;
        const double s = (1.0 - c * c) / (c * c);                                           // tan^2
        return 0.75 / std::numbers::pi * std::pow(1.0 + s, -1.75) * (1.0 + s) * (1.0 + s);  // P22 (1 + s)^2
    }
};

}  // namespace

TEST_CASE("GGX mixture: P22 <= K Q on points of its own, K <= 3, for every bounded NDF", "[walk_routes]") {
    const NdfRegistry ndfs = registry_with_donly();
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> ln_s(std::log(1e-14), std::log(1e14));
    for (const std::string& spec : bounded_specs()) {
        const AnyNdf ndf = ndfs.make(spec);
        const VisibleNormals<AnyNdf> vn(ndf, VisibleRoute::mixture);
        INFO(spec);
        REQUIRE(vn.mixture().has_value());
        const detail::GgxMixture& m = *vn.mixture();
        CHECK(m.bound() <= detail::GgxMixture::max_bound);
        CHECK(m.bound() >= 1.0);  // both are densities: Q cannot lie above P22 everywhere
        double worst = 0.0;
        const double r02 = std::pow(core_slope_scale(ndf), 2.0);
        for (int i = 0; i < 200000; ++i) {
            const double s = r02 * std::exp(ln_s(rng));
            worst = std::max(worst, slope_density(ndf, s) / m.Q(s));
        }
        INFO("K " << m.bound() << ", greatest P22 / Q found " << worst);
        CHECK(worst <= m.bound());
        // The lobes' weights are a distribution, each lobe a GGX of positive alpha.
        double sum = 0.0;
        for (int k = 0; k < m.lobes(); ++k) {
            CHECK(m.alpha(k) > 0.0);
            CHECK(m.weight(k) > 0.0);
            sum += m.weight(k);
        }
        CHECK(std::abs(sum - 1.0) < 1e-12);
    }
}

TEST_CASE("GGX mixture: a tail heavier than GGX's has no bound, and its visible normals take the rejection route",
          "[walk_routes]") {
    NdfRegistry ndfs = builtin_registry();
    for (const AnyNdf& ndf : {ndfs.make("student(alpha=0.3, gamma=1.65)"), as_any(HeavyTail{})}) {
        INFO(ndf.spec());
        const VisibleNormals<AnyNdf> vn(ndf);
        CHECK_FALSE(vn.mixture().has_value());
        CHECK_FALSE(vn.closed_form());
        WalkRng g(1, 2, 3);
        const Vec3 m = vn.sample(direction_from_theta_deg(60.0), g);
        CHECK(m.z() > 0.0);
    }
}

TEST_CASE("GGX mixture: the acceptance counted equals A(v) / (K A_Q(v)), above and below the horizon",
          "[walk_routes]") {
    // Von Neumann's rejection accepts with probability (target mass) / (K proposal mass); counting the generator's
    // draws per normal checks the bound is the one used, and that no draw is lost. A_Q(v) = sum_k w_k (R_k + v.z) / 2.
    const NdfRegistry ndfs = registry_with_donly();
    for (const char* spec : {"gtr(alpha=0.5, gamma=1.5)", "beckmann(alpha=0.5)", "donly_ggx(alpha=0.3)"}) {
        const AnyNdf ndf = ndfs.make(spec);
        const VisibleNormals<AnyNdf> vn(ndf, VisibleRoute::mixture);
        REQUIRE(vn.mixture().has_value());
        const detail::GgxMixture& mix = *vn.mixture();
        for (double theta : {30.0, 80.0, 100.0}) {
            const Vec3 v = direction_from_deg(theta, 20.0);
            double AQ = 0.0;
            const double d2 = v.x() * v.x() + v.y() * v.y();
            for (int k = 0; k < mix.lobes(); ++k)
                AQ += mix.weight(k) * 0.5 * (std::sqrt(v.z() * v.z() + mix.alpha(k) * mix.alpha(k) * d2) + v.z());
            const double expected = vn.projected_area(v) / (mix.bound() * AQ);
            // Count the accepted normals among n tries: sample() with a generator that stops after one try.
            long accepted = 0;
            const long tries = 200000;
            Rng g = make_rng(5, static_cast<std::uint64_t>(theta));
            for (long i = 0; i < tries; ++i)
                if (mix.sample(
                           v, [&](double s) { return slope_density(ndf, s); }, g, 1)
                        .z() > 0.0)
                    ++accepted;
            const double p = static_cast<double>(accepted) / tries, se = std::sqrt(expected * (1 - expected) / tries);
            INFO(spec << " theta " << theta << ": accepted " << p << ", A / (K A_Q) " << expected);
            CHECK(std::abs(p - expected) < 5.0 * se);
        }
    }
}

TEST_CASE("Lambda spline: within its tolerance of Beckmann's closed form and of the quadrature route",
          "[walk_routes]") {
    // The walk's Lambda of an NDF without GGX's closed form is FastLambda::at_tan2: the spline over the bits of
    // tan^2 built from the closed form (Beckmann) or the LambdaTable (the rest). Checked at t spread over every
    // binade the spline covers and beyond, against the closed form in mu and the adaptive quadrature route.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> ln_t(std::log(0x1p-44), std::log(0x1p44));
    const double tol = FastLambda<Beckmann>::spline_tolerance, floor = FastLambda<Beckmann>::spline_floor;
    for (double alpha : {0.5, 0.05, 1.0}) {
        const Beckmann b = beckmann(alpha);
        const FastLambda<Beckmann> L(b);
        double worst = 0.0;
        for (int i = 0; i < 100000; ++i) {
            const double t = std::exp(ln_t(rng)), exact = b.Lambda(1.0 / std::sqrt(t));
            worst = std::max(worst, std::abs(L.at_tan2(t) - exact) / std::max(exact, floor));
        }
        INFO("beckmann alpha " << alpha << ": worst " << worst);
        CHECK(worst <= tol);
    }
    const NdfRegistry ndfs = registry_with_donly();
    for (const char* spec :
         {"gtr(alpha=0.5, gamma=1.5)", "gtr(alpha=0.001, gamma=1)", "blinn(n=20)", "donly_ggx(alpha=0.3)"}) {
        const AnyNdf ndf = ndfs.make(spec);
        const FastLambda<AnyNdf> L(ndf);
        double worst = 0.0;
        for (int i = 0; i < 400; ++i) {
            const double t = std::exp(ln_t(rng)), mu = 1.0 / std::sqrt(t);
            if (mu < 1e-5 || mu > 1e5) continue;  // the quadrature route's own domain (lambda_table.hpp)
            const double exact = Lambda(ndf, mu);
            worst = std::max(worst, std::abs(L.at_tan2(t) - exact) / std::max(exact, floor));
        }
        INFO(spec << ": worst " << worst << ", stated " << L.error_estimate());
        CHECK(worst <= L.error_estimate());
    }
}

TEST_CASE("Lambda spline: pieces of a power law meet the tolerance, the ends and bad t answer NaN", "[walk_routes]") {
    // f = t^(1/2) (Lambda's grazing limit) and f = t (its normal-incidence limit for GGX-like tails): every piece
    // in range answers, within the tolerance.
    for (double p : {0.5, 1.0}) {
        const detail::Tan2Spline s([p](double t) { return std::pow(t, p); }, 1e-7, 0.0);
        CHECK(s.answered() == 1.0);
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> ln_t(std::log(0x1p-40), std::log(0x1p40));
        double worst = 0.0;
        for (int i = 0; i < 100000; ++i) {
            const double t = std::exp(ln_t(rng));
            worst = std::max(worst, std::abs(s(t) / std::pow(t, p) - 1.0));
        }
        INFO("p " << p << ": worst relative " << worst);
        CHECK(worst <= 1e-7);
    }
    const detail::Tan2Spline s([](double t) { return t; }, 1e-7, 0.0);
    for (double t : {0.0, -1.0, 0x1p-41, 0x1p40, double{INFINITY}, std::nan("")}) CHECK(std::isnan(s(t)));
    CHECK(s(0x1p-40) == 0x1p-40);
    // A function the cubics cannot follow (a jump inside a piece) leaves that piece to the caller.
    const detail::Tan2Spline jump([](double t) { return t < 1.01 ? 1.0 : 2.0; }, 1e-7, 0.0);
    CHECK(std::isnan(jump(1.01)));
    CHECK(jump(3.0) == 2.0);
}
