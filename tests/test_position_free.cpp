// The position-free eval estimator (walk/position_free.hpp) and the depth law it carries (walk/depth_law.hpp):
// - the law's closed forms against a simulation of the exponential depth steps themselves (an independent route);
// - unbiased against the height walk (reciprocal), order by order and component by component, over NDFs (closed form,
//   generic, GTR, a tabulated table, a D-only plug-in) x facets (mirror, conductor, lambert, fresnel-diffuse,
//   dielectric) x direction pairs, grazing ones included;
// - its first hit on mirror facets is the closed-form single scattering exactly (no variance);
// - reciprocal, and a white furnace for lossless facets (mirror; the dielectric over both sides).
// Each term of the estimator was dropped in turn and these cases run against it: the new exponential of a downward
// step (eq. 3), the last term of the escape sum (eq. 5), the other side's escape (eq. 6) and the roulette's weight;
// each fails them (7 to 122 of 732 assertions).
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <smithlab/walk/trace.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "estimates.hpp"

namespace {

namespace walk = smithlab::walk;
using smithlab::Vec3;
using smithlab_test::sigmas;
using walk::EvalEstimator;

// A depth chain simulated step by step: from above at rate a0, then the given moves (rate > 0 up, < 0 down); the
// chance to be alive at the last hit times e^{-L t} (escape toward a direction of Lambda L), and times
// (1 - e^{-t})^L (the other side), each a sample mean over n chains.
struct Simulated {
    double escape = 0.0, escape2 = 0.0, other = 0.0, other2 = 0.0;
    std::int64_t n = 0;
};
Simulated simulate(double a0, const std::vector<double>& moves, double L, std::int64_t n) {
    Simulated s;
    s.n = n;
    smithlab::WalkRng g(5, 1, 0);
    for (std::int64_t k = 0; k < n; ++k) {
        double t = -std::log(1.0 - smithlab::uniform01(g)) / a0;
        bool alive = true;
        for (const double m : moves) {
            const double x = -std::log(1.0 - smithlab::uniform01(g)) / std::abs(m);
            t += m > 0.0 ? -x : x;
            if (t < 0.0) {
                alive = false;
                break;
            }
        }
        const double e = alive ? std::exp(-L * t) : 0.0, o = alive ? std::pow(-std::expm1(-t), L) : 0.0;
        s.escape += e, s.escape2 += e * e, s.other += o, s.other2 += o * o;
    }
    return s;
}

double z(double value, double sum, double sum2, std::int64_t n) {
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    return std::abs(value - mean) / se;
}

// GGX(0.3)'s D beside a wider lobe, sampled every degree to 89 (tabulated.hpp): a measured NDF of no closed form.
smithlab::TabulatedNdf two_lobe_table() {
    const smithlab::Ggx a = smithlab::ggx(0.3), b = smithlab::ggx(0.8);
    std::ostringstream csv;
    csv.precision(17);
    csv << "theta_deg,D\n";
    for (int t = 0; t <= 89; ++t) {
        const double c = std::cos(t * std::numbers::pi / 180.0);
        csv << t << "," << 0.7 * a.D(c) + 0.3 * b.D(c) << "\n";
    }
    return smithlab::tabulated_ndf_from_csv(csv.str(), "two_lobe.csv", {true});
}

// position_free against the height walk (independent walks) at each point: the total, each order bin and, for a diffuse
// material, each component of it.
template <class N, class M>
void check_unbiased(const std::string& name, const N& ndf, const M& material, std::int64_t walks) {
    const walk::Microsurface ms(ndf);
    struct Point {
        double ti, to, phi;
    };
    std::uint64_t cell = 0;
    for (const Point p : {Point{45, 60, 135}, {0, 40, 0}, {30, 20, 90}, {80, 85, 0}, {15, 85, 90}, {60, 120, 180}}) {
        if (p.to > 90.0 && !walk::TwoSided<M>) continue;
        walk::EvalRequest r{.wi = smithlab::direction_from_deg(p.ti, 0.0),
                            .wo = smithlab::direction_from_deg(p.to, p.phi),
                            .cell = cell++,
                            .walks = walks};
        // The reference: reciprocal (itself checked against next_event, test_eval_estimators.cpp), which starts from
        // the same end and so has a variance its standard error tracks where next_event's, toward a grazing wo, is
        // heavy-tailed.
        r.seed = 21;
        r.estimator = EvalEstimator::reciprocal;
        const walk::EvalTally height = walk::eval_cell(ms, material, r);
        r.seed = 22;
        r.estimator = EvalEstimator::position_free;
        const walk::EvalTally free = walk::eval_cell(ms, material, r);
        INFO(name << " at (" << p.ti << ", " << p.to << ", " << p.phi << "): height walk " << height.value().value
                  << " +- " << height.value().stderr_ << ", position-free " << free.value().value << " +- "
                  << free.value().stderr_);
        REQUIRE(height.value().value > 0.0);
        CHECK(sigmas(height.value(), free.value()) < 4.5);
        for (int b = 0; b < walk::order_bins; ++b)
            for (const walk::Component c : {walk::Component::specular, walk::Component::diffuse}) {
                const walk::Estimate o = height.value(b, c), n = free.value(b, c);
                INFO("order bin " << b + 1 << (c == walk::Component::diffuse ? " diffuse: " : " specular: ") << o.value
                                  << " +- " << o.stderr_ << " against " << n.value << " +- " << n.stderr_);
                if (o.stderr_ + n.stderr_ > 0.0) CHECK(sigmas(o, n) < 4.5);
                else CHECK(std::abs(o.value - n.value) <= 1e-12 * height.value().value);
            }
    }
}

// A D-only plug-in: GGX's D and nothing else (its Lambda and visible normals derived).
struct PlugInGgx {
    smithlab::Ggx ggx;
    double D(double c) const { return ggx.D(c); }
};

}  // namespace

