// The samplers: chi-square goodness of fit for every sampler on every registered NDF family (and a D-only one),
// visible normals below the horizon too,
// alpha down to 1e-3, normal to grazing incidence; pdfs that integrate to 1; the tables against the analytic
// inversions; the reflection Jacobian; the projected area over the whole sphere against quadrature; the geometry
// helpers (frame, refraction, half vectors, Jacobians); bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/gtr.hpp>
#include <string>
#include <vector>

#include "chi2.hpp"
#include "donly_registry.hpp"

using namespace smithlab;

namespace {

struct Case {
    std::string sampler, spec;
    double theta_i;
};

std::vector<std::string> ndf_specs() {
    return {"ggx(alpha=1)",
            "ggx(alpha=0.3)",
            "ggx(alpha=0.001)",
            "beckmann(alpha=1)",
            "beckmann(alpha=0.3)",
            "beckmann(alpha=0.001)",
            "blinn(n=1)",
            "blinn(n=20)",
            "blinn(n=2000000)",
            "gtr(alpha=0.3, gamma=0.5)",
            "gtr(alpha=0.001, gamma=1)",
            "gtr(alpha=0.3, gamma=1.5)",
            "gtr(alpha=0.5, gamma=3.3)",
            "gtr(alpha=0.001, gamma=10)",
            "gtr(alpha=1, gamma=4)",
            "gtr(alpha=0.3, gamma=2)",
            "student(alpha=0.3, gamma=1.65)",
            "student(alpha=0.001, gamma=4)",
            "student(alpha=1, gamma=30)",
            "donly_ggx(alpha=0.3)"};
}

bool is_visible(const std::string& sampler) { return sampler.rfind("vndf", 0) == 0; }

// Below the horizon (wi.z < 0), visible normals on a handful of (sampler, NDF): heavy and light tails, the tables,
// the closed forms; and one whose projected area underflows (refused).
std::vector<Case> below_horizon_cases() {
    std::vector<Case> cases;
    auto add = [&](const std::string& sampler, const std::string& spec, std::vector<double> thetas) {
        for (double t : thetas) cases.push_back({sampler, spec, t});
    };
    const std::vector<double> three = {100.0, 135.0, 170.0};
    for (const char* spec : {"ggx(alpha=0.3)", "beckmann(alpha=0.3)", "gtr(alpha=0.3, gamma=1.5)", "blinn(n=20)"})
        add("vndf", spec, three);
    add("vndf", "beckmann(alpha=1)", {170.0});
    add("vndf", "donly_ggx(alpha=0.3)", {135.0});
    add("vndf-table", "ggx(alpha=0.3)", {135.0});
    for (const char* spec : {"beckmann(alpha=0.3)", "gtr(alpha=0.3, gamma=1.5)", "gtr(alpha=0.001, gamma=1)",
                             "blinn(n=20)", "student(alpha=0.3, gamma=4)", "donly_ggx(alpha=0.3)"})
        add("vndf-mixture", spec, three);
    add("vndf-ggx", "ggx(alpha=0.3)", three);
    add("vndf-ggx", "ggx(alpha=0.001)", {135.0});
    add("vndf-ggx", "gtr(alpha=0.3, gamma=2)", {135.0});
    add("vndf-beckmann", "beckmann(alpha=1)", three);
    add("vndf-beckmann", "beckmann(alpha=0.3)", three);
    add("vndf-beckmann", "beckmann(alpha=0.001)", {100.0});  // A(wi) = Lambda(|mu|) |wi.z| underflows: refused
    return cases;
}

// Every (sampler, NDF, incidence) the chi-square tests run; the Sidak correction is over all of them.
std::vector<Case> all_cases(const NdfRegistry& ndfs, const std::vector<SamplerInfo>& samplers) {
    std::vector<Case> cases;
    for (const SamplerInfo& s : samplers)
        for (const std::string& spec : ndf_specs()) {
            if (!s.applies(ndfs.make(spec))) continue;
            // The tables are the same code for every NDF: a few NDFs suffice for the -table variants.
            const bool few = spec == "ggx(alpha=0.3)" || spec == "gtr(alpha=0.001, gamma=1)" || spec == "blinn(n=20)" ||
                spec == "beckmann(alpha=0.001)";
            if (s.name.find("-table") != std::string::npos && !few) continue;
            using I = SamplerInfo::Incidence;
            const std::vector<double> thetas = s.incidence == I::ignored ? std::vector<double>{0.0}
                : is_visible(s.name)                                     ? std::vector<double>{0.0, 45.0, 89.0}
                                                                         : std::vector<double>{89.0, 100.0, 150.0};
            for (double t : thetas) cases.push_back({s.name, spec, t});
        }
    for (const Case& c : below_horizon_cases()) cases.push_back(c);
    return cases;
}

// Runs the cases whose sampler name starts with `prefix` (but not with `except`, when given).
void run_chi2(const std::string& prefix, const std::string& except = "") {
    const NdfRegistry ndfs = registry_with_donly();
    const std::vector<SamplerInfo> samplers = builtin_samplers();
    const std::vector<Case> cases = all_cases(ndfs, samplers);
    const double alpha_1 = chi2::sidak(0.01, cases.size());
    INFO(cases.size() << " tests in all, per-test significance " << alpha_1);
    Rng rng = make_rng(20261122);
    int ran = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        if (c.sampler.rfind(prefix, 0) != 0 || (!except.empty() && c.sampler.rfind(except, 0) == 0)) continue;
        ++ran;
        const AnyNdf ndf = ndfs.make(c.spec);
        const Vec3 wi = direction_from_theta_deg(c.theta_i);
        if (c.sampler == "hammon" && HammonSampler(ndf).facing_fraction(wi) == 0.0) {
            // A ray going up at 60 degrees cannot hit a Beckmann(1e-3) facet: its D cos mass there underflows.
            INFO(c.spec << " at theta_i = " << c.theta_i);
            CHECK(DcosSampler(ndf).sf(wi.z() * wi.z() / (wi.x() * wi.x())) == 0.0);
            CHECK_THROWS_AS(prepare(find_sampler(samplers, c.sampler), ndf, wi), input_error);
            continue;
        }
        if (is_visible(c.sampler) && VisibleNormalSampler(ndf).projected_area(wi) == 0.0) {
            // Beckmann(1e-3) seen from 10 degrees below the horizon: Lambda(|mu|) |wi.z| ~ e^{-31000} underflows.
            INFO(c.spec << " at theta_i = " << c.theta_i);
            CHECK_THROWS_WITH(prepare(find_sampler(samplers, c.sampler), ndf, wi), Catch::Contains("visible"));
            continue;
        }
        const BoundSampler bound = prepare(find_sampler(samplers, c.sampler), ndf, wi);
        // The bins' slope scale: the median tan(theta_m) of 1001 pilot samples from their own stream.
        chi2::Bins bins;
        bins.scale = chi2::median_slope(bound, 1001, make_rng(7, k));
        // Hammon's pdf jumps, and the visible normals' kinks, where wi.m = 0: the bin integrals split there (chi2.hpp).
        bins.crease = wi;
        const chi2::Result r = chi2::test(bound, bins, 100000, rng);
        INFO(c.sampler << " on " << c.spec << " at theta_i = " << c.theta_i << ": chi2 = " << r.statistic << ", dof "
                       << r.dof << ", p = " << r.p_value << ", pdf integral " << r.pdf_integral << " " << r.note);
        CHECK(r.bad_samples == 0);
        // The bins' quadrature, split where the pdf jumps (Hammon's facing boundary) or kinks (the visible normals'
        // wi.m = 0, and their ridge ~alpha^2 / |mu| wide below the horizon), sums to 1 within 2e-8 on every case
        // (unsplit it resolved a jump to ~1e-4 only, and this was 1e-3 for Hammon, 1e-4 below the horizon): 1e-5
        // for all leaves room for the tabulated Lambda's stated 1e-6 in A(wi), and none for a wrong normalization.
        CHECK(std::abs(r.pdf_integral - 1.0) < 1e-5);
        CHECK(r.p_value >= alpha_1);
    }
    CHECK(ran > 0);
}

}  // namespace

