/// @file
/// smithlab/fit/diffuse/common.hpp -- the terms several diffuse models share, in C++ and as GLSL: the fifth power
/// of Schlick's factors, the tangential dot product, Fujii's s/t, and EON's constants, G(mu) and rho_ms (Fujii's model
/// is EON's single-scattering lobe). An exported GLSL library holds the GLSL ones, and smithlab_pi, smithlab_inv_pi,
/// smithlab_eon_c1 and smithlab_eon_c2, before every model's own functions (fit/glsl.hpp): any transcription may call
/// them.
///
/// Each GLSL function transcribes the C++ function of the same name line for line (same clamps, same guards against
/// 0/0, same order of operations), with (L, V, N) for (wi, wo, z): wi.z() -> dot(N, L), the tangential part (x, y) ->
/// L - dot(N, L) N. Symmetry in wi and wo is kept to the last bit wherever it is cheap: every quantity is built from
/// symmetric pieces (wi.wo, wi + wo, min and max of the two cosines, the products of the two Schlick factors), so
/// f(wi, wo) and f(wo, wi) differ at most by the rounding of a product's order.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "smithlab/geometry.hpp"

namespace smithlab::fit::common {

/// pi and 1/pi (smithlab_pi and smithlab_inv_pi in GLSL).
///@{
inline constexpr double pi = std::numbers::pi;
inline constexpr double inv_pi = std::numbers::inv_pi;
///@}

/// x^5 as (x^2)^2 x: the fifth power of Schlick's factors (1 - cos)^5.
inline double pow5(double x) {
    const double x2 = x * x;
    return x2 * x2 * x;
}

/// s = wi.wo - (n.wi)(n.wo) = cos(phi) sin(theta_i) sin(theta_o), from the tangential components: no cancellation.
inline double tangential_dot(const Vec3& wi, const Vec3& wo) { return wi.x() * wo.x() + wi.y() * wo.y(); }

/// Fujii's s/t (and EON's): s where s <= 0, else s / max(n.wi, n.wo) (= cos(phi) sin(alpha') tan(beta)).
inline double s_over_t(const Vec3& wi, const Vec3& wo) {
    const double s = tangential_dot(wi, wo);
    return s > 0.0 ? s / std::max(wi.z(), wo.z()) : s;
}

/// EON's constants (the paper's constant1_FON and constant2_FON): A = 1/(1 + c1 r), `<E_F>` = A (1 + c2 r).
///@{
inline constexpr double eon_c1 = 0.5 - 2.0 / (3.0 * pi);
inline constexpr double eon_c2 = 2.0 / 3.0 - 28.0 / (15.0 * pi);
///@}

/// G(mu) of E_F (fit/diffuse/eon.hpp), with (S/mu)(1 - S^3) = S mu (1 + S + S^2)/(1 + S) (as 1 - S = mu^2/(1 + S)):
/// no 0/0 at grazing, where G -> pi/2 - 2/3 = pi c1.
inline double eon_g(double mu) {
    const double m = std::clamp(mu, 0.0, 1.0), s = std::sqrt((1.0 - m) * (1.0 + m));
    return s * (std::acos(m) - s * m) + (2.0 / 3.0) * (s * m * (1.0 + s + s * s) / (1.0 + s) - s);
}
/// `<E_F>` = A (1 + c2 r).
inline double eon_average_albedo(double r) { return (1.0 + eon_c2 * r) / (1.0 + eon_c1 * r); }
/// 1 - E_F(mu) = A r (c1 - G(mu)/pi), written without the cancellation of 1 - E_F near r = 0 and near grazing.
inline double eon_one_minus_fon_albedo(double mu, double r) {
    return r / (1.0 + eon_c1 * r) * std::max(0.0, eon_c1 - eon_g(mu) * inv_pi);
}
/// rho_ms = rho^2 `<E_F>` / (1 - rho (1 - `<E_F>`)).
inline double eon_rho_ms(double r, double albedo) {
    const double avg = eon_average_albedo(r);
    return albedo * albedo * avg / (1.0 - albedo * (1.0 - avg));
}

/// The GLSL functions above (the constants are written from the doubles above, fit/glsl.cpp).
inline constexpr std::string_view glsl_functions =
    R"(float smithlab_pow5(float x)
{
    float x2 = x * x;
    return x2 * x2 * x;
}

// s = L.V - (N.L)(N.V) = cos(phi) sin(theta_i) sin(theta_o), from the tangential components: no cancellation.
float smithlab_tangential_dot(vec3 L, vec3 V, vec3 N)
{
    return dot(L - dot(N, L) * N, V - dot(N, V) * N);
}

// Fujii's s/t (and EON's): s where s <= 0, else s / max(N.L, N.V) (= cos(phi) sin(alpha') tan(beta)).
float smithlab_s_over_t(vec3 L, vec3 V, vec3 N)
{
    float s = smithlab_tangential_dot(L, V, N);
    return s > 0.0 ? s / max(dot(N, L), dot(N, V)) : s;
}

// G(mu) of EON's E_F, with (S/mu)(1 - S^3) = S mu (1 + S + S^2)/(1 + S): no 0/0 at grazing.
float smithlab_eon_g(float mu)
{
    float m = clamp(mu, 0.0, 1.0);
    float s = sqrt((1.0 - m) * (1.0 + m));
    return s * (acos(m) - s * m) + (2.0 / 3.0) * (s * m * (1.0 + s + s * s) / (1.0 + s) - s);
}

// EON's rho_ms = rho^2 <E_F> / (1 - rho (1 - <E_F>)).
float smithlab_eon_rho_ms(float r, float albedo)
{
    float avg = (1.0 + smithlab_eon_c2 * r) / (1.0 + smithlab_eon_c1 * r);
    return albedo * albedo * avg / (1.0 - albedo * (1.0 - avg));
}
)";

}  // namespace smithlab::fit::common
