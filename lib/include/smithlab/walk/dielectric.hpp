/// @file
/// smithlab/walk/dielectric.hpp -- the facet material `Dielectric` (a smooth dielectric interface): how a facet
/// scatters (sample), its phase function (phase), and its registration (info, make, spec; material_registry.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab::walk {

/// A smooth dielectric interface on every facet, index eta below the surface over that above (Heitz et al. 2016,
/// sec. 6.2, the dielectric microsurface): the exact Fresnel reflectance F (fresnel.hpp) reflects, 1 - F refracts
/// (Snell), chosen with probability F (weights stay 1). On the side below, the relative index is 1 / eta and past the
/// critical angle everything reflects. The phase function toward wo, the part of it that leaves along wo from this
/// side: reflection when wo.z > 0 (F D(h) / (4 A(wi)), as for mirrors), refraction when wo.z < 0,
///     (1 - F(wi.h)) <wi.h> D(h) / A(wi) |d omega_h / d omega_o|,  h = -(wi + eta' wo) / |.| turned up,
/// the Jacobian Walter 2007 eq. 17 (geometry.hpp, dm_dwo_refraction), eta' the relative index on this side.
struct Dielectric {
    double eta;                              ///< the index below the surface over that above
    static constexpr bool two_sided = true;  ///< light goes through to the other side (TwoSided, facets.hpp)

    /// The registration (material_registry.hpp): name, parameters and description; the material a checked spec
    /// makes; and its spec back.
    ///@{
    static MaterialInfo info() {
        return {"dielectric",
                {{"eta", 1.5, 1e-3, 1e3}},
                "a smooth dielectric interface on every facet, eta the index below over that above (in [1e-3, 1e3]): "
                "reflection and transmission, light from above or below (Heitz et al. 2016, sec. 6.2)"};
    }
    static Dielectric make(const MaterialParams& p) { return {p.at("eta")}; }
    NdfSpec spec() const { return {"dielectric", {{"eta", eta}}}; }
    ///@}
    /// Index-matched (eta = 1), it neither reflects nor bends light: every ray leaves along -wi, a Dirac delta at
    /// wo = -wi (within 1e-9 of a unit vector: the rounding of directions given in degrees) the eval estimator has no
    /// finite density for.
    bool dirac_at(const Vec3& wi, const Vec3& wo) const { return eta == 1.0 && (wi + wo).norm() <= 1e-9; }
    /// Reflection about m with probability F(wi.m), else refraction (Snell; reflection past the critical angle),
    /// weight 1; `above`: the side the ray is on.
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G& g, bool above) const {
        const double e = above ? eta : 1.0 / eta;
        Vec3 t;
        if (uniform01(g) < fresnel_dielectric(wi.dot(m), e) || !refract(wi, m, e, t))
            return {reflect(wi, m), 1.0, false};
        return {t, 1.0, false, true};
    }
    /// The reflected or the refracted part toward wo from the side `above` names (the formulas above); no diffuse part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G&, bool above) const {
        const double e = above ? eta : 1.0 / eta;
        if (wo.z() > 0.0)
            return {detail::mirror_phase(ms, wi, wo, [e](double c) { return fresnel_dielectric(c, e); }), 0.0};
        Vec3 h = half_vector_transmission(wi, wo, e);
        if (h.z() < 0.0) h = -h;
        const double ci = wi.dot(h);
        if (!(ci > 0.0 && wo.dot(h) < 0.0) || !(h.z() > 0.0)) return {};
        return {(1.0 - fresnel_dielectric(ci, e)) * ci * ms.normals().D(h) / ms.normals().projected_area(wi) *
                    dm_dwo_refraction(wi, wo, h, e),
                0.0};
    }
};

}  // namespace smithlab::walk