TEST_CASE("chi-square: D cos samplers, analytic and tabulated, every NDF family, alpha to 1e-3", "[sampling][chi2]") {
    run_chi2("dcos");
}

TEST_CASE(
    "chi-square: visible-normal samplers, generic, tabulated, GGX and Beckmann, normal incidence to 10 degrees below "
    "the horizon",
    "[sampling][chi2][slow]") {
    run_chi2("vndf", "vndf-mixture");
}

TEST_CASE("chi-square: visible normals by a mixture of GGX lobes, every NDF it bounds, above and below the horizon",
          "[sampling][chi2][slow]") {
    run_chi2("vndf-mixture");
}

TEST_CASE("chi-square: Hammon's facing-restricted D cos, rays going down and up", "[sampling][chi2][slow]") {
    run_chi2("hammon");
}

TEST_CASE("D cos laws: the analytic survival functions against quadrature of pi P22, and their inverses",
          "[sampling]") {
    // Independent route: S(s) = pi * integral_s^inf P22 by Boost quadrature on the slope density, not the inversions.
    auto check = [](const auto& ndf, const std::string& what) {
        for (double s : {1e-12, 1e-7, 1e-4, 0.01, 0.3, 1.0, 3.0, 100.0, 1e6}) {
            const double want = integrate([&](double x) { return std::numbers::pi * slope_density(ndf, x); }, s,
                                          INFINITY, {Backend::boost, 1e-13});
            const double got = ndf.Dcos_sf(s);
            INFO(what << " s=" << s << " S=" << got << " quadrature " << want);
            CHECK(std::abs(got - want) <= 1e-12 * std::max(want, 1e-3));  // relative in the tail, absolute near 1
            // The inverse, in probability (near the pole S = 1 - tiny cannot carry s's digits, nor need it).
            if (got > 1e-300 && got < 1.0) CHECK(std::abs(ndf.Dcos_sf(ndf.Dcos_r2(got)) - got) <= 1e-12 * got + 1e-16);
            if (got > 1e-300 && got < 0.5) CHECK(ndf.Dcos_r2(got) == Approx(s).epsilon(1e-9));
        }
    };
    for (double a : {1e-4, 0.01, 0.3, 1.0}) {
        check(ggx(a), "ggx " + std::to_string(a));
        check(beckmann(a), "beckmann " + std::to_string(a));
        for (double g : {0.0, 0.5, 1.0, 1.0 + 1e-9, 1.5, 2.0, 3.3, 20.0})
            check(gtr(a, g), "gtr " + std::to_string(a) + " " + std::to_string(g));
    }
    check(gtr(0.999999, 2.5), "gtr 0.999999");
    check(gtr(1e-30, 2.5), "gtr 1e-30 2.5");
    check(gtr(1e-30, 25.0), "gtr 1e-30 25");  // (gamma - 1) ln(1/alpha^2) = 3300: expm1 would overflow
    for (double n : {0.0, 1.0, 20.0, 1e4}) check(blinn(n), "blinn " + std::to_string(n));
    for (double a : {1e-4, 0.3, 1.0})
        for (double g : {1.65, 2.0, 3.3, 30.0, 1e6})
            check(student(a, g), "student " + std::to_string(a) + " " + std::to_string(g));
    check(student(1e-30, 2.5), "student 1e-30 2.5");
}

