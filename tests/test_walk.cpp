// The microsurface walk (lib/include/smithlab/walk/) against what it must reproduce: energy conservation (white
// furnace, by both estimators), the analytic single-scattering BRDF for its first bounce, reciprocity, independence
// of the height law, the same bits for any number of threads; and a wrong walk (a Lambda that does not belong to D)
// is caught by the furnace. The statistical cases are [slow]: the sanitized CI build runs the others
// (tests/CMakeLists.txt).
#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <smithlab/single_scattering.hpp>
#include <smithlab/walk/trace.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "donly_registry.hpp"

namespace {

using smithlab::Vec3;
namespace walk = smithlab::walk;
constexpr double pi = std::numbers::pi;

Vec3 dir(double theta_deg, double phi_deg) {
    const double t = theta_deg * pi / 180.0, p = phi_deg * pi / 180.0;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// The integral of the eval estimator, f |cos theta_o|, over a hemisphere of wo (above, or below: transmission), by
// wo ~ |cos| / pi there, one walk each: the directional albedo by order bin and in all, each with its standard error.
struct EvalAlbedo {
    std::array<walk::Estimate, walk::order_bins> orders;
    walk::Estimate all;
};
template <class MS, class M>
EvalAlbedo eval_albedo(const MS& ms, const M& material, const Vec3& wi, int n, std::uint64_t seed, std::uint64_t cell,
                       bool below = false) {
    std::array<walk::Moments, walk::order_bins> orders{};
    walk::Moments all;
    for (int k = 0; k < n; ++k) {
        smithlab::WalkRng g(seed, cell, static_cast<std::uint64_t>(k));
        const double r = std::sqrt(smithlab::uniform01(g)), phi = 2.0 * pi * smithlab::uniform01(g);
        const double c = std::sqrt(std::max(1e-300, 1.0 - r * r));
        const Vec3 wo(r * std::cos(phi), r * std::sin(phi), below ? -c : c);
        const walk::EvalSample s = walk::eval_walk(ms, material, wi, wo, g);
        double f = 0.0;
        for (int o = 0; o < walk::order_bins; ++o) {
            orders[o].add((s.specular[o] + s.diffuse[o]) * pi / c);
            f += s.specular[o] + s.diffuse[o];
        }
        all.add(f * pi / c);
    }
    EvalAlbedo out{{}, walk::estimate(all, n)};
    for (int o = 0; o < walk::order_bins; ++o) out.orders[o] = walk::estimate(orders[o], n);
    return out;
}

// A microsurface whose Lambda is not D's: GGX's D with Lambda scaled by 1.3.
struct WrongLambda {
    smithlab::Ggx ggx;
    double D(double c) const { return ggx.D(c); }
    double slope_density(double r2) const { return ggx.slope_density(r2); }
    double Lambda(double mu) const { return 1.3 * ggx.Lambda(mu); }
};

// f on the concrete type of a built-in material (the walk templates take it directly).
template <class F>
auto visit_builtin(const walk::Material& material, F f) {
    return walk::visit(material, f, [&](const smithlab::MaterialKernels&) -> decltype(f(walk::Mirror{})) {
        throw std::logic_error("visit_builtin: " + material.spec() + " is not a built-in material");
    });
}

}  // namespace

TEST_CASE("white furnace, sample estimator: every walk leaves with all its energy", "[walk][slow]") {
    const walk::Material materials[] = {walk::Mirror{}, walk::Lambert{1.0}, walk::FresnelDiffuse{0.02, 1.0},
                                        walk::Dielectric{1.5}};
    for (double alpha : {0.01, 0.3, 1.0}) {
        const walk::Microsurface ms(smithlab::ggx(alpha));
        for (const walk::Material& material : materials) {
            for (double theta : {0.0, 45.0, 85.0}) {
                walk::CellRequest r;
                r.wi = dir(theta, 0.0);
                r.walks = 20'000;
                const walk::CellResult c =
                    visit_builtin(material, [&](const auto& m) { return walk::trace_cell(ms, m, r); });
                INFO("alpha " << alpha << " " << material.spec() << " theta_i " << theta);
                CHECK(c.albedo.capped == 0);
                const walk::Estimate all =
                    c.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
                CHECK(all.value == Approx(1.0).margin(1e-12));
                const double t =
                    c.albedo.albedo(walk::Hemisphere::transmission, walk::all_orders, walk::Component::all).value;
                if (material.transmits())
                    CHECK(t > 0.3);  // eta 1.5: a flat interface transmits 0.96 at 0, 0.39 at 85 deg
                else CHECK(t == 0.0);
            }
        }
    }
}

TEST_CASE("white furnace, eval estimator: the hemisphere integral of f cos is 1", "[walk][slow]") {
    const Vec3 wi = dir(60.0, 0.0);
    auto check = [&](const auto& ms, const walk::Material& material, const std::string& what) {
        const walk::Estimate e =
            visit_builtin(material, [&](const auto& m) { return eval_albedo(ms, m, wi, 40'000, 5, 99).all; });
        INFO(what << " " << material.spec() << ": " << e.value << " +- " << e.stderr_);
        CHECK(std::abs(e.value - 1.0) < 4.0 * e.stderr_ + 1e-3);
        CHECK(e.stderr_ < 0.02);
    };
    for (const walk::Material& m : {walk::Material{walk::Mirror{}}, walk::Material{walk::Lambert{1.0}},
                                    walk::Material{walk::FresnelDiffuse{0.02, 1.0}}}) {
        check(walk::Microsurface(smithlab::ggx(0.5)), m, "ggx(0.5)");
        check(walk::Microsurface(smithlab::beckmann(0.5)), m, "beckmann(0.5)");
        check(walk::Microsurface(smithlab::gtr(0.5, 1.5)), m, "gtr(0.5, 1.5)");
        check(walk::Microsurface(smithlab::gtr(0.5, 3.7)), m, "gtr(0.5, 3.7)");
        check(walk::Microsurface(smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.5)}), m, "D-only ggx(0.5)");
    }
}

TEST_CASE("a Lambda that does not belong to D fails the furnace", "[walk][slow]") {
    const walk::Microsurface ms(WrongLambda{smithlab::ggx(0.5)});
    const walk::Estimate e = eval_albedo(ms, walk::Mirror{}, dir(60.0, 0.0), 40'000, 5, 99).all;
    INFO(e.value << " +- " << e.stderr_);
    CHECK(std::abs(e.value - 1.0) > 10.0 * e.stderr_);
}

TEST_CASE("the first bounce is the analytic single-scattering BRDF", "[walk][slow]") {
    for (double alpha : {0.1, 0.5}) {
        const smithlab::Ggx ggx = smithlab::ggx(alpha);
        const walk::Microsurface ms(ggx);
        for (auto [ti, pi_, to, po] : {std::array{30.0, 0.0, 30.0, 180.0}, std::array{70.0, 0.0, 50.0, 150.0},
                                       std::array{85.0, 0.0, 80.0, 180.0}, std::array{10.0, 0.0, 60.0, 90.0}}) {
            const Vec3 wi = dir(ti, pi_), wo = dir(to, po);
            walk::EvalRequest r{.wi = wi, .wo = wo, .walks = 40'000};
            r.limits.max_order = 1;
            const walk::EvalTally t = walk::eval_cell(ms, walk::Conductor{0.2, 3.0}, r);
            const double want = smithlab::single_scattering_reflection(
                ggx, wi, wo, [](double c) { return smithlab::fresnel_conductor(c, 0.2, 3.0); });
            const walk::Estimate got = t.value(0, walk::Component::specular);
            INFO("alpha " << alpha << " wi " << ti << " wo " << to << "," << po << ": " << got.value << " +- "
                          << got.stderr_ << " against " << want);
            CHECK(std::abs(got.value - want) < 4.0 * got.stderr_ + 1e-12);
            CHECK(got.stderr_ < 0.05 * want + 1e-9);
            CHECK(t.value(1, walk::Component::all).value == 0.0);  // nothing past order 1 when it is not asked for
        }
    }
}

TEST_CASE("reciprocity: f(wi, wo) = f(wo, wi) over 20 pairs, grazing ones included", "[walk][slow]") {
    const walk::Microsurface ms(smithlab::ggx(0.6));
    // 20 pairs (theta_i, phi_i, theta_o, phi_o): back- and forward-scattering, side lobes, and grazing ones to 89 deg.
    const std::array<std::array<double, 4>, 20> pairs = {
        {{20, 0, 60, 180}, {45, 0, 80, 90},   {75, 30, 10, 250},  {88, 0, 60, 120},  {50, 10, 87, 200},
         {0, 0, 40, 0},    {30, 0, 30, 0},    {60, 0, 60, 10},    {85, 0, 85, 180},  {89, 0, 30, 180},
         {89, 0, 89, 90},  {10, 45, 70, 300}, {65, 120, 35, 330}, {80, 0, 20, 20},   {40, 200, 75, 20},
         {55, 0, 5, 180},  {70, 90, 70, 270}, {15, 0, 88, 0},     {35, 60, 62, 100}, {86, 0, 45, 180}}};
    for (const walk::Material& material : {walk::Material{walk::Mirror{}}, walk::Material{walk::Lambert{0.8}},
                                           walk::Material{walk::FresnelDiffuse{0.04, 0.9}}}) {
        for (const auto& p : pairs) {
            const Vec3 a = dir(p[0], p[1]), b = dir(p[2], p[3]);
            auto f = [&](const Vec3& wi, const Vec3& wo, std::uint64_t cell) {
                walk::EvalRequest r{.wi = wi, .wo = wo, .cell = cell, .walks = 40'000};
                const walk::EvalTally t =
                    visit_builtin(material, [&](const auto& m) { return walk::eval_cell(ms, m, r); });
                const walk::Estimate e = t.value();
                return walk::Estimate{e.value / wo.z(), e.stderr_ / wo.z()};
            };
            const walk::Estimate ab = f(a, b, 1), ba = f(b, a, 2);
            INFO(material.spec() << " (" << p[0] << "," << p[1] << ") <-> (" << p[2] << "," << p[3] << "): " << ab.value
                                 << " +- " << ab.stderr_ << " vs " << ba.value << " +- " << ba.stderr_);
            CHECK(std::abs(ab.value - ba.value) < 4.0 * std::hypot(ab.stderr_, ba.stderr_));
        }
    }
}

TEST_CASE("the height law does not change the result", "[walk][slow]") {
    const smithlab::Ggx ggx = smithlab::ggx(0.8);
    const walk::Microsurface<smithlab::Ggx, walk::UniformHeights> uniform(ggx);
    const walk::Microsurface<smithlab::Ggx, walk::GaussianHeights> gaussian(ggx);
    walk::CellRequest r;
    r.wi = dir(70.0, 0.0);
    r.walks = 100'000;
    const walk::CellResult a = walk::trace_cell(uniform, walk::Lambert{1.0}, r);
    r.seed = 2;
    const walk::CellResult b = walk::trace_cell(gaussian, walk::Lambert{1.0}, r);
    for (int order = 0; order < walk::order_bins; ++order) {
        const walk::Estimate x = a.albedo.albedo(walk::Hemisphere::reflection, order, walk::Component::all);
        const walk::Estimate y = b.albedo.albedo(walk::Hemisphere::reflection, order, walk::Component::all);
        INFO("order bin " << order << ": " << x.value << " +- " << x.stderr_ << " vs " << y.value << " +- "
                          << y.stderr_);
        CHECK(std::abs(x.value - y.value) < 4.0 * std::hypot(x.stderr_, y.stderr_));
    }
}

TEST_CASE("the same bits for any number of threads, and orders not asked for are not traced", "[walk]") {
    const walk::Microsurface ms(smithlab::gtr(0.4, 1.5));
    walk::CellRequest r;
    r.wi = dir(50.0, 20.0);
    r.walks = 30'000;
    r.block = 1000;
    r.brdf = {8, 16, false};
    r.threads = 1;
    const walk::CellResult one = walk::trace_cell(ms, walk::Lambert{0.9}, r);
    for (unsigned threads : {2u, 3u}) {
        r.threads = threads;
        const walk::CellResult many = walk::trace_cell(ms, walk::Lambert{0.9}, r);
        for (std::size_t i = 0; i < one.albedo.bins.size(); ++i) {
            CHECK(one.albedo.bins[i].sum == many.albedo.bins[i].sum);
            CHECK(one.albedo.bins[i].sum2 == many.albedo.bins[i].sum2);
        }
        for (std::size_t i = 0; i < one.brdf->cells.size(); ++i)
            CHECK(one.brdf->cells[i].sum == many.brdf->cells[i].sum);
        CHECK(one.albedo.events == many.albedo.events);
    }
    r.limits.max_order = 1;
    const walk::CellResult first = walk::trace_cell(ms, walk::Lambert{0.9}, r);
    CHECK(first.albedo.events == first.albedo.walks);  // a ray from above always hits, and stops there
    CHECK(one.albedo.events > first.albedo.walks + first.albedo.walks / 5);
    CHECK(first.albedo.albedo(walk::Hemisphere::all, 1, walk::Component::all).value == 0.0);
    // Order 1 is the same walks' first bounces either way.
    CHECK(first.albedo.albedo(walk::Hemisphere::all, 0, walk::Component::all).value ==
          one.albedo.albedo(walk::Hemisphere::all, 0, walk::Component::all).value);
}

TEST_CASE("material specs: named, validated, refused with the item named", "[walk]") {
    CHECK(smithlab::MaterialRegistry().make("fresnel-diffuse").spec() == "fresnel-diffuse(f0=0.02, albedo=1)");
    CHECK(smithlab::MaterialRegistry().make("dielectric").spec() == "dielectric(eta=1.5)");
    CHECK(smithlab::MaterialRegistry().make("dielectric(eta=1.33)").transmits());
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("dielectric(eta=0)"), Catch::Contains("eta"));
    CHECK(smithlab::MaterialRegistry().make("conductor(eta=0.2, k=3)").spec() == "conductor(eta=0.2, k=3)");
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("velvet"), Catch::Contains("unknown material 'velvet'"));
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("lambert(albedo=1.5)"), Catch::Contains("albedo"));
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("lambert(rho=0.5)"),
                      Catch::Contains("unknown parameter 'rho'"));
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("conductor(eta=1)"), Catch::Contains("'k' is required"));
    CHECK_THROWS_WITH(smithlab::MaterialRegistry().make("mirror(albedo=nan)"), Catch::Contains("albedo"));
}

