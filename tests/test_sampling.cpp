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

// GGX written as D alone: no slope form, no sampler, no Lambda. Everything is derived (tabulated) for it.
struct DOnlyGgx {
    double alpha;
    double D(double c) const {
        if (c <= 0.0) return 0.0;
        const double s = (1.0 - c) * (1.0 + c) + alpha * alpha * c * c;
        return alpha * alpha / (std::numbers::pi * s * s);
    }
};

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
    r.add({"donly_ggx", {"alpha"}, "GGX as D alone", {"donly_ggx(alpha=0.3)"}},
          [](const NdfParams& p) { return DOnlyGgx{p.at("alpha")}; });
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

TEST_CASE("chi-square: visible-normal samplers, generic and GGX, normal to grazing incidence", "[sampling][chi2]") {
    run_chi2("vndf");
}

TEST_CASE("chi-square: Hammon's facing-restricted D cos, rays going down and up", "[sampling][chi2]") {
    run_chi2("hammon");
}