TEST_CASE("D cos tables: against the analytic inversions, within their stated error", "[sampling]") {
    auto compare = [](const auto& ndf, const std::string& what) {
        const DcosSampler exact(ndf), table(ndf, true);
        REQUIRE(table.tabulated());
        INFO(what << ": table error estimate " << table.table_error());
        CHECK(table.table_error() < 1e-8);
        for (double v : {1e-15, 1e-9, 1e-4, 0.1, 0.5, 0.9, 0.999999}) {
            const double s = exact.isf(v);
            INFO("v=" << v << " s=" << s);
            CHECK(std::abs(table.sf(s) - v) <= table.table_error() + 1e-15);
            CHECK(std::abs(exact.sf(table.isf(v)) - v) <= table.table_error() + 1e-15);
        }
        // The table's inverse inverts the table itself (its cell found by the guide table, then Newton), from v = 1
        // down to the tail: to the rounding of s = e^y and y = ln s between the two (|y| <= 230).
        smithlab::Rng g = smithlab::make_rng(11);
        double worst = 0.0;
        for (int i = 0; i < 4000; ++i) {
            const double v = i % 2 ? 1.0 - smithlab::uniform01(g) : std::pow(10.0, -12.0 * smithlab::uniform01(g));
            worst = std::max(worst, std::abs(table.sf(table.isf(v)) / v - 1.0));
        }
        INFO("worst relative |sf(isf(v)) / v - 1| " << worst);
        CHECK(worst < 1e-11);  // measured: 4e-13 (beckmann(0.3)), the rest 1e-14..9e-14
    };
    compare(ggx(1e-3), "ggx(1e-3)");
    compare(beckmann(0.3), "beckmann(0.3)");
    compare(gtr(1e-3, 1.0), "gtr(1e-3, 1)");
    compare(gtr(0.5, 20.0), "gtr(0.5, 20)");
    compare(blinn(20.0), "blinn(20)");
    compare(student(1e-3, 1.65), "student(1e-3, 1.65)");
    compare(student(0.5, 30.0), "student(0.5, 30)");
}