TEST_CASE("Hammon's transmission lobe is sampled from its CDF", "[walk]") {
    // The reference: Y inverted by bisection in long double (Y increasing on [0, 1]), 120 halvings.
    auto Y = [](long double c) { return c * c * c * (3.5L + c * (-5.25L + c * (4.2L + c * (-1.75L + c * 0.3L)))); };
    auto inverse = [&](double u) {
        long double lo = 0, hi = 1;
        for (int i = 0; i < 120; ++i) (Y((lo + hi) / 2) > u ? hi : lo) = (lo + hi) / 2;
        return (lo + hi) / 2;
    };
    std::vector<double> us = {0x1p-53, 1e-15, 1e-12, 1e-6, 0.000999, 0.001,
                              0.01,    0.3,   0.5,   0.9,  0.999999, 1.0 - 0x1p-53};
    smithlab::Rng g = smithlab::make_rng(7);
    for (int i = 0; i < 2000; ++i)
        us.push_back(i % 2 ? smithlab::uniform01(g) : std::pow(10.0, -16.0 * smithlab::uniform01(g)));
    double worst = 0.0;
    for (double u : us) {
        const long double want = inverse(u);
        worst = std::max(worst, static_cast<double>(std::abs(walk::detail::hammon_lobe_cos(u) / want - 1)));
    }
    INFO("worst relative error " << worst);
    CHECK(worst < 2e-15);
    CHECK(walk::detail::hammon_lobe_cos(0.0) == 0.0);
    CHECK(walk::detail::hammon_lobe_cos(1.0) == 1.0);
}

