/// @file
/// smithlab/walk/facets.hpp -- what a single facet does with light: the facet materials of the microsurface walk.
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
/// The closed set of materials is a std::variant (Material), visited once per block of walks, never per bounce.
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <variant>

#include "smithlab/fresnel.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/rng.hpp"
#include "smithlab/turn.hpp"

namespace smithlab::walk {

/// What one event of a material does: the next direction and the weight it carries.
struct Scatter {
    /// The next direction, away from the facet (on the other side when transmitted).
    Vec3 wo;
    double weight;  ///< 0: absorbed
    /// Whether the event was diffuse (it counts toward the diffuse tallies and the diffuse events of the walk).
    bool diffuse;
    bool transmitted = false;  ///< through to the other side (two-sided materials only)
};

/// The phase function of a material toward wo (the file comment), split into its specular and diffuse parts.
struct Phase {
    /// The part from specular events (mirror facets, the half vector's) and the part from diffuse ones.
    /// @{
    double specular = 0.0, diffuse = 0.0;
    /// @}
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

/// F = 1: every facet a perfect mirror.
struct Mirror {
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The mirror reflection of wi about m, weight 1.
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G&) const {
        return {reflect(wi, m), 1.0, false};
    }
    /// D(h) / (4 A(wi)), h the half vector of wi and wo (F = 1); no diffuse part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G&) const {
        return {detail::mirror_phase(ms, wi, wo, [](double) { return 1.0; }), 0.0};
    }
};

/// Mirror facets of a conductor, complex index eta + i k, with the exact Fresnel reflectance (fresnel.hpp).
struct Conductor {
    /// The complex index eta + i k: eta in [1e-6, 1e6], k in [0, 1e6].
    /// @{
    double eta, k;
    /// @}
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The mirror reflection of wi about m, weighted by the Fresnel reflectance F(wi.m).
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G&) const {
        return {reflect(wi, m), fresnel_conductor(wi.dot(m), eta, k), false};
    }
    /// F(wi.h) D(h) / (4 A(wi)), h the half vector of wi and wo; no diffuse part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G&) const {
        return {detail::mirror_phase(ms, wi, wo, [this](double c) { return fresnel_conductor(c, eta, k); }), 0.0};
    }
};

/// Lambertian facets (Heitz et al. 2016, sec. 5.3, the diffuse microsurface): each reflects albedo / pi about m.
struct Lambert {
    /// The facets' albedo, in [0, 1].
    double albedo;
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// A cosine-distributed direction about m (Malley's method), weight albedo; a diffuse event.
    template <class G>
    Scatter sample(const Vec3&, const Vec3& m, G& g) const {
        if (albedo == 0.0) return {m, 0.0, true};
        return {detail::about(m, std::sqrt(uniform01(g)), g), albedo, true};  // Malley: cos = sqrt(u)
    }
    /// The diffuse part albedo / pi <wo.m>, estimated at one visible normal m of wi; no specular part.
    template <class Microsurface, class G>
    Phase phase(const Microsurface& ms, const Vec3& wi, const Vec3& wo, G& g) const {
        if (albedo == 0.0) return {};
        const Vec3 m = ms.visible_normal(wi, g);
        return {0.0, albedo / std::numbers::pi * std::max(0.0, wo.dot(m))};
    }
};

/// Hammon 2017's facets ("Reflection/Transmission", "Transmission Direction"): Schlick F reflects specularly; the
/// rest enters, is tinted by albedo, and leaves through the facet again into the lobe k (1 - (1 - cos)^5) cos about m,
/// k = 21 / (20 pi): facet BRDF F spec + (1 - F(wi.m)) albedo k (1 - (1 - wo.m)^5), symmetric in wi and wo.
/// The branch is chosen with probability F (Russian roulette between the two, unbiased), so weights stay in [0, 1].
struct FresnelDiffuse {
    /// f0, Schlick's reflectance at normal incidence, and the albedo of the light that enters: both in [0, 1].
    /// @{
    double f0, albedo;
    /// @}
    static constexpr bool reciprocal = true;  ///< f(wi, wo) = f(wo, wi) facet by facet
    /// The normalization of Hammon's lobe k (1 - (1 - cos)^5) cos.
    static constexpr double k = 21.0 / (20.0 * std::numbers::pi);