TEST_CASE("D cos tables: a law reaching the ends of the table's range is refused, not truncated", "[sampling]") {
    CHECK_NOTHROW(DcosSampler(ggx(1e-40), true));
    CHECK_THROWS_WITH(DcosSampler(ggx(1e-49), true), Catch::Contains("1e-100"));
    CHECK_THROWS_WITH(DcosSampler(ggx(1e49), true), Catch::Contains("1e100"));
    CHECK_NOTHROW(DcosSampler(ggx(1e-49)));  // the analytic inversion has no range
}

TEST_CASE("reflected directions: pdf_m / (4 |i.m|) integrates to 1 over the sphere of outgoing directions",
          "[sampling][sweep]") {
    // o = reflect(i, m) and m = normalize(i + o): the Jacobian d omega_m / d omega_o = 1 / (4 |i.m|) (Walter 2007 eq.
    // 14).
    const Vec3 wi = direction_from_theta_deg(30.0);
    const Ggx g = ggx(0.3);
    const DcosSampler dcos(g);
    const VisibleNormalSampler vis(g);
    for (int which = 0; which < 2; ++which) {
        auto pdf_m = [&](const Vec3& m) { return which == 0 ? dcos.pdf(m) : vis.pdf(wi, m); };
        auto over_phi = [&](double z) {
            const double st = std::sqrt((1.0 - z) * (1.0 + z));
            return integrate(
                [&](double phi) {
                    const Vec3 o(st * std::cos(phi), st * std::sin(phi), z);
                    const Vec3 h = (wi + o).normalized();
                    return reflected_pdf(pdf_m(h), wi, h);
                },
                0.0, 2.0 * std::numbers::pi, {Backend::boost, 1e-9});
        };
        const double total = integrate(over_phi, -1.0, 1.0, {Backend::boost, 1e-9});
        // A facet facing away from wi (possible under D cos) sends o where the half vector is -m: those are lost,
        // so the D cos total is the mass of the facets facing wi, Hammon's Z (computed by a 1D quadrature).
        const double want = which == 0 ? HammonSampler(g).facing_fraction(wi) : 1.0;
        INFO((which == 0 ? "D cos" : "visible normals") << ": integral " << total << ", expected " << want);
        CHECK(std::abs(total - want) < 2e-6);  // the quadrature of a peaked integrand: a wrong Jacobian is O(1) off
        // And reflect() maps a sampled m to the o whose half vector is m.
        Rng rng = make_rng(5);
        const NormalSample s = which == 0 ? dcos.sample(rng) : vis.sample(wi, rng);
        CHECK((wi + reflect(wi, s.m)).normalized().isApprox(s.m, 1e-12));
    }
}

