/// @file
/// smithlab/detail/visible_normals_closed.hpp -- visible normals in closed form, for a direction v anywhere on the
/// sphere with A(v) > 0: the law D_v(m) = <v.m>^+ D(m) / A(v) over m.z > 0 (visible_normals.hpp) of the GGX and the
/// Beckmann distributions. Both stretch v to the alpha = 1 configuration (slopes scale by alpha; Heitz & d'Eon 2014,
/// "Importance Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals", sec. 4, steps 1-5), sample
/// there, and unstretch. An NDF reaches these through its capability ggx_alpha() / beckmann_alpha() (ndf.hpp).
/// no_normal() (dcos_law.hpp) when v is straight down (no normal is visible) or rounding defeats 100 draws.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "smithlab/dcos_law.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/rng.hpp"
#include "smithlab/turn.hpp"

namespace smithlab::detail {

/// GGX: Dupuy & Benyoub 2023, "Sound and Fast Sampling of Visible GGX Normals with Spherical Caps", listing 3. At
/// alpha = 1, D_v is the clamped cosine about vs restricted to m.z > 0, and m = normalize(vs + u) for u uniform on the
/// unit sphere has density <vs.m>^+ on the whole sphere, so u uniform on the cap u.z > -vs.z gives it on m.z > 0 --
/// for vs of either sign of z: below the horizon the cap is (|vs.z|, 1], the same formula.
///
/// Written scale-free and without cancellation: with the stretched s = (alpha v.x, alpha v.y, v.z), l = |s|,
/// d2 = s.x^2 + s.y^2, and P = l + s.z, Q = l - s.z (P Q = d2: the one of the two that would cancel is d2 over the
/// other), the cap's height is z = (1 - u) (1 + vs.z) - vs.z, and l times the cap point plus s is
///     h.z = (1 - u) P,   h_xy = sqrt(u P (Q + h.z)) (cos phi, sin phi) + s_xy,
/// since l (1 - z) = u P and l (1 + z) = Q + h.z: h.z > 0 by construction, and near the poles (the cap a sliver, or
/// the whole sphere) every digit is kept: within 5 degrees of them the normal is within 3e-14 of a long-double
/// evaluation of the same draw, where the unit-vector form (1 + vs.z, 1 - z) was 5e-13 off near straight up and 1e-3
/// within 1e-5 degrees of straight down. The cap's u and azimuth come together from one point (a, b) uniform in the
/// unit disk (the fact under Marsaglia & Bray 1964's polar method, "A convenient method for generating normal
/// variables": a^2 + b^2 is uniform in [0, 1) and independent of the angle, and sqrt(a^2 + b^2) (cos phi, sin phi) =
/// (a, b)), so with u = a^2 + b^2
///     h_xy = sqrt(P (Q + h.z)) (a, b) + s_xy:
/// no trigonometry, drawn by rejection from the square (acceptance pi / 4; one 64-bit draw per try, its halves on a
/// grid of 2^-31: rng.hpp, uniform_square). m is the unstretched h, normalized: one root and a division for the
/// stretch, a root for the cap, a root and a division for m.
/// v stretched to the alpha = 1 configuration, s = (alpha v.x, alpha v.y, v.z), with P = |s| + s.z and Q = |s| - s.z
/// (P Q = |s_xy|^2; the one that would cancel is formed as the quotient). P / 2 is GGX's projected area A(v) over the
/// whole sphere in Smith's convention (Heitz 2014 eq. 72: (1 + Lambda) cos theta above the horizon, Lambda |cos|
/// below).
struct GgxCap {
    /// GGX's alpha; s_xy, the stretched direction's horizontal part; P and Q as above.
    /// @{
    double alpha, sx, sy, P, Q;
    /// @}
};

/// The cap of GGX of roughness alpha for the unit direction v: v stretched, P and Q formed without cancellation.
inline GgxCap ggx_cap(double alpha, const Vec3& v) {
    const double sx = alpha * v.x(), sy = alpha * v.y(), sz = v.z();
    const double d2 = sx * sx + sy * sy, l = std::sqrt(d2 + sz * sz);
    const double P = sz >= 0.0 ? l + sz : d2 / (l - sz), Q = sz >= 0.0 ? d2 / P : l - sz;
    return {alpha, sx, sy, P, Q};
}

/// One try of the cap (P > 0): false when the point falls outside the unit disk, else the normal h, unnormalized
/// (h.z > 0): its slope is what a caller accepting by the slope needs before it normalizes.
template <class G>
bool ggx_cap_try(const GgxCap& c, G& g, Vec3& h) {
    const auto [a, b] = uniform_square(g);
    const double u = a * a + b * b;
    if (!(u < 1.0)) return false;
    const double hz = (1.0 - u) * c.P, r = std::sqrt(c.P * (c.Q + hz));
    h = Vec3(c.alpha * (r * a + c.sx), c.alpha * (r * b + c.sy), hz);
    return true;
}

/// h normalized, when it faces v and lies above the surface (not, only by rounding at grazing normals).
inline bool ggx_cap_normal(const Vec3& h, const Vec3& v, Vec3& m) {
    const double n = 1.0 / std::sqrt(h.x() * h.x() + h.y() * h.y() + h.z() * h.z());
    m = Vec3(h.x() * n, h.y() * n, h.z() * n);
    return m.z() > 0.0 && v.dot(m) > 0.0;
}

/// A visible normal of GGX of roughness alpha for the unit direction v, by the spherical cap (Dupuy & Benyoub 2023, as
/// above); no_normal() when v is straight down or 100 tries fail.
template <class G>
Vec3 sample_ggx_visible_normal(double alpha, const Vec3& v, G& g) {
    const GgxCap c = ggx_cap(alpha, v);
    if (!(c.P > 0.0)) return no_normal();  // straight down: no normal is visible
    Vec3 h, m;
    for (int tries = 0; tries < 100; ++tries)
        if (ggx_cap_try(c, g, h) && ggx_cap_normal(h, v, m)) return m;
    return no_normal();
}

/// Beckmann, alpha = 1 configuration, v turned into the xz-plane with mu = cot(theta) of either sign: the visible
/// slopes (x, y) have density (mu - x)^+ e^{-x^2} e^{-y^2} / pi (Heitz & d'Eon 2014 eq. 5-6 with P22 =
/// e^{-x^2-y^2}/pi): y is Gaussian of variance 1/2, independent, and x is this function of u in (0, 1] (sampling.cpp):
/// with w = -x, b = -mu, the density (w - b)^+ e^{-w^2} has survival N(w) / N(b), N(w) = ierfc(w) + (w - b) erfc(w)
/// (A&S 7.2.5: ierfc' = -erfc), all terms positive for w >= b; solved by Newton's method on ln N.
double beckmann_visible_slope(double mu, double u);

/// A visible normal of Beckmann of roughness alpha for the unit direction v: the slopes of the alpha = 1 configuration
/// (beckmann_visible_slope and a Gaussian y), turned back and unstretched (Heitz & d'Eon 2014 sec. 4); straight up, the
/// D cos law (Walter 2007 eq. 28); no_normal() when v is straight down or 100 tries fail.
template <class G>
Vec3 sample_beckmann_visible_normal(double alpha, const Vec3& v, G& g) {
    const double sin_v = norm_xy(v);
    if (sin_v == 0.0) {
        if (!(v.z() > 0.0)) return no_normal();
        // Straight up, D_v = D cos: tan^2 = -alpha^2 ln(1 - u) (Walter 2007 eq. 28).
        const double s = -alpha * alpha * std::log(1.0 - uniform01(g));
        return normal_from_slope(s, cos_sin_turn(uniform01(g)));
    }
    const double mu = v.z() / (alpha * sin_v), c = v.x() / sin_v, s = v.y() / sin_v;
    for (int tries = 0; tries < 100; ++tries) {
        const double x = beckmann_visible_slope(mu, 1.0 - uniform01(g));
        const double y = std::sqrt(-std::log(1.0 - uniform01(g))) * cos_sin_turn(uniform01(g)).c;
        const double sx = alpha * (c * x - s * y), sy = alpha * (s * x + c * y);  // turned back, unstretched
        const Vec3 m = Vec3(-sx, -sy, 1.0) / std::sqrt(1.0 + sx * sx + sy * sy);  // the normal of slope (sx, sy)
        if (v.dot(m) > 0.0) return m;
    }
    return no_normal();
}

}  // namespace smithlab::detail