TEST_CASE("the two estimators agree, order by order", "[walk][slow]") {
    const Vec3 wi = dir(70.0, 0.0);
    auto check = [&](const auto& ms, const std::string& what) {
        walk::CellRequest r;
        r.wi = wi;
        r.walks = 100'000;
        const walk::CellResult c = walk::trace_cell(ms, walk::Mirror{}, r);
        const EvalAlbedo eval = eval_albedo(ms, walk::Mirror{}, wi, 40'000, 3, 7);
        for (int o = 0; o < walk::order_bins; ++o) {
            const walk::Estimate a = c.albedo.albedo(walk::Hemisphere::reflection, o, walk::Component::all);
            const walk::Estimate b = eval.orders[o];
            INFO(what << " order bin " << o << ": sample " << a.value << " +- " << a.stderr_ << ", eval " << b.value
                      << " +- " << b.stderr_);
            CHECK(std::abs(a.value - b.value) < 4.0 * std::hypot(a.stderr_, b.stderr_) + 1e-4);
        }
    };
    check(walk::Microsurface(smithlab::ggx(0.7)), "ggx(0.7), closed-form visible normals");
    check(walk::Microsurface(smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.7)}), "D-only ggx(0.7)");
    check(walk::Microsurface(smithlab::gtr(0.7, 1.5)), "gtr(0.7, 1.5)");
    check(walk::Microsurface(smithlab::beckmann(0.7)), "beckmann(0.7)");
}