TEST_CASE("samplers: the same seed gives the same samples, and bad input is an error naming the item", "[sampling]") {
    const NdfRegistry ndfs = builtin_registry();
    const std::vector<SamplerInfo> samplers = builtin_samplers();
    const AnyNdf ndf = ndfs.make("gtr(alpha=0.2, gamma=1.5)");
    for (const SamplerInfo& s : samplers) {
        if (!s.applies(ndf)) continue;
        const BoundSampler b = prepare(s, ndf, direction_from_theta_deg(40.0));
        Rng g1 = make_rng(42), g2 = make_rng(42);
        for (int i = 0; i < 10; ++i) CHECK(b.sample(g1).m == b.sample(g2).m);
    }
    Rng g = make_rng(1);
    CHECK_THROWS_WITH(find_sampler(samplers, "nope"), Catch::Contains("nope") && Catch::Contains("vndf"));
    CHECK_NOTHROW(prepare(find_sampler(samplers, "vndf"), ndf, direction_from_theta_deg(120.0)));  // below: any wi
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf"), ndf, Vec3(0, 0, -1)), Catch::Contains("visible"));
    CHECK_THROWS_WITH(VisibleNormalSampler(ndf).sample(Vec3(0, 0, -1), g), Catch::Contains("visible"));
    CHECK_THROWS_WITH(sample_ggx_visible(0.3, Vec3(0, 0, -1), g), Catch::Contains("visible"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "hammon"), ndf, Vec3(0, 0, -1)), Catch::Contains("no microfacet"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf"), ndf, Vec3(0, 0, 2)), Catch::Contains("unit"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf-ggx"), ndf, Vec3(0, 0, 1)),
                      Catch::Contains("does not apply"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf-beckmann"), ndf, Vec3(0, 0, 1)),
                      Catch::Contains("does not apply"));
}

namespace {

// A(v) = integral over m.z > 0 of <v.m>^+ D(m) dm, by quadrature of the NDF's slope form alone (no Lambda): with
// D(m) dm = P22 dx dy / cos(theta_m) and v.m = cos(theta_m) (v.z - v_xy . (x, y)) for m = (-x, -y, 1) cos(theta_m),
//     A(v) = integral (v.z - |v_xy| r cos phi)^+ P22(r^2) r dr dphi,  v turned into the xz-plane,
// the azimuth by 20-point Gauss-Legendre where the integrand (a cosine) is positive, from its zero at cos phi = mu / r
// (exact to rounding there); r by adaptive Gauss-Kronrod on [0, |mu|] and [|mu|, inf), split at the kink.
template <class N>
double projected_area_by_quadrature(const N& ndf, const Vec3& v) {
    using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
    using GL = boost::math::quadrature::gauss<double, 20>;
    const double st = std::hypot(v.x(), v.y()), ct = v.z(), a = std::abs(ct / st), pi = std::numbers::pi;
    auto over_phi = [&](double r) {
        const double f = slope_density(ndf, r * r) * r;
        if (f == 0.0) return 0.0;
        if (st * r <= std::abs(ct)) return ct > 0.0 ? 2.0 * pi * ct * f : 0.0;
        const double phi_c = std::acos(ct / (st * r));  // positive on (phi_c, 2 pi - phi_c)
        return 2.0 * f *
            GL::integrate([&](double phi) { return std::max(0.0, ct - st * r * std::cos(phi)); }, phi_c, pi);
    };
    return GK::integrate(over_phi, 0.0, a, 12, 1e-11) + GK::integrate(over_phi, a, INFINITY, 12, 1e-11);
}

}  // namespace

