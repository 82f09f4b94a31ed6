/// @file
/// smithlab/walk/facets.hpp -- what a single facet does with light: the interface of the facet materials of the
/// microsurface walk, and what they share.
///
/// Each material, in the frame of the macrosurface, with wi pointing away from the facet toward where the light came
/// from and m the facet's normal (wi.m > 0):
///   sample(wi, m, g)      the next direction and the weight it carries (0: absorbed), and whether the event
///                         was diffuse;
///   phase(ms, wi, wo, g)  the phase function rho(wi -> wo) = integral of D_wi(m) f_m(wi, wo) <wo.m> dm over the
///                         visible normals D_wi of wi, the density (with its weight) of the next direction, split
///                         into its specular and diffuse parts: analytic where the facet is a mirror (the half vector
///                         decides m: F D(h) / (4 A(wi)), Heitz et al. 2016 eq. 20 with Walter 2007 eq. 14),
///                         one-sample estimates over m ~ D_wi where it is diffuse (Heitz et al. 2016, sec. 5.3).
/// A two-sided material (TwoSided: the dielectric) lets rays through to the other side of the microsurface. It works,
/// as every material does, in the frame of the side the ray is on (walk.hpp: below the surface, every vector and
/// height negated, where the microsurface looks as it does from above), and is told which side that is.
/// The built-in materials have a file each (mirror.hpp, conductor.hpp, lambert.hpp, fresnel_diffuse.hpp,
/// dielectric.hpp); any type with these members is a material (docs/extending.md), registered by name in a
/// MaterialRegistry (material_registry.hpp) and held as a walk::Material (material.hpp).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/fresnel.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/rng.hpp"
#include "smithlab/turn.hpp"

namespace smithlab::walk {

/// What sample returns: the next direction, the weight it carries, and what kind of event it was.
struct Scatter {
    Vec3 wo;                   ///< the next direction, unit, in the frame of the side the ray is on
    double weight;             ///< 0: absorbed
    bool diffuse;              ///< whether the event was diffuse (counted in the diffuse orders, walk.hpp)
    bool transmitted = false;  ///< through to the other side (two-sided materials only)
};

/// What phase returns: the phase function rho(wi -> wo), per steradian, split into its specular and diffuse parts.
struct Phase {
    /// The mirror part (analytic) and the diffuse part (one-sample estimate).
    ///@{
    double specular = 0.0, diffuse = 0.0;
    ///@}
};

namespace detail {
/// The specular part of a phase function, F(wi.h) D(h) / (4 A(wi)), h the half vector of wi and wo.
template <class Microsurface, class Fresnel>
double mirror_phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, Fresnel F) {
    Vec3 h = wi + wo;
    const double n2 = h.squaredNorm();
    if (!(n2 > 0.0) || !(h.z() > 0.0)) return 0.0;
    h /= std::sqrt(n2);
    const double c = wi.dot(h);
    if (!(c > 0.0)) return 0.0;
    return F(c) * ms.normals().D(h) / (4.0 * ms.normals().projected_area(wi));
}

/// A direction about m with cos(theta) = c and a uniform azimuth.
template <class G>
Vec3 about(const Vec3& m, double c, G& g) {
    const double s = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
    const CosSin phi = cos_sin_turn(uniform01(g));  // turn.hpp: 2 pi u without libm's argument reduction
    return Frame(m).to_world(Vec3(s * phi.c, s * phi.s, c));
}

/// Hammon 2017 appendix, "Transmission Direction": cos(theta) about the facet normal drawn from the lobe
/// k (1 - (1 - c)^5) c, k = 21 / (20 pi), whose CDF in c is
///     Y(c) = 7/2 c^3 - 21/4 c^4 + 21/5 c^5 - 7/4 c^6 + 3/10 c^7,
/// solved for Y = u by Newton's method from Shirley's rational first guess (the slide's), kept in [0, 1] by bisection.
double hammon_lobe_cos(double u);
}  // namespace detail

template <class M>
concept TwoSided = requires {
    requires M::two_sided;
};

/// A one-sided material whose facet BRDF is symmetric in wi and wo: its microsurface's BSDF is then reciprocal under
/// Smith's downward convention, f(wi, wo) = f(wo, wi) (Heitz et al. 2016, sec. 5, the walk's BSDF; test_walk checks
/// it for every material here), and it says so (`static constexpr bool reciprocal = true`);
/// EvalEstimator::reciprocal relies on it (walk.hpp).
template <class M>
concept Reciprocal = !TwoSided<M> && requires {
    requires M::reciprocal;
};

/// What a material type may say about itself, each optional: whether any of its events is diffuse (the tallies of
/// the diffuse component exist only then; default: none is), and where its BSDF holds a Dirac delta that the eval
/// estimator has no finite density for (default: nowhere).
///@{
template <class M>
bool material_has_diffuse(const M& m) {
    if constexpr (requires { m.has_diffuse(); }) return m.has_diffuse();
    else return false;
}
template <class M>
bool material_dirac_at(const M& m, const Vec3& wi, const Vec3& wo) {
    if constexpr (requires { m.dirac_at(wi, wo); }) return m.dirac_at(wi, wo);
    else return false;
}
///@}

}  // namespace smithlab::walk