// ---- the dielectric: both sides of the surface --------------------------------------------------------------------

TEST_CASE("dielectric: the eval estimator's energy over both hemispheres is 1, from above and from below",
          "[walk][slow]") {
    // (alpha 0.3 and up: wo ~ cos has too much variance for a sharper lobe; the sample estimator's furnace, every walk
    // leaving with its energy, covers alpha = 0.01.)
    for (double alpha : {0.3, 0.6, 1.0}) {
        const walk::Microsurface ms(smithlab::ggx(alpha));
        // From below at 30 degrees (inside the glass, under the critical angle of 41.8) and at 60 (past it).
        for (double theta : {0.0, 60.0, 85.0, 150.0, 120.0}) {
            const Vec3 wi = dir(theta, 0.0);
            const walk::Estimate up = eval_albedo(ms, walk::Dielectric{1.5}, wi, 100'000, 11, 1).all;
            const walk::Estimate down = eval_albedo(ms, walk::Dielectric{1.5}, wi, 100'000, 11, 2, true).all;
            const double total = up.value + down.value, err = std::hypot(up.stderr_, down.stderr_);
            INFO("alpha " << alpha << " theta_i " << theta << ": up " << up.value << " down " << down.value << " total "
                          << total << " +- " << err);
            CHECK(std::abs(total - 1.0) < 4.0 * err + 2e-3);
            CHECK(err < 0.02);
        }
    }
}

TEST_CASE("dielectric: the first bounce is Walter's reflection and transmission BSDF", "[walk][slow]") {
    for (double alpha : {0.1, 0.5}) {
        const smithlab::Ggx ggx = smithlab::ggx(alpha);
        const walk::Microsurface ms(ggx);
        const walk::Dielectric glass{1.5};
        auto F = [](double c) { return smithlab::fresnel_dielectric(c, 1.5); };
        for (auto [ti, to, po] :
             {std::array{30.0, 30.0, 180.0}, std::array{70.0, 60.0, 180.0}, std::array{30.0, 160.0, 180.0},
              std::array{60.0, 150.0, 180.0}, std::array{80.0, 130.0, 150.0}}) {
            const Vec3 wi = dir(ti, 0.0), wo = dir(to, po);
            walk::EvalRequest r{.wi = wi, .wo = wo, .walks = 40'000};
            r.limits.max_order = 1;
            const walk::Estimate got = walk::eval_cell(ms, glass, r).value(0, walk::Component::specular);
            const double want = wo.z() > 0.0 ? smithlab::single_scattering_reflection(ggx, wi, wo, F)
                                             : smithlab::single_scattering_transmission(ggx, wi, wo, 1.0, 1.5, F);
            INFO("alpha " << alpha << " wi " << ti << " wo " << to << "," << po << ": " << got.value << " +- "
                          << got.stderr_ << " against " << want);
            REQUIRE(want > 0.0);
            CHECK(std::abs(got.value - want) < 4.0 * got.stderr_ + 1e-12);
            CHECK(got.stderr_ < 0.05 * want);
        }
    }
}

TEST_CASE("dielectric: reciprocity, with eta^2 across the surface", "[walk][slow]") {
    // f(wi, wo) / eta_o^2 = f(wo, wi) / eta_i^2 (Veach 1997, sec. 6.2), eta the index of each direction's medium.
    const double eta = 1.5;
    const walk::Microsurface ms(smithlab::ggx(0.6));
    auto f = [&](const Vec3& wi, const Vec3& wo, std::uint64_t cell) {
        walk::EvalRequest r{.wi = wi, .wo = wo, .cell = cell, .walks = 60'000};
        const walk::Estimate e = walk::eval_cell(ms, walk::Dielectric{eta}, r).value();
        return walk::Estimate{e.value / std::abs(wo.z()), e.stderr_ / std::abs(wo.z())};
    };
    const std::array<std::array<double, 4>, 8> pairs = {{{20, 0, 160, 180},
                                                         {45, 0, 120, 90},
                                                         {75, 30, 170, 250},
                                                         {60, 0, 100, 180},
                                                         {30, 0, 60, 180},
                                                         {80, 0, 40, 120},
                                                         {110, 0, 150, 200},
                                                         {130, 0, 100, 90}}};
    for (const auto& p : pairs) {
        const Vec3 a = dir(p[0], p[1]), b = dir(p[2], p[3]);
        const double eta_a = a.z() > 0.0 ? 1.0 : eta, eta_b = b.z() > 0.0 ? 1.0 : eta;
        const walk::Estimate ab = f(a, b, 1), ba = f(b, a, 2);
        const double x = ab.value / (eta_b * eta_b), y = ba.value / (eta_a * eta_a);
        const double err = std::hypot(ab.stderr_ / (eta_b * eta_b), ba.stderr_ / (eta_a * eta_a));
        INFO("(" << p[0] << "," << p[1] << ") <-> (" << p[2] << "," << p[3] << "): f/eta_o^2 " << x << " vs " << y
                 << " +- " << err);
        CHECK(x > 0.0);
        CHECK(std::abs(x - y) < 4.0 * err);
    }
}

TEST_CASE("dielectric: the two estimators agree, hemisphere by hemisphere and order by order", "[walk][slow]") {
    const walk::Microsurface ms(smithlab::gtr(0.6, 1.5));
    for (double theta : {50.0, 140.0}) {
        const Vec3 wi = dir(theta, 0.0);
        walk::CellRequest r;
        r.wi = wi;
        r.walks = 100'000;
        const walk::CellResult c = walk::trace_cell(ms, walk::Dielectric{1.5}, r);
        for (bool below : {false, true}) {
            const EvalAlbedo eval = eval_albedo(ms, walk::Dielectric{1.5}, wi, 40'000, 3, below ? 8 : 7, below);
            const walk::Hemisphere h = below ? walk::Hemisphere::transmission : walk::Hemisphere::reflection;
            for (int o = 0; o < walk::order_bins; ++o) {
                const walk::Estimate a = c.albedo.albedo(h, o, walk::Component::all), b = eval.orders[o];
                INFO("theta_i " << theta << (below ? " below" : " above") << " order bin " << o << ": sample "
                                << a.value << " +- " << a.stderr_ << ", eval " << b.value << " +- " << b.stderr_);
                CHECK(std::abs(a.value - b.value) < 4.0 * std::hypot(a.stderr_, b.stderr_) + 1e-4);
            }
        }
    }
}

// ---- single scattering, exactly ----------------------------------------------------------------------------------

namespace {

// The single-scattering albedo of mirror facets, E1(wi) = integral of f1(wi, wo) cos theta_o over wo, by nested
// adaptive quadrature in slope space, from the NDF's slope density P22(r^2) and a Lambda(mu) given here: with m the
// normal of slope (p, q), D dm = P22 dp dq / cos theta_m and <wi.m> = (wi.z - p wi.x - q wi.y) cos theta_m, so (Walter
// 2007 eq. 20 through the half-vector Jacobian, the height-correlated G2 over A(wi) = (1 + Lambda_i) cos theta_i)
//     E1 = integral P22(p, q) (wi.z - p wi.x)^+ / ((1 + Lambda_i + Lambda_o) wi.z) [wo.z > 0] dp dq,
// wi in the x-z plane, wo = reflect(wi, m). In polar slopes (r, phi) both kinks in phi are known: wi.m = 0 at
// cos phi = cot theta_i / r, and wo.z = 0 at cos phi = cot theta_i (1 - r^2) / (2 r); r is integrated in ln r.
template <class P22, class Lambda>
double single_albedo(const P22& P22_of, const Lambda& Lambda_of, double alpha, double theta_i_deg) {
    using boost::math::quadrature::gauss_kronrod;
    const double ti = theta_i_deg * pi / 180.0, sx = std::sin(ti), cz = std::cos(ti), cot = cz / sx;
    auto Lambda_mu = [&](double mu) { return mu <= 0.0 ? INFINITY : Lambda_of(mu); };
    const double Li = Lambda_mu(cot);
    auto at_phi = [&](double r, double phi) {
        const double p = r * std::cos(phi), q = r * std::sin(phi), norm = std::sqrt(1.0 + r * r);
        const double im = (cz - p * sx) / norm;  // wi.m
        if (!(im > 0.0)) return 0.0;
        const double ox = 2.0 * im * (-p / norm) - sx, oy = 2.0 * im * (-q / norm), oz = 2.0 * im / norm - cz;
        if (!(oz > 0.0)) return 0.0;
        return P22_of(r * r) * (cz - p * sx) / ((1.0 + Li + Lambda_mu(oz / std::hypot(ox, oy))) * cz);
    };
    auto over_phi = [&](double r) {  // integral over phi in [0, pi], doubled (the integrand is even in phi)
        std::vector<double> cuts = {0.0, pi};
        for (double c : {cot / r, cot * (1.0 - r * r) / (2.0 * r)})
            if (c > -1.0 && c < 1.0) cuts.push_back(std::acos(c));
        std::sort(cuts.begin(), cuts.end());
        double sum = 0.0;
        for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
            sum += gauss_kronrod<double, 31>::integrate([&](double phi) { return at_phi(r, phi); }, cuts[k],
                                                        cuts[k + 1], 8, 1e-12);
        return 2.0 * sum * r;  // dp dq = r dr dphi
    };
    // r's own kinks: where the phi cuts enter or leave [0, pi] (cot / r = 1; cot (1 - r^2) / (2 r) = +-1), and the
    // lobe's scale. Integrated in ln r (r dr = r^2 dln r) from 1e-8 alpha (below: < 1e-16 of the mass) to 1e8.
    const double root = std::sqrt(1.0 + cot * cot);
    std::vector<double> rc = {1e-8 * alpha, cot, (root - 1.0) / cot, (root + 1.0) / cot, alpha, 1e8};
    std::sort(rc.begin(), rc.end());
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < rc.size(); ++k)
        sum += gauss_kronrod<double, 31>::integrate(
            [&](double t) {
                const double r = std::exp(t);
                return over_phi(r) * r;
            },
            std::log(rc[k]), std::log(rc[k + 1]), 10, 1e-10);
    return sum;
}

// GGX's P22 and Lambda written out here: no smithlab code.
double ggx_single_albedo(double alpha, double theta_i_deg) {
    const double a2 = alpha * alpha;
    return single_albedo([&](double r2) { return a2 / (pi * (r2 + a2) * (r2 + a2)); },
                         [&](double mu) { return 0.5 * (std::sqrt(1.0 + a2 / (mu * mu)) - 1.0); }, alpha, theta_i_deg);
}

}  // namespace

TEST_CASE("single scattering, exactly: the order-1 albedo of GGX mirror facets equals its quadrature at 1e7 walks",
          "[walk][slow]") {
    // The reference code's rational GGX visible-normal fit biases this by up to 5e-4 at alpha = 0.1;
    // smithlab's sampler is exact: the difference is within the walk's standard error (a few 1e-5 here).
    for (double alpha : {0.1, 0.01}) {
        for (double theta : {45.0, 80.0}) {
            const walk::Microsurface ms(smithlab::ggx(alpha));
            walk::CellRequest r;
            r.wi = dir(theta, 0.0);
            r.walks = 10'000'000;
            r.limits.max_order = 1;
            const walk::CellResult c = walk::trace_cell(ms, walk::Mirror{}, r);
            const walk::Estimate e = c.albedo.albedo(walk::Hemisphere::reflection, 0, walk::Component::all);
            const double want = ggx_single_albedo(alpha, theta);
            INFO("alpha " << alpha << " theta_i " << theta << ": walk " << e.value << " +- " << e.stderr_
                          << ", quadrature " << want << " (difference " << (e.value - want) / e.stderr_ << " sigma)");
            CHECK(std::abs(e.value - want) < 4.0 * e.stderr_);
            CHECK(e.stderr_ < 1e-4);
        }
    }
}

TEST_CASE("single scattering, exactly, for every NDF: the order-1 albedo of mirror facets equals its quadrature",
          "[walk][slow]") {
    // The walk's visible normals of every NDF but GGX come from a mixture of GGX lobes accepted with P22 / (K Q)
    // (Beckmann's too), and its Lambda from a spline in the bits of tan^2: both enter the order-1 albedo, which the
    // reference integrates from the NDF's P22 and Lambda by quadrature (LambdaOptions' route, not the walk's).
    const smithlab::NdfRegistry ndfs = registry_with_donly();
    for (const char* spec :
         {"beckmann(alpha=0.5)", "gtr(alpha=0.5, gamma=1.5)", "gtr(alpha=0.1, gamma=1)", "gtr(alpha=0.3, gamma=3.3)",
          "blinn(n=20)", "student(alpha=0.3, gamma=4)", "abc(b=30, c=2)", "donly_ggx(alpha=0.3)"}) {
        const smithlab::AnyNdf ndf = ndfs.make(spec);
        const walk::Microsurface ms(ndf);
        walk::CellRequest r;
        r.wi = dir(60.0, 0.0);
        r.walks = 4'000'000;
        r.threads = 2;
        r.limits.max_order = 1;
        const walk::CellResult c = walk::trace_cell(ms, walk::Mirror{}, r);
        const walk::Estimate e = c.albedo.albedo(walk::Hemisphere::reflection, 0, walk::Component::all);
        const double want =
            single_albedo([&](double r2) { return smithlab::slope_density(ndf, r2); },
                          [&](double mu) { return smithlab::Lambda(ndf, mu); }, smithlab::core_slope_scale(ndf), 60.0);
        INFO(spec << ": walk " << e.value << " +- " << e.stderr_ << ", quadrature " << want << " (difference "
                  << (e.value - want) / e.stderr_ << " sigma); mixture " << (ms.normals().mixture() ? "yes" : "no"));
        CHECK(ms.normals().mixture().has_value());
        CHECK(std::abs(e.value - want) < 4.0 * e.stderr_);
        CHECK(e.stderr_ < 3e-4);
    }
}

TEST_CASE("single scattering, bin by bin: the order-1 brdf tally equals the analytic BRDF integrated over each bin",
          "[walk][slow]") {
    using boost::math::quadrature::gauss_kronrod;
    const smithlab::Ggx ggx = smithlab::ggx(0.5);
    const walk::Microsurface ms(ggx);
    const walk::Conductor gold{0.2, 3.0};
    walk::CellRequest r;
    r.wi = dir(50.0, 0.0);
    r.walks = 2'000'000;
    r.limits.max_order = 1;
    r.brdf = {6, 8, false};
    const walk::CellResult c = walk::trace_cell(ms, gold, r);
    auto F = [&](double x) { return smithlab::fresnel_conductor(x, gold.eta, gold.k); };
    int checked = 0;
    for (int t = 0; t < r.brdf.n_theta; ++t)
        for (int q = 0; q < r.brdf.n_phi; ++q) {
            // The bin: |cos theta_o| in [1 - (t + 1)/n, 1 - t/n], phi_o in [q, q + 1) 2 pi / n_phi (tally.hpp).
            const double c_lo = 1.0 - (t + 1.0) / r.brdf.n_theta, c_hi = 1.0 - static_cast<double>(t) / r.brdf.n_theta;
            const double p_lo = 2.0 * pi * q / r.brdf.n_phi, p_hi = 2.0 * pi * (q + 1) / r.brdf.n_phi;
            const double integral = gauss_kronrod<double, 15>::integrate(
                [&](double co) {
                    return gauss_kronrod<double, 15>::integrate(
                        [&](double phi) {
                            const double so = std::sqrt(std::max(0.0, 1.0 - co * co));
                            return smithlab::single_scattering_reflection(
                                ggx, r.wi, Vec3(so * std::cos(phi), so * std::sin(phi), co), F);
                        },
                        p_lo, p_hi, 10, 1e-10);
                },
                c_lo, c_hi, 10, 1e-10);
            const double want = integral / c.brdf->solid_angle();
            const walk::Estimate got = c.brdf->value(0, t, q, 0, walk::Component::specular);
            INFO("bin theta " << t << " phi " << q << ": " << got.value << " +- " << got.stderr_ << " against "
                              << want);
            CHECK(std::abs(got.value - want) < 4.5 * got.stderr_ + 1e-9);
            ++checked;
        }
    CHECK(checked == 48);
}

// ---- The walk's fast paths: each against the form it replaces, to rounding. ----

TEST_CASE("cos_sin_turn: cos and sin of 2 pi u within 2 ulp, the quadrants exact", "[walk]") {
    smithlab::Rng g = smithlab::make_rng(11);
    double worst = 0.0;
    auto ulps = [](double got, long double want) {
        const double w = static_cast<double>(std::abs(want));
        return w == 0.0 ? 0.0 : static_cast<double>(std::abs(got - want)) / (std::nextafter(w, INFINITY) - w);
    };
    for (int i = 0; i < 1'000'000; ++i) {
        const double u = i < 64 ? i / 64.0 : smithlab::uniform01(g);
        const smithlab::CosSin cs = smithlab::cos_sin_turn(u);
        // The reference reduces as the kernel does (exactly: u is a multiple of 2^-53), in long double.
        const long double t = 4.0L * u, q = std::nearbyint(t), x = (t - q) * 1.5707963267948966192313216916397514L;
        const long double c = std::cos(x), s = std::sin(x);
        const int k = static_cast<int>(q) & 3;
        const long double want_c = k == 0 ? c : k == 1 ? -s : k == 2 ? -c : s;
        const long double want_s = k == 0 ? s : k == 1 ? c : k == 2 ? -s : -c;
        worst = std::max({worst, ulps(cs.c, want_c), ulps(cs.s, want_s)});
    }
    INFO("worst " << worst << " ulp");
    CHECK(worst <= 2.0);
    CHECK(smithlab::cos_sin_turn(0.25).c == 0.0);
    CHECK(smithlab::cos_sin_turn(0.25).s == 1.0);
    CHECK(smithlab::cos_sin_turn(0.5).c == -1.0);
    CHECK(smithlab::cos_sin_turn(0.75).s == -1.0);
}

TEST_CASE("FastLambda of a direction: GGX's tan^2 and reciprocal forms equal the closed form in mu", "[walk]") {
    for (double alpha : {1e-3, 0.3, 1.0, 40.0}) {
        const smithlab::Ggx ggx = smithlab::ggx(alpha);
        const smithlab::FastLambda<smithlab::Ggx> L(ggx);
        double worst = 0.0;
        for (double theta : {1e-6, 0.01, 1.0, 30.0, 45.0, 60.0, 85.0, 89.0, 89.999, 89.9999999}) {
            const Vec3 w = dir(theta, 37.0);
            const double d2 = w.x() * w.x() + w.y() * w.y(), az = std::abs(w.z());
            const double want = ggx.Lambda(az / std::hypot(w.x(), w.y()));
            INFO("alpha " << alpha << " theta " << theta << ": Lambda " << want);
            const double rel[] = {L.at_tan2(smithlab::tan2_theta(w)) / want - 1.0,
                                  L.inv_Lambda(d2, az).value() * want - 1.0,
                                  L.inv_1p_Lambda(d2, az).value() * (1.0 + want) - 1.0};
            for (double r : rel) worst = std::max(worst, std::abs(r));
        }
        INFO("alpha " << alpha << ": worst relative difference " << worst);
        CHECK(worst < 1e-14);
        CHECK(L.at_tan2(0.0) == 0.0);
        CHECK(L.at_tan2(INFINITY) == INFINITY);
    }
}

TEST_CASE("the height carried as ln C1 steps as a carried height does", "[walk]") {
    // One step from the same C1 along the same direction with the same S: the uniform law's ln C1 state and the
    // Gaussian law's height agree on escaping and on C1 afterwards.
    const smithlab::Ggx ggx = smithlab::ggx(0.6);
    const walk::Microsurface<smithlab::Ggx, walk::UniformHeights> ln_c1(ggx);
    const walk::Microsurface<smithlab::Ggx, walk::GaussianHeights> height(ggx);
    smithlab::Rng g = smithlab::make_rng(3);
    int escapes = 0, disagree = 0;
    double worst = 0.0;
    for (int i = 0; i < 100'000; ++i) {
        const double c0 = 0.01 + 0.98 * smithlab::uniform01(g), S = 1.0 - smithlab::uniform01(g);
        const Vec3 w = dir(180.0 * smithlab::uniform01(g), 360.0 * smithlab::uniform01(g));
        double u = std::log(c0), h = walk::GaussianHeights::invC1(c0);
        const bool a = ln_c1.next_height(w, u, S), b = height.next_height(w, h, S);
        if (a != b) {
            ++disagree;
            continue;
        }
        escapes += !a;
        if (a) worst = std::max(worst, std::abs(std::exp(u) / walk::GaussianHeights::C1(h) - 1.0));
    }
    INFO(escapes << " escapes, " << disagree << " disagreements, worst C1 " << worst);
    CHECK(disagree == 0);
    CHECK(escapes > 10'000);
    CHECK(worst < 1e-12);
    // The other side: C1 -> 1 - C1.
    for (double c : {1e-300, 1e-10, 0.3, 0.5, 0.9, 1.0 - 1e-12})
        CHECK(std::exp(ln_c1.other_side(std::log(c))) == Approx(1.0 - c).epsilon(1e-12));
}

namespace {
// A microsurface whose hit normals cannot be drawn (what a sampler returns then: no_normal(), a NaN vector).
struct NoHitNormal {
    walk::Microsurface<smithlab::Ggx> ms;
    bool next_height(const Vec3& w, double& h, double S) const { return ms.next_height(w, h, S); }
    double escape(const Vec3& wo, double h) const { return ms.escape(wo, h); }
    Vec3 hit_normal(const Vec3&, smithlab::WalkRng&) const { return smithlab::no_normal(); }
    double other_side(double h) const { return ms.other_side(h); }
    const smithlab::VisibleNormals<smithlab::Ggx>& normals() const { return ms.normals(); }
    const walk::MicrosurfaceOptions& options() const { return ms.options(); }
};
}  // namespace

TEST_CASE("Hammon's hit normal: the walk runs, keeps every walk's energy, and its first bounce is its own law's",
          "[walk][slow]") {
    // Hammon 2017's hit normal, D(m) cos(theta_m) over the normals facing the ray, against the visible normals. What
    // is the same: the first hit's height (it depends on Lambda(wi) only), energy (every walk leaves with all of it:
    // mirror and lambert(1) total 1, none capped), and, at normal incidence only, the first normal's law (both are D
    // cos there). What differs: the first normal's law at any other incidence, so the order-1 albedo -- measured with
    // 4e6 walks per cell, GGX mirror 0.3 at 75 degrees: 0.824 visible, 0.675 Hammon (the grazing hit finds steeper
    // facets, more of whose reflections go down and scatter again). The order-1 albedo of Hammon's walk is checked
    // against its own law: E[(1 + Lambda_i) / (1 + Lambda_i + Lambda_o)] over m drawn from Hammon's sampler, wo =
    // reflect(wi, m) up (the height-correlated chance that the first reflection escapes; 0 for wo going down), which
    // involves no height.
    const walk::MicrosurfaceOptions hammon{.hit_normal = walk::HitNormal::hammon_dcos};
    for (double alpha : {0.3, 0.8}) {
        const smithlab::Ggx ggx = smithlab::ggx(alpha);
        const walk::Microsurface visible_ms(ggx), hammon_ms(ggx, hammon);
        for (double theta : {0.0, 45.0, 75.0}) {
            walk::CellRequest r;
            r.wi = dir(theta, 0.0);
            r.walks = 200'000;
            const walk::CellResult hm = walk::trace_cell(hammon_ms, walk::Mirror{}, r);
            const walk::CellResult hl = walk::trace_cell(hammon_ms, walk::Lambert{1.0}, r);
            const walk::CellResult vm = walk::trace_cell(visible_ms, walk::Mirror{}, r);
            INFO("alpha " << alpha << " theta_i " << theta);
            for (const walk::CellResult* c : {&hm, &hl}) {
                CHECK(c->albedo.capped == 0);
                CHECK(c->albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all).value ==
                      Approx(1.0).margin(1e-12));
            }
            // Order 1 against Hammon's law, by drawing its normals directly.
            smithlab::WalkRng g(9, 1, static_cast<std::uint64_t>(theta));
            walk::Moments esc;
            const double Li = smithlab::Lambda(ggx, smithlab::cot_theta(r.wi));
            const int n = 1'000'000;
            for (int k = 0; k < n; ++k) {
                const Vec3 m = smithlab::sample_hammon_normal(hammon_ms.normals().dcos(), r.wi, g);
                const Vec3 wo = smithlab::reflect(r.wi, m);
                esc.add(wo.z() > 0.0 ? (1.0 + Li) / (1.0 + Li + smithlab::Lambda(ggx, smithlab::cot_theta(wo))) : 0.0);
            }
            const walk::Estimate want = walk::estimate(esc, n);
            const walk::Estimate got = hm.albedo.albedo(walk::Hemisphere::all, 0, walk::Component::all);
            const walk::Estimate vis = vm.albedo.albedo(walk::Hemisphere::all, 0, walk::Component::all);
            const double sigma = std::hypot(got.stderr_, want.stderr_), sigma_v = std::hypot(got.stderr_, vis.stderr_);
            INFO("order 1: Hammon walk " << got.value << " +- " << got.stderr_ << ", its law " << want.value << " +- "
                                         << want.stderr_ << ", visible walk " << vis.value << " +- " << vis.stderr_);
            CHECK(std::abs(got.value - want.value) < 4.0 * sigma);
            if (theta == 0.0) CHECK(std::abs(got.value - vis.value) < 4.0 * sigma_v);
            else CHECK(std::abs(got.value - vis.value) > 8.0 * sigma_v);
        }
    }
    // The eval estimator refuses it: its phase functions are visible-normal densities.
    CHECK_THROWS_WITH(walk::require_eval_normals(hammon), Catch::Contains("visible normals"));
    CHECK_NOTHROW(walk::require_eval_normals({}));
    const walk::Microsurface hammon_ms(smithlab::ggx(0.5), hammon);
    smithlab::WalkRng g(1, 0, 0);
    const walk::EvalSample e = walk::eval_walk(hammon_ms, walk::Mirror{}, dir(30.0, 0.0), dir(40.0, 180.0), g);
    CHECK(e.capped);
    CHECK(e.events == 0);
    // A hit normal that cannot be drawn (no_normal()) ends the walk as capped, with no NaN in what it returns.
    const NoHitNormal broken{walk::Microsurface(smithlab::ggx(0.5))};
    const walk::WalkSample s = walk::sample_walk(broken, walk::Mirror{}, dir(30.0, 0.0), g);
    CHECK(s.capped);
    CHECK(!s.escaped);
    CHECK(s.weight == 0.0);
    CHECK(std::isfinite(s.wo.x() + s.wo.y() + s.wo.z()));
    const walk::EvalSample es = walk::eval_walk(broken, walk::Mirror{}, dir(30.0, 0.0), dir(40.0, 180.0), g);
    CHECK(es.capped);
}
