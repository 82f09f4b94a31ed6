/// @file
/// smithlab/walk/lambert.hpp -- the facet material `Lambert` (Lambertian facets): how a facet scatters (sample), its
/// phase function (phase), and its registration (info, make, spec; material_registry.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

/// Lambertian facets (Heitz et al. 2016, sec. 5.3, the diffuse microsurface): each reflects albedo / pi about m.
struct Lambert {
    double albedo;                            ///< the facets' reflectance, in [0, 1]
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The registration (material_registry.hpp): name, parameters and description; the material a checked spec
    /// makes; and its spec back.
    ///@{
    static MaterialInfo info() {
        return {"lambert",
                {{"albedo", 1.0, 0.0, 1.0}},
                "Lambertian facets, each reflecting albedo / pi about its normal (albedo in [0, 1]; Heitz et al. 2016, "
                "sec. 5.3)"};
    }
    static Lambert make(const MaterialParams& p) { return {p.at("albedo")}; }
    NdfSpec spec() const { return {"lambert", {{"albedo", albedo}}}; }
    ///@}
    /// Whether any event is diffuse (albedo > 0).
    bool has_diffuse() const { return albedo > 0.0; }
    /// A cosine-distributed direction about m (Malley), weight albedo; absorbed where albedo is 0.
    template <class G>
    Scatter sample(const Vec3&, const Vec3& m, G& g) const {
        if (albedo == 0.0) return {m, 0.0, true};
        return {detail::about(m, std::sqrt(uniform01(g)), g), albedo, true};  // Malley: cos = sqrt(u)
    }
    /// The one-sample estimate albedo / pi `<`wo.m`>` over m ~ D_wi (Heitz et al. 2016, sec. 5.3); no specular part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G& g) const {
        if (albedo == 0.0) return {};
        const Vec3 m = ms.visible_normal(wi, g);
        return {0.0, albedo / std::numbers::pi * std::max(0.0, wo.dot(m))};
    }
};

}  // namespace smithlab::walk
