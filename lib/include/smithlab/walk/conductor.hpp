/// @file
/// smithlab/walk/conductor.hpp -- the facet material `Conductor` (mirror facets of a conductor): how a facet scatters
/// (sample), its phase function (phase), and its registration (info, make, spec; material_registry.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

/// Mirror facets of a conductor, complex index eta + i k, with the exact Fresnel reflectance (fresnel.hpp).
struct Conductor {
    /// The complex index eta + i k (relative to the medium above).
    ///@{
    double eta, k;
    ///@}
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The registration (material_registry.hpp): name, parameters and description; the material a checked spec
    /// makes; and its spec back.
    ///@{
    static MaterialInfo info() {
        return {"conductor",
                {{"eta", NAN, 1e-6, 1e6}, {"k", NAN, 0.0, 1e6}},
                "mirror facets of a conductor of complex index eta + i k (both required; eta in [1e-6, 1e6], k in [0, "
                "1e6]), the exact Fresnel reflectance"};
    }
    static Conductor make(const MaterialParams& p) { return {p.at("eta"), p.at("k")}; }
    NdfSpec spec() const { return {"conductor", {{"eta", eta}, {"k", k}}}; }
    ///@}
    /// The mirror reflection of wi about m, its weight the Fresnel reflectance F(wi.m).
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G&) const {
        return {reflect(wi, m), fresnel_conductor(wi.dot(m), eta, k), false};
    }
    /// F(wi.h) D(h) / (4 A(wi)), h the half vector (Heitz et al. 2016 eq. 20 with Walter 2007 eq. 14); no diffuse part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G&) const {
        return {detail::mirror_phase(ms, wi, wo, [this](double c) { return fresnel_conductor(c, eta, k); }), 0.0};
    }
};

}  // namespace smithlab::walk