TEST_CASE("projected area A(v) over the whole sphere: against quadrature of <v.m>^+ D, and A(v) - A(-v) = v.z",
          "[sampling]") {
    // Smith's convention Lambda(-mu) = -1 - Lambda(mu) (Heitz et al. 2016): A(v) = (1 + Lambda(v)) cos(theta_v) is the
    // projected area of the microsurface's facets facing v, above and below the horizon.
    const NdfRegistry ndfs = registry_with_donly();
    for (const char* spec : {"ggx(alpha=0.3)", "beckmann(alpha=0.3)", "gtr(alpha=0.3, gamma=1.5)", "blinn(n=20)",
                             "donly_ggx(alpha=0.3)"}) {
        const AnyNdf ndf = ndfs.make(spec);
        const VisibleNormals<AnyNdf> vn(ndf);
        // A tabulated Lambda (GTR, Blinn, D only) holds 1e-6 (its estimate; measured 1e-7); the closed forms 1e-9.
        const double tol = vn.Lambda().tabulated() ? 1e-6 : 1e-9;
        for (double t : {10.0, 45.0, 80.0, 89.9}) {
            const Vec3 v = direction_from_deg(t, 30.0), below = -v;
            const double up = projected_area_by_quadrature(ndf, v), down = projected_area_by_quadrature(ndf, below);
            INFO(spec << " theta " << t << ": A(v) " << vn.projected_area(v) << " quadrature " << up << "; A(-v) "
                      << vn.projected_area(below) << " quadrature " << down);
            CHECK(std::abs(vn.projected_area(v) - up) <= tol * up);
            CHECK(std::abs(vn.projected_area(below) - down) <= tol * down);
            CHECK(std::abs(up - down - v.z()) <= 1e-10 * up);  // the convention, on the independent route
            CHECK(std::abs(vn.projected_area(v) - vn.projected_area(below) - v.z()) <= 1e-15);
        }
        CHECK(vn.projected_area(Vec3(0, 0, 1)) == 1.0);
        CHECK(vn.projected_area(Vec3(0, 0, -1)) == 0.0);
        // Horizontal: A = E[x^+], the mean positive slope, the limit of mu Lambda(mu).
        const Vec3 h(1, 0, 0);
        CHECK(std::abs(vn.projected_area(h) - projected_area_by_quadrature(ndf, h)) <= 1e-9 * vn.projected_area(h));
    }
}

TEST_CASE("visible normals below the horizon: samples face v, any 64-bit generator, none straight down", "[sampling]") {
    // (That the pdf <v.m>^+ D / A(v) integrates to 1 is the projected-area test above; the chi-square cases integrate
    // it bin by bin as well.)
    const Ggx g = ggx(0.3);
    const VisibleNormals<Ggx> closed(g), rejection(g, VisibleRoute::rejection);
    CHECK(closed.closed_form());
    CHECK_FALSE(rejection.closed_form());
    for (double t : {100.0, 135.0, 170.0}) {
        const Vec3 v = direction_from_deg(t, 70.0);
        Rng rng = make_rng(11);
        for (int i = 0; i < 2000; ++i)
            for (const VisibleNormals<Ggx>* vn : {&closed, &rejection}) {
                const Vec3 m = vn->sample(v, rng);
                CHECK(m.z() > 0.0);
                CHECK(v.dot(m) > 0.0);
                CHECK(std::abs(m.norm() - 1.0) < 1e-12);
            }
    }
    // The templates take any 64-bit generator: the walk's counter-based one too.
    WalkRng w(1, 2, 3);
    CHECK(closed.sample(direction_from_theta_deg(135.0), w).z() > 0.0);
    CHECK(std::isnan(closed.sample(Vec3(0, 0, -1), w).x()));  // straight down: nothing is visible
    CHECK(std::isnan(rejection.sample(Vec3(0, 0, -1), w).x()));
}

TEST_CASE("Beckmann visible slopes: the x quantile against quadrature of (mu - x)^+ e^{-x^2}", "[sampling]") {
    // Independent route: the survival of w = -x, integral_w^inf (t - b) e^{-t^2} dt / integral_b^inf, by Gauss-Kronrod.
    using GK = boost::math::quadrature::gauss_kronrod<double, 61>;
    for (double mu : {30.0, 3.0, 1.0, 0.0, -0.5, -3.0, -10.0, -19.0}) {
        const double b = -mu;
        // Scaled by e^{b^2} for b > 0, so that the tail at b = 19 (e^{-361}) keeps its digits.
        const double c = std::max(b, 0.0);
        auto dens = [&](double t) { return (t - b) * std::exp((c - t) * (c + t)); };
        const double total = GK::integrate(dens, b, INFINITY, 15, 1e-14);
        for (double u : {1e-12, 1e-3, 0.3, 0.7, 0.999}) {
            const double w = -detail::beckmann_visible_slope(mu, u);
            const double S = GK::integrate(dens, w, INFINITY, 15, 1e-14) / total;
            INFO("mu " << mu << " u " << u << ": w " << w << " survival " << S);
            CHECK(w >= b);
            CHECK(std::abs(S - u) <= 1e-11 * u);
        }
    }
}

