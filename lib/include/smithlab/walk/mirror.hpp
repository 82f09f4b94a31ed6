/// @file
/// smithlab/walk/mirror.hpp -- the facet material `Mirror` (every facet a perfect mirror): how a facet scatters
/// (sample), its phase function (phase), and its registration (info, make, spec; material_registry.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

/// F = 1: every facet a perfect mirror.
struct Mirror {
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The registration (material_registry.hpp): name, parameters and description; the material a checked spec
    /// makes; and its spec back.
    ///@{
    static MaterialInfo info() { return {"mirror", {}, "every facet a perfect mirror (F = 1)"}; }
    static Mirror make(const MaterialParams&) { return {}; }
    NdfSpec spec() const { return {"mirror", {}}; }
    ///@}
    /// The mirror reflection of wi about m, weight 1.
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G&) const {
        return {reflect(wi, m), 1.0, false};
    }
    /// D(h) / (4 A(wi)), h the half vector (Heitz et al. 2016 eq. 20 with Walter 2007 eq. 14); no diffuse part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G&) const {
        return {detail::mirror_phase(ms, wi, wo, [](double) { return 1.0; }), 0.0};
    }
};

}  // namespace smithlab::walk