TEST_CASE("depth law: its closed forms agree with the depth steps simulated", "[walk][position_free]") {
    struct Chain {
        double a0;
        std::vector<double> moves;  // rate > 0 up, < 0 down
        double L;
    };
    for (const Chain& c : {Chain{1.3, {}, 0.7}, Chain{1.3, {0.4}, 0.7}, Chain{2.0, {-1.5, 0.8}, 0.3},
                           Chain{1.1, {0.2, -3.0, 1.7, -1.2}, 1.4}, Chain{4.0, {-1.0, -2.5, 0.6, 0.6, -1.8}, 0.0},
                           Chain{1.0, {-1.0001, 0.9}, 2.5}}) {
        walk::DepthLaw law(c.a0);
        bool kept = true;
        for (const double m : c.moves) {
            if (m > 0.0) law.up(m);
            else kept = kept && law.down(-m);
        }
        if (!kept) continue;  // refused: the walk leaves the law there (tested below)
        const Simulated s = simulate(c.a0, c.moves, c.L, 400'000);
        INFO("a0 " << c.a0 << ", " << c.moves.size() << " moves, L " << c.L << ": law " << law.escape(c.L)
                   << ", simulated " << s.escape / s.n);
        CHECK(z(law.escape(c.L), s.escape, s.escape2, s.n) < 4.5);
        CHECK(z(law.escape_other_side(c.L), s.other, s.other2, s.n) < 4.5);
        CHECK(law.mass() == Approx(law.escape(0.0)));
    }
}

TEST_CASE("depth law: a depth drawn from it has its mean, and a move it cannot keep is refused",
          "[walk][position_free]") {
    walk::DepthLaw law(1.5);
    law.up(0.6);
    REQUIRE(law.down(2.7));
    law.up(1.1);
    // The mean depth int t p / int p = sum c_i / r_i^2 / mass, from the escape chance's derivative at L = 0:
    // d/dL sum c_i / (r_i + L) = -sum c_i / (r_i + L)^2.
    const double h = 1e-6, mean = -(law.escape(h) - law.escape(0.0)) / h / law.mass();
    smithlab::WalkRng g(9, 0, 0);
    double sum = 0.0, sum2 = 0.0;
    const std::int64_t n = 200'000;
    for (std::int64_t k = 0; k < n; ++k) {
        const double t = law.sample(g);
        sum += t, sum2 += t * t;
    }
    CHECK(z(mean, sum, sum2, n) < 4.5);
    CHECK_FALSE(walk::DepthLaw(1.5).down(1.5));  // c a / (a - r): a at the rate it holds
    // Step after step down, the law grows a term each until a step would exceed max_terms or its conditioning: then
    // refused, the law unchanged.
    walk::DepthLaw law2(1.2);
    int kept = 1;
    while (kept < 40 && law2.down(1.2 + 0.37 * kept)) ++kept;
    CHECK(kept < 40);
    CHECK(law2.terms() == kept);
    CHECK(law2.terms() <= walk::DepthLaw::max_terms);
    const double before = law2.mass();
    CHECK_FALSE(law2.down(1.2 + 0.37 * kept));
    CHECK(law2.mass() == before);
}

TEST_CASE("position-free: unbiased against the height walk, order by order", "[walk][position_free][slow]") {
    check_unbiased("ggx(0.5) mirror", smithlab::ggx(0.5), walk::Mirror{}, 40'000);
    check_unbiased("ggx(0.1) conductor", smithlab::ggx(0.1), walk::Conductor{0.2, 3.0}, 40'000);
    check_unbiased("ggx(1) lambert", smithlab::ggx(1.0), walk::Lambert{1.0}, 30'000);
    check_unbiased("beckmann(0.5) fresnel-diffuse", smithlab::beckmann(0.5), walk::FresnelDiffuse{0.04, 1.0}, 30'000);
    check_unbiased("gtr(0.5, 3) lambert", smithlab::gtr(0.5, 3.0), walk::Lambert{0.8}, 30'000);
    check_unbiased("gtr(1, 1) mirror", smithlab::gtr(1.0, 1.0), walk::Mirror{}, 30'000);
    check_unbiased("two-lobe table fresnel-diffuse", two_lobe_table(), walk::FresnelDiffuse{0.04, 1.0}, 20'000);
    check_unbiased("D-only ggx(0.5) lambert", PlugInGgx{smithlab::ggx(0.5)}, walk::Lambert{1.0}, 20'000);
    check_unbiased("ggx(0.5) dielectric", smithlab::ggx(0.5), walk::Dielectric{1.5}, 30'000);
    check_unbiased("ggx(1) dielectric 1.1", smithlab::ggx(1.0), walk::Dielectric{1.1}, 30'000);
}

TEST_CASE("position-free: its first hit on mirrors is the single scattering exactly", "[walk][position_free]") {
    for (const double alpha : {0.05, 0.4, 1.0}) {
        const smithlab::Ggx ndf = smithlab::ggx(alpha);
        const walk::Microsurface ms(ndf);
        for (const auto& [ti, to, phi] : {std::tuple{30.0, 50.0, 180.0}, {70.0, 20.0, 90.0}, {85.0, 80.0, 0.0}}) {
            const Vec3 wi = smithlab::direction_from_deg(ti, 0.0), wo = smithlab::direction_from_deg(to, phi);
            // f |cos theta_o| by Walter et al. 2007 eq. 20 with the height-correlated G2 (single_scattering.hpp).
            const double exact = smithlab::single_scattering_reflection(ndf, wi, wo, [](double) { return 1.0; });
            for (std::uint64_t k = 0; k < 20; ++k) {
                smithlab::WalkRng g(3, 0, k);
                const walk::EvalSample s =
                    walk::detail::eval_walk_position_free(ms, walk::Mirror{}, wi, wo, g, {.max_order = 1});
                INFO("alpha " << alpha << " (" << ti << ", " << to << ", " << phi << ") walk " << k);
                CHECK(s.specular[0] == Approx(exact).epsilon(1e-10));
            }
        }
    }
}

TEST_CASE("position-free: reciprocal, and energy-conserving facets keep all energy", "[walk][position_free][slow]") {
    // f(wi, wo) = f(wo, wi): f |cos theta_o| / cos theta_o from both ends, each walk from its own end.
    const walk::Microsurface ms(smithlab::ggx(0.6));
    const auto value = [&](const auto& material, const Vec3& a, const Vec3& b, std::uint64_t seed) {
        double sum = 0.0, sum2 = 0.0;
        const std::int64_t n = 100'000;
        for (std::int64_t k = 0; k < n; ++k) {
            smithlab::WalkRng g(seed, 0, k);
            const walk::EvalSample s = walk::detail::eval_walk_position_free(ms, material, a, b, g, {});
            double y = 0.0;
            for (int i = 0; i < walk::order_bins; ++i) y += s.specular[i] + s.diffuse[i];
            y /= b.z();
            sum += y, sum2 += y * y;
        }
        const double mean = sum / n;
        return walk::Estimate{mean, std::sqrt((sum2 / n - mean * mean) / n)};
    };
    const Vec3 a = smithlab::direction_from_deg(20.0, 0.0), b = smithlab::direction_from_deg(70.0, 120.0);
    CHECK(sigmas(value(walk::Lambert{1.0}, a, b, 1), value(walk::Lambert{1.0}, b, a, 2)) < 4.5);
    CHECK(sigmas(value(walk::Mirror{}, a, b, 3), value(walk::Mirror{}, b, a, 4)) < 4.5);
    CHECK(sigmas(value(walk::FresnelDiffuse{0.04, 1.0}, a, b, 5), value(walk::FresnelDiffuse{0.04, 1.0}, b, a, 6)) <
          4.5);

    // The white furnace: wo uniform over the hemisphere (the sphere for the dielectric), 2 pi (4 pi) f |cos theta_o|
    // averages to the albedo, 1.
    const auto furnace = [&](const auto& material, bool sphere, std::uint64_t seed) {
        const Vec3 wi = smithlab::direction_from_deg(40.0, 0.0);
        double sum = 0.0, sum2 = 0.0;
        const std::int64_t n = 200'000;
        for (std::int64_t k = 0; k < n; ++k) {
            smithlab::WalkRng g(seed, 0, k);
            const double c = sphere ? 2.0 * smithlab::uniform01(g) - 1.0 : smithlab::uniform01(g);
            const double r = std::sqrt(std::max(0.0, 1.0 - c * c)),
                         phi = 2.0 * std::numbers::pi * smithlab::uniform01(g);
            const Vec3 wo(r * std::cos(phi), r * std::sin(phi), c);
            const walk::EvalSample s = walk::detail::eval_walk_position_free(ms, material, wi, wo, g, {});
            double y = 0.0;
            for (int i = 0; i < walk::order_bins; ++i) y += s.specular[i] + s.diffuse[i];
            y *= (sphere ? 4.0 : 2.0) * std::numbers::pi;
            sum += y, sum2 += y * y;
        }
        return z(1.0, sum, sum2, n);
    };
    CHECK(furnace(walk::Mirror{}, false, 7) < 4.5);
    CHECK(furnace(walk::Lambert{1.0}, false, 8) < 4.5);
    CHECK(furnace(walk::Dielectric{1.5}, true, 9) < 4.5);
}