TEST_CASE("geometry: the orthonormal frame, refraction, half vectors and Jacobians", "[sampling]") {
    Rng rng = make_rng(3);
    auto random_unit = [&] {
        const double z = 2.0 * uniform01(rng) - 1.0, phi = 2.0 * std::numbers::pi * uniform01(rng);
        const double s = std::sqrt((1.0 - z) * (1.0 + z));
        return Vec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    // Duff et al. 2017: orthonormal and right-handed everywhere, -z and +z included.
    std::vector<Vec3> normals = {Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(1e-9, 0, -1).normalized(), Vec3(1, 0, 0)};
    for (int i = 0; i < 200; ++i) normals.push_back(random_unit());
    for (const Vec3& n : normals) {
        const Frame f(n);
        CHECK(std::abs(f.s.norm() - 1.0) < 1e-14);
        CHECK(std::abs(f.t.norm() - 1.0) < 1e-14);
        CHECK(std::abs(f.s.dot(f.t)) < 1e-14);
        CHECK((f.s.cross(f.t) - n).norm() < 1e-14);
        const Vec3 w = random_unit();
        CHECK((f.to_world(f.to_local(w)) - w).norm() < 1e-14);
        CHECK(std::abs(f.to_local(n).z() - 1.0) < 1e-14);
    }
    CHECK((direction_from_deg(135.0, 90.0) - Vec3(0, std::sqrt(0.5), -std::sqrt(0.5))).norm() < 1e-15);
    CHECK(direction_from_theta_deg(30.0) == direction_from_deg(30.0, 0.0));
    // Refraction: Snell's law eta_i sin_i = eta_t sin_t, coplanar with wi and m, on the far side; TIR refused.
    for (int i = 0; i < 200; ++i) {
        Vec3 m = random_unit(), wi = random_unit();
        if (m.z() < 0.0) m = -m;
        if (wi.dot(m) < 0.0) wi = -wi;
        for (double eta : {1.5, 1.0 / 1.5}) {
            Vec3 wt = Vec3::Zero();
            const double ci = wi.dot(m), si = std::sqrt(std::max(0.0, 1.0 - ci * ci));
            const bool ok = refract(wi, m, eta, wt);
            CHECK(ok == (si < eta));
            if (!ok) continue;
            CHECK(std::abs(wt.norm() - 1.0) < 1e-12);
            CHECK(wt.dot(m) < 0.0);
            CHECK(std::abs(si - eta * wt.cross(m).norm()) < 1e-12);
            CHECK(std::abs(wt.dot(wi.cross(m))) < 1e-12);
            // Walter eq. 16 recovers the facet normal (up to orientation), eq. 13 likewise for reflection.
            CHECK(std::abs(std::abs(half_vector_transmission(wi, wt, eta).dot(m)) - 1.0) < 1e-12);
            CHECK((half_vector_reflection(wi, reflect(wi, m)) - std::copysign(1.0, wi.z()) * m).norm() < 1e-12);
            // Walter eq. 17 and 14 against the area ratio of the images of a small patch of normals.
            const Frame f(m);
            const double e = 1e-6;
            auto image = [&](const Vec3& n, bool transmit) {
                Vec3 o = Vec3::Zero();
                if (!transmit) return reflect(wi, n);
                refract(wi, n, eta, o);
                return o;
            };
            for (bool transmit : {false, true}) {
                const Vec3 o = image(m, transmit);
                const Vec3 d1 = image((m + e * f.s).normalized(), transmit) - o;
                const Vec3 d2 = image((m + e * f.t).normalized(), transmit) - o;
                const double dwo_dm = d1.cross(d2).norm() / (e * e);
                const double want = 1.0 / (transmit ? dm_dwo_refraction(wi, o, m, eta) : dm_dwo_reflection(o, m));
                INFO("eta " << eta << (transmit ? " refraction" : " reflection") << ": finite differences " << dwo_dm
                            << ", Walter " << want);
                // (Away from grazing, where the finite differences lose their digits.)
                if (std::abs(o.dot(m)) > 0.05 && want < 1e3) CHECK(std::abs(dwo_dm - want) < 1e-4 * want);
            }
        }
    }
}
