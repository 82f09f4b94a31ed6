/// @file
/// smithlab/geometry.hpp -- directions in the frame of the macrosurface (z up, unit vectors pointing away from the
/// surface point): angles and slopes, an orthonormal frame about any unit vector, mirror reflection and refraction
/// about a facet normal m, their half vectors and the Jacobians that turn a density of m into one of the scattered
/// direction (Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces", sec. 4
/// and 5; "Walter" below).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <cmath>
#include <numbers>

#include "smithlab/turn.hpp"

namespace smithlab {

/// A direction or a point: Eigen's 3-vector of doubles, z along the macrosurface normal.
using Vec3 = Eigen::Vector3d;

/// mu = cot(theta) of a direction, the argument of Lambda: +inf straight up, -inf straight down.
inline double cot_theta(const Vec3& w) { return w.z() / std::hypot(w.x(), w.y()); }
/// tan^2(theta) of a unit vector, (x^2 + y^2) / z^2.
inline double tan2_theta(const Vec3& m) { return (m.x() * m.x() + m.y() * m.y()) / (m.z() * m.z()); }
/// |w_xy| = sqrt(x^2 + y^2), sin(theta) of a unit vector: the root of the squares where they neither under- nor
/// overflow (within an ulp of std::hypot, at a fraction of its cost), std::hypot where they might.
inline double norm_xy(const Vec3& w) {
    const double s2 = w.x() * w.x() + w.y() * w.y();
    return s2 > 1e-300 && s2 < 1e300 ? std::sqrt(s2) : std::hypot(w.x(), w.y());
}

/// The normal of slope tan^2(theta) = s at azimuth phi; cos and sin come from s, exact at the pole.
inline Vec3 normal_from_slope(double s, double phi) {
    if (!(s < INFINITY)) return {std::cos(phi), std::sin(phi), 0.0};
    const double c = 1.0 / std::sqrt(1.0 + s), sn = std::sqrt(s) * c;
    return {sn * std::cos(phi), sn * std::sin(phi), c};
}
/// ... at the azimuth whose cosine and sine are given (turn.hpp: cos_sin_turn of a uniform azimuth).
inline Vec3 normal_from_slope(double s, const CosSin& phi) {
    if (!(s < INFINITY)) return {phi.c, phi.s, 0.0};
    const double c = 1.0 / std::sqrt(1.0 + s), sn = std::sqrt(s) * c;
    return {sn * phi.c, sn * phi.s, c};
}

/// The direction of polar angle theta and azimuth phi (degrees; theta > 90 is below the surface, phi from the x axis
/// towards y): (sin theta cos phi, sin theta sin phi, cos theta).
inline Vec3 direction_from_deg(double theta_deg, double phi_deg) {
    constexpr double deg = std::numbers::pi / 180.0;
    const double t = theta_deg * deg, p = phi_deg * deg, st = std::sin(t);
    return {st * std::cos(p), st * std::sin(p), std::cos(t)};
}
/// ... in the xz-plane: (sin theta, 0, cos theta).
inline Vec3 direction_from_theta_deg(double theta_deg) { return direction_from_deg(theta_deg, 0.0); }

/// An orthonormal, right-handed frame (s, t, n) about a unit vector n, continuous everywhere but across n.z = 0 with
/// n.x = n.y = 0 excluded by construction: Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building
/// an Orthonormal Basis, Revisited", listing 3 (sign = copysign(1, n.z): no singularity at n = -z).
struct Frame {
    /// The frame's tangent s, bitangent t and normal n.
    /// @{
    Vec3 s, t, n;
    /// @}
    /// The frame about the unit vector `normal`.
    explicit Frame(const Vec3& normal) : n(normal) {
        const double sign = std::copysign(1.0, n.z()), a = -1.0 / (sign + n.z()), b = n.x() * n.y() * a;
        s = Vec3(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
        t = Vec3(b, sign + n.y() * n.y() * a, -n.y());
    }
    /// v in the frame's coordinates (s, t, n), and back.
    /// @{
    Vec3 to_local(const Vec3& v) const { return {v.dot(s), v.dot(t), v.dot(n)}; }
    Vec3 to_world(const Vec3& v) const { return v.x() * s + v.y() * t + v.z() * n; }
    /// @}
};

/// Mirror reflection of i about m (Walter eq. 39), and the pdf of the reflected direction given m's: pdf_m / (4 |i.m|)
/// (Walter eq. 14; the blog's "one extra step").
inline Vec3 reflect(const Vec3& i, const Vec3& m) { return 2.0 * i.dot(m) * m - i; }
/// |d omega_m / d omega_o| for reflection, o = reflect(i, m): 1 / (4 |o.m|) (Walter eq. 14).
inline double dm_dwo_reflection(const Vec3& o, const Vec3& m) { return 1.0 / (4.0 * std::abs(o.dot(m))); }
/// The pdf of o = reflect(i, m) given m's pdf_m: pdf_m / (4 |i.m|) (Walter eq. 14).
inline double reflected_pdf(double pdf_m, const Vec3& i, const Vec3& m) { return pdf_m * dm_dwo_reflection(i, m); }

/// Refraction of wi through a facet of normal m (either orientation), both directions pointing away from the surface
/// point, eta = eta_t / eta_i (the index on the far side over that on wi's side): Walter eq. 40 with his
/// eta_W = eta_i / eta_t = 1 / eta,
///     wt = (eta_W c - sign(c) cos_t) m - eta_W wi,   c = wi.m,   cos_t = sqrt(1 - eta_W^2 (1 - c^2))   (Snell's law).
/// False (wt untouched) under total internal reflection, where the root is imaginary.
inline bool refract(const Vec3& wi, const Vec3& m, double eta, Vec3& wt) {
    const double c = wi.dot(m), e = 1.0 / eta;
    const double cos_t2 = 1.0 - e * e * (1.0 - c) * (1.0 + c);
    if (!(cos_t2 >= 0.0)) return false;
    wt = (e * c - std::copysign(std::sqrt(cos_t2), c)) * m - e * wi;
    return true;
}

/// The half vectors (Walter eq. 13 and 16): reflection, h_r = sign(i.z) (i + o) / |i + o|, on i's side of the
/// macrosurface; transmission, o on the side of index eta_o, eta = eta_o / eta_i, h_t = -(i + eta o) / |i + eta o|
/// (Walter's -(eta_i i + eta_o o) / |.| divided by eta_i): it points into the medium of the lower index, so to the
/// m.z > 0 side only when eta > 1 and i is above (multiply by sign(h.z) for the NDF's hemisphere).
inline Vec3 half_vector_reflection(const Vec3& i, const Vec3& o) {
    return std::copysign(1.0, i.z()) * (i + o).normalized();
}
/// h_t = -(i + eta o) / |i + eta o|, as above.
inline Vec3 half_vector_transmission(const Vec3& i, const Vec3& o, double eta) { return -(i + eta * o).normalized(); }

/// |d omega_m / d omega_o| for refraction (Walter eq. 17, divided through by eta_i^2):
///     eta^2 |o.m| / (i.m + eta o.m)^2,   eta = eta_o / eta_i.
inline double dm_dwo_refraction(const Vec3& i, const Vec3& o, const Vec3& m, double eta) {
    const double d = i.dot(m) + eta * o.dot(m);
    return eta * eta * std::abs(o.dot(m)) / (d * d);
}

}  // namespace smithlab