    /// With probability F(wi.m) the mirror reflection (weight 1), else a direction from Hammon's lobe about m (weight
    /// albedo, a diffuse event).
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G& g) const {
        if (uniform01(g) < fresnel_schlick(f0, wi.dot(m))) return {reflect(wi, m), 1.0, false};
        if (albedo == 0.0) return {m, 0.0, true};
        return {detail::about(m, detail::hammon_lobe_cos(uniform01(g)), g), albedo, true};
    }
    /// The specular part F(wi.h) D(h) / (4 A(wi)), and the diffuse part (1 - F(wi.m)) albedo k (1 - (1 - wo.m)^5) wo.m
    /// estimated at one visible normal m of wi.
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

/// A smooth dielectric interface on every facet, index eta below the surface over that above (Heitz et al. 2016,
/// sec. 6.2, the dielectric microsurface): the exact Fresnel reflectance F (fresnel.hpp) reflects, 1 - F refracts
/// (Snell), chosen with probability F (weights stay 1). On the side below, the relative index is 1 / eta and past the
/// critical angle everything reflects. The phase function toward wo, the part of it that leaves along wo from this
/// side: reflection when wo.z > 0 (F D(h) / (4 A(wi)), as for mirrors), refraction when wo.z < 0,
///     (1 - F(wi.h)) <wi.h> D(h) / A(wi) |d omega_h / d omega_o|,  h = -(wi + eta' wo) / |.| turned up,
/// the Jacobian Walter 2007 eq. 17 (geometry.hpp, dm_dwo_refraction), eta' the relative index on this side.
struct Dielectric {
    /// The index below the surface over that above, in [1e-3, 1e3].
    double eta;
    /// It lets rays through to the other side (TwoSided).
    static constexpr bool two_sided = true;

    /// With probability F(wi.m) (or under total internal reflection) the mirror reflection, else the refraction
    /// (Snell), weight 1; `above` tells the side, hence the relative index.
    template <class G>
    Scatter sample(const Vec3& wi, const Vec3& m, G& g, bool above) const {
        const double e = above ? eta : 1.0 / eta;
        Vec3 t;
        if (uniform01(g) < fresnel_dielectric(wi.dot(m), e) || !refract(wi, m, e, t))
            return {reflect(wi, m), 1.0, false};
        return {t, 1.0, false, true};
    }
    /// Toward wo on this side (wo.z > 0) the reflection's part, below it the refraction's (the formula above), both
    /// specular; `above` tells the side.
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

/// A material that lets rays through to the other side of the microsurface (`static constexpr bool two_sided = true`):
/// its sample and phase are told the side the ray is on.
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

/// The facet materials, a closed set, visited once per block of walks.
using Material = std::variant<Mirror, Conductor, Lambert, FresnelDiffuse, Dielectric>;

/// "mirror", "conductor(eta=, k=)", "lambert(albedo=1)", "fresnel-diffuse(f0=0.02, albedo=1)", "dielectric(eta=1.5)";
/// input_error naming an unknown material (with the known ones), an unknown or missing parameter, or a value out of
/// its range.
Material parse_material(std::string_view spec);
/// The material's canonical spec, every parameter given, as parse_material reads it.
std::string format_material(const Material& material);
/// Whether any event of the material is diffuse (the tallies of the diffuse component exist only then).
bool has_diffuse(const Material& material);
/// Whether light goes through it (the transmission tallies exist only then).
bool transmits(const Material& material);
/// Whether the material's BSDF holds a Dirac delta at (wi, wo), where it has no finite density for the eval estimator
/// to return: a dielectric of eta = 1 (index-matched) neither reflects nor bends light, so every ray leaves along -wi
/// (wo = -wi, within 1e-9 of a unit vector: the rounding of directions given in degrees), and nowhere else.
bool dirac_at(const Material& material, const Vec3& wi, const Vec3& wo);

}  // namespace smithlab::walk
