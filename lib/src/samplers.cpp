#include "smithlab/samplers.hpp"

#include <cmath>
#include <memory>

#include "smithlab/errors.hpp"

namespace smithlab {

namespace {

using Incidence = SamplerInfo::Incidence;

bool any_ndf(const AnyNdf&) { return true; }
// The capabilities (ndf.hpp): the NDF is exactly GGX / Beckmann of some alpha.
bool is_ggx(const AnyNdf& n) { return !std::isnan(ggx_alpha(n)); }
bool is_beckmann(const AnyNdf& n) { return !std::isnan(beckmann_alpha(n)); }
// A mixture of GGX lobes bounds its slope density (detail/visible_normals_mixture.hpp). Only the D cos law and the fit
// are built here; the sampler's other tables (its Lambda), and their refusal of an NDF beyond them, come when it is
// prepared.
bool has_mixture(const AnyNdf& n) { return fit_ggx_mixture(n, DcosLaw<AnyNdf>(n)).has_value(); }

BoundSampler dcos(const AnyNdf& ndf, bool tabulate) {
    auto s = std::make_shared<const DcosSampler>(ndf, tabulate);
    return {[s](Rng& g) { return s->sample(g); }, [s](const Vec3& m) { return s->pdf(m); }, s->table_error()};
}

// Visible normals of wi by a route; input_error at once when no normal is visible from wi.
BoundSampler visible(const AnyNdf& ndf, const Vec3& wi, VisibleRoute route) {
    auto s = std::make_shared<const VisibleNormalSampler>(ndf, route);
    if (!(s->projected_area(wi) > 0.0))
        throw input_error("visible-normal sampler: no microfacet normal of '" + ndf.spec() +
                          "' is visible from wi (straight down, or a projected area that underflows in double)");
    return {[s, wi](Rng& g) { return s->sample(wi, g); }, [s, wi](const Vec3& m) { return s->pdf(wi, m); },
            s->table_error()};
}

}  // namespace

std::vector<SamplerInfo> builtin_samplers() {
    return {
        {"dcos",
         "D(m) cos(theta_m): the NDF's analytic inversion (GGX, Beckmann, Blinn, GTR by Burley 2012), else tabulated",
         Incidence::ignored, any_ndf, [](const AnyNdf& n, const Vec3&) { return dcos(n, false); }},
        {"dcos-table", "D(m) cos(theta_m) by a tabulated inverse CDF of pi P22(tan^2), for any NDF", Incidence::ignored,
         any_ndf, [](const AnyNdf& n, const Vec3&) { return dcos(n, true); }},
        {"vndf",
         "visible normals <wi.m>^+ D / A(wi), wi anywhere, any NDF: slope-space rejection (Heitz & d'Eon 2014 law)",
         Incidence::any, any_ndf,
         [](const AnyNdf& n, const Vec3& wi) { return visible(n, wi, VisibleRoute::rejection); }},
        {"vndf-table", "visible normals as vndf, with the D cos part tabulated too (what a D-only NDF gets)",
         Incidence::any, any_ndf,
         [](const AnyNdf& n, const Vec3& wi) { return visible(n, wi, VisibleRoute::tabulated); }},
        {"vndf-mixture",
         "visible normals of any NDF with tails up to GGX's: GGX lobes' visible normals accepted with P22 / (K Q), "
         "exact, wi anywhere (what the walk uses)",
         Incidence::any, has_mixture,
         [](const AnyNdf& n, const Vec3& wi) { return visible(n, wi, VisibleRoute::mixture); }},
        {"vndf-ggx", "GGX visible normals in closed form, spherical caps (Dupuy & Benyoub 2023), wi anywhere",
         Incidence::any, is_ggx, [](const AnyNdf& n, const Vec3& wi) { return visible(n, wi, VisibleRoute::closed); }},
        {"vndf-beckmann",
         "Beckmann visible normals in closed form (Heitz & d'Eon 2014 slopes, Newton on ierfc), wi anywhere",
         Incidence::any, is_beckmann,
         [](const AnyNdf& n, const Vec3& wi) { return visible(n, wi, VisibleRoute::closed); }},
        {"hammon",
         "D(m) cos(theta_m) over the normals facing wi, Hammon 2017's shrunk range (ray T = -wi; wi may be below)",
         Incidence::any, any_ndf,
         [](const AnyNdf& n, const Vec3& wi) -> BoundSampler {
             auto s = std::make_shared<const HammonSampler>(n);
             const double Z = s->facing_fraction(wi);
             if (!(Z > 0.0)) throw input_error("hammon sampler: no microfacet faces this direction");
             return {[s, wi, Z](Rng& g) {
                         const Vec3 m = s->sample_normal(wi, g);
                         return NormalSample{m, s->pdf(wi, m, Z)};
                     },
                     [s, wi, Z](const Vec3& m) { return s->pdf(wi, m, Z); }, 0.0};
         }},
    };
}

const SamplerInfo& find_sampler(const std::vector<SamplerInfo>& samplers, std::string_view name) {
    std::string known;
    for (const SamplerInfo& s : samplers) {
        if (s.name == name) return s;
        known += (known.empty() ? "" : ", ") + s.name;
    }
    throw input_error("unknown sampler '" + std::string(name) + "' (known: " + known + ")");
}

BoundSampler prepare(const SamplerInfo& sampler, const AnyNdf& ndf, const Vec3& wi) {
    if (!sampler.applies(ndf))
        throw input_error("sampler '" + sampler.name + "' does not apply to ndf '" + ndf.spec() + "'");
    if (!(std::abs(wi.squaredNorm() - 1.0) < 1e-9))
        throw input_error("sampler '" + sampler.name + "': wi is not a unit vector");
    if (sampler.incidence == SamplerInfo::Incidence::upper && !(wi.z() > 0.0))
        throw input_error("sampler '" + sampler.name +
                          "' needs an incident direction above the surface (theta_i < 90)");
    return sampler.prepare(ndf, wi);
}

}  // namespace smithlab
