// The samplers: chi-square goodness of fit for every sampler on every registered NDF family (and a D-only one),
// alpha down to 1e-3, normal to grazing incidence; pdfs that integrate to 1; the tables against the analytic
// inversions; the reflection Jacobian; bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <smithlab/smithlab.hpp>
#include <string>
#include <vector>

#include "chi2.hpp"

using namespace smithlab;

namespace {

struct Case {
    std::string sampler, spec;
    double theta_i;
};

std::vector<std::string> ndf_specs() {
    return {"ggx(alpha=1)",           "ggx(alpha=0.3)",         "ggx(alpha=0.001)",
            "beckmann(alpha=1)",      "beckmann(alpha=0.3)",    "beckmann(alpha=0.001)",
            "blinn(n=1)",             "blinn(n=20)",            "blinn(n=2000000)",
            "gtr(alpha=0.3, gamma=0.5)", "gtr(alpha=0.001, gamma=1)", "gtr(alpha=0.3, gamma=1.5)",
            "gtr(alpha=0.5, gamma=3.3)", "gtr(alpha=0.001, gamma=10)", "gtr(alpha=1, gamma=4)",
            "gtr(alpha=0.3, gamma=2)",   "donly_ggx(alpha=0.3)"};
}

NdfRegistry registry_with_donly() {
    NdfRegistry r = builtin_registry();
    // GGX as D alone: no slope form, no sampler, no Lambda; everything is derived (tabulated) for it.
    r.add({"donly_ggx", {"alpha"}, "GGX as D alone", {"donly_ggx(alpha=0.3)"}},
          [](const NdfParams& p) { return DOnly<Ggx>{ggx(p.at("alpha"))}; });
    return r;
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
                                               : s.incidence == I::upper ? std::vector<double>{0.0, 45.0, 89.0}
                                                                         : std::vector<double>{89.0, 100.0, 150.0};
            for (double t : thetas) cases.push_back({s.name, spec, t});
        }
    return cases;
}

// Runs the cases whose sampler name starts with `prefix`.
void run_chi2(const std::string& prefix) {
    const NdfRegistry ndfs = registry_with_donly();
    const std::vector<SamplerInfo> samplers = builtin_samplers();
    const std::vector<Case> cases = all_cases(ndfs, samplers);
    const double alpha_1 = chi2::sidak(0.01, cases.size());
    INFO(cases.size() << " tests in all, per-test significance " << alpha_1);
    Rng rng = make_rng(20261122);
    int ran = 0;
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        if (c.sampler.rfind(prefix, 0) != 0) continue;
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
        const BoundSampler bound = prepare(find_sampler(samplers, c.sampler), ndf, wi);
        // The bins' slope scale: the median tan(theta_m) of 1001 pilot samples from their own stream.
        chi2::Bins bins;
        bins.scale = chi2::median_slope(bound, 1001, make_rng(7, k));
        const chi2::Result r = chi2::test(bound, bins, 100000, rng);
        INFO(c.sampler << " on " << c.spec << " at theta_i = " << c.theta_i << ": chi2 = " << r.statistic << ", dof "
                       << r.dof << ", p = " << r.p_value << ", pdf integral " << r.pdf_integral << " " << r.note);
        CHECK(r.bad_samples == 0);
        // Hammon's pdf jumps at the facing boundary; the bins' adaptive quadrature resolves a jump to ~1e-4.
        CHECK(std::abs(r.pdf_integral - 1.0) < (c.sampler == "hammon" ? 1e-3 : 1e-5));
        CHECK(r.p_value >= alpha_1);
    }
    CHECK(ran > 0);
}

}  // namespace

TEST_CASE("chi-square: D cos samplers, analytic and tabulated, every NDF family, alpha to 1e-3", "[sampling][chi2]") {
    run_chi2("dcos");
}

TEST_CASE("chi-square: visible-normal samplers, generic and GGX, normal to grazing incidence", "[sampling][chi2][slow]") {
    run_chi2("vndf");
}

