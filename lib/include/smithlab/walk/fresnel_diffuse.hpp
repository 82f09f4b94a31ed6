/// @file
/// smithlab/walk/fresnel_diffuse.hpp -- the facet material `FresnelDiffuse` (Hammon 2017's facets): how a facet
/// scatters (sample), its phase function (phase), and its registration (info, make, spec; material_registry.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

/// Hammon 2017's facets ("Reflection/Transmission", "Transmission Direction"): Schlick F reflects specularly; the
/// rest enters, is tinted by albedo, and leaves through the facet again into the lobe k (1 - (1 - cos)^5) cos about m,
/// k = 21 / (20 pi): facet BRDF F spec + (1 - F(wi.m)) albedo k (1 - (1 - wo.m)^5), symmetric in wi and wo.
/// The branch is chosen with probability F (Russian roulette between the two, unbiased), so weights stay in [0, 1].
struct FresnelDiffuse {
    /// Schlick's F at normal incidence, and the tint of the diffuse part, both in [0, 1].
    ///@{
    double f0, albedo;
    ///@}
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The diffuse lobe's normalization, 21 / (20 pi) (Hammon 2017).
    static constexpr double k = 21.0 / (20.0 * std::numbers::pi);

    /// The registration (material_registry.hpp): name, parameters and description; the material a checked spec
    /// makes; and its spec back.
    ///@{
    static MaterialInfo info() {
        return {"fresnel-diffuse",
                {{"f0", 0.02, 0.0, 1.0}, {"albedo", 1.0, 0.0, 1.0}},
                "Hammon 2017's facets: Schlick's F (f0 at normal incidence) reflects specularly, the rest leaves "
                "diffusely, tinted by albedo (both in [0, 1])"};
    }
    static FresnelDiffuse make(const MaterialParams& p) { return {p.at("f0"), p.at("albedo")}; }
    NdfSpec spec() const { return {"fresnel-diffuse", {{"f0", f0}, {"albedo", albedo}}}; }
    ///@}
    /// Whether any event is diffuse (albedo > 0).
    bool has_diffuse() const { return albedo > 0.0; }
    /// With probability F(wi.m) the mirror reflection (weight 1), else a direction of the Hammon lobe about m (weight
    /// albedo).
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G& g) const {
        if (uniform01(g) < fresnel_schlick(f0, wi.dot(m))) return {reflect(wi, m), 1.0, false};
        if (albedo == 0.0) return {m, 0.0, true};
        return {detail::about(m, detail::hammon_lobe_cos(uniform01(g)), g), albedo, true};
    }
    /// The specular part F(wi.h) D(h) / (4 A(wi)), and the diffuse part's one-sample estimate over m ~ D_wi,
    /// (1 - F(wi.m)) albedo k (1 - (1 - wo.m)^5) wo.m.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G& g) const {
        Phase p{detail::mirror_phase(ms, wi, wo, [this](double c) { return fresnel_schlick(f0, c); }), 0.0};
        if (albedo == 0.0) return p;
        const Vec3 m = ms.visible_normal(wi, g);
        const double c = wo.dot(m);
        if (c > 0.0) {
            const double t = 1.0 - c, t5 = t * t * t * t * t;
            p.diffuse = (1.0 - fresnel_schlick(f0, wi.dot(m))) * albedo * k * (1.0 - t5) * c;
        }
        return p;
    }
};

}  // namespace smithlab::walk