TEST_CASE("chi-square: Hammon's facing-restricted D cos, rays going down and up", "[sampling][chi2][slow]") {
    run_chi2("hammon");
}

TEST_CASE("D cos laws: the analytic survival functions against quadrature of pi P22, and their inverses", "[sampling]") {
    // Independent route: S(s) = pi * integral_s^inf P22 by Boost quadrature on the slope density, not the inversions.
    auto check = [](const auto& ndf, const std::string& what) {
        for (double s : {1e-12, 1e-7, 1e-4, 0.01, 0.3, 1.0, 3.0, 100.0, 1e6}) {
            const double want = integrate([&](double x) { return std::numbers::pi * slope_density(ndf, x); }, s, INFINITY,
                                          {Backend::boost, 1e-13});
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
        for (double g : {0.0, 0.5, 1.0, 1.0 + 1e-9, 1.5, 2.0, 3.3, 20.0}) check(gtr(a, g), "gtr " + std::to_string(a) + " " + std::to_string(g));
    }
    check(gtr(0.999999, 2.5), "gtr 0.999999");
    check(gtr(1e-30, 2.5), "gtr 1e-30 2.5");
    check(gtr(1e-30, 25.0), "gtr 1e-30 25");  // (gamma - 1) ln(1/alpha^2) = 3300: expm1 would overflow
    for (double n : {0.0, 1.0, 20.0, 1e4}) check(blinn(n), "blinn " + std::to_string(n));
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
    };
    compare(ggx(1e-3), "ggx(1e-3)");
    compare(beckmann(0.3), "beckmann(0.3)");
    compare(gtr(1e-3, 1.0), "gtr(1e-3, 1)");
    compare(gtr(0.5, 20.0), "gtr(0.5, 20)");
    compare(blinn(20.0), "blinn(20)");
}

TEST_CASE("D cos tables: a law reaching the ends of the table's range is refused, not truncated", "[sampling]") {
    CHECK_NOTHROW(DcosSampler(ggx(1e-40), true));
    CHECK_THROWS_WITH(DcosSampler(ggx(1e-49), true), Catch::Contains("1e-100"));
    CHECK_THROWS_WITH(DcosSampler(ggx(1e49), true), Catch::Contains("1e100"));
    CHECK_NOTHROW(DcosSampler(ggx(1e-49)));  // the analytic inversion has no range
}

TEST_CASE("reflected directions: pdf_m / (4 |i.m|) integrates to 1 over the sphere of outgoing directions", "[sampling]") {
    // o = reflect(i, m) and m = normalize(i + o): the Jacobian d omega_m / d omega_o = 1 / (4 |i.m|) (Walter 2007 eq. 14).
    const Vec3 wi = direction_from_theta_deg(30.0);
    const Ggx g = ggx(0.3);
    const DcosSampler dcos(g);
    const VisibleNormalSampler vis(g);
    for (int which = 0; which < 2; ++which) {
        auto pdf_m = [&](const Vec3& m) { return which == 0 ? dcos.pdf(m) : vis.pdf(wi, m); };
        auto over_phi = [&](double z) {
            const double st = std::sqrt((1.0 - z) * (1.0 + z));
            return integrate([&](double phi) {
                const Vec3 o(st * std::cos(phi), st * std::sin(phi), z);
                const Vec3 h = (wi + o).normalized();
                return reflected_pdf(pdf_m(h), wi, h);
            }, 0.0, 2.0 * std::numbers::pi, {Backend::boost, 1e-9});
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
    CHECK_THROWS_WITH(find_sampler(samplers, "nope"), Catch::Contains("nope") && Catch::Contains("vndf"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf"), ndf, direction_from_theta_deg(120.0)), Catch::Contains("above"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "hammon"), ndf, Vec3(0, 0, -1)), Catch::Contains("no microfacet"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf"), ndf, Vec3(0, 0, 2)), Catch::Contains("unit"));
    CHECK_THROWS_WITH(prepare(find_sampler(samplers, "vndf-ggx"), ndf, Vec3(0, 0, 1)), Catch::Contains("does not apply"));
}
