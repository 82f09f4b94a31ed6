/// @file
/// smithlab/fit/diffuse/oren_nayar.hpp -- Oren and Nayar 1994, "Generalization of Lambert's Reflectance Model"
/// (SIGGRAPH), the full functional approximation: its direct term L1 (with C1, C2, C3) plus its interreflection term
/// L2, both divided by E0 cos(theta_i):
///     f = albedo/pi [C1 + cos(phi) C2 tan(beta) + (1 - |cos(phi)|) C3 tan((alpha' + beta)/2)]
///       + 0.17 albedo^2/pi sigma^2/(sigma^2 + 0.13) [1 - cos(phi) (2 beta/pi)^2],
/// alpha' = max(theta_i, theta_o), beta = min, phi the azimuth between them, sigma the standard deviation of the
/// facets' slope angle (radians); C1 = 1 - 0.5 sigma^2/(sigma^2 + 0.33), C2 = 0.45 sigma^2/(sigma^2 + 0.09) sin(alpha')
/// where cos(phi) >= 0 and 0.45 sigma^2/(sigma^2 + 0.09)(sin(alpha') - (2 beta/pi)^3) otherwise,
/// C3 = 0.125 sigma^2/(sigma^2 + 0.09) (4 alpha' beta/pi^2)^2. Can dip below 0 (forward scattering, both grazing, at
/// sigma >~ 0.7): smithlab returns max(0, f).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Oren and Nayar 1994's full model (L1 + L2, file comment), sigma the facets' slope-angle standard deviation
/// (radians), albedo in [0, 1]; max(0, f).
inline double oren_nayar(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    using common::pi;
    const double s2 = sigma * sigma;
    const double ri = norm_xy(wi), ro = norm_xy(wo);
    // alpha' = max(theta_i, theta_o) and beta = min, by their sines and cosines (min and max keep it symmetric to the
    // bit): sin(alpha') = the larger sine, cos(beta) = the larger cosine. tan(beta) = sin/cos and
    // tan((alpha' + beta)/2) = (sin(alpha') + sin(beta)) / (cos(alpha') + cos(beta)) come from them directly: finite
    // for z > 0 and exact at grazing, where tan of an angle near pi/2 would lose digits.
    const double sin_a = std::max(ri, ro), sin_b = std::min(ri, ro);
    const double cos_a = std::min(wi.z(), wo.z()), cos_b = std::max(wi.z(), wo.z());
    const double a = std::atan2(sin_a, cos_a), b = std::atan2(sin_b, cos_b);
    const double tan_b = sin_b / cos_b, tan_half_sum = (sin_a + sin_b) / (cos_a + cos_b);
    // cos(phi): either direction along the normal makes it undefined, and every term it multiplies vanishes there
    // (tan(beta) = 0, beta = 0): 0 is as good as any value.
    const double rr = ri * ro;
    const double cos_phi = rr > 0.0 ? std::clamp(common::tangential_dot(wi, wo) / rr, -1.0, 1.0) : 0.0;
    const double b2 = 2.0 * b / pi;  // 2 beta / pi
    const double c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    const double c2 = 0.45 * s2 / (s2 + 0.09) * (cos_phi >= 0.0 ? sin_a : sin_a - b2 * b2 * b2);
    const double c3_root = 4.0 * a * b / (pi * pi), c3 = 0.125 * s2 / (s2 + 0.09) * c3_root * c3_root;
    const double l1 = c1 + cos_phi * c2 * tan_b + (1.0 - std::abs(cos_phi)) * c3 * tan_half_sum;
    const double l2 = 0.17 * albedo * s2 / (s2 + 0.13) * (1.0 - cos_phi * b2 * b2);
    return std::max(0.0, albedo * common::inv_pi * (l1 + l2));
}

/// GLSL transcription of oren_nayar: smithlab_oren_nayar(L, V, N, sigma, albedo).
inline constexpr std::string_view oren_nayar_glsl =
    R"(// Oren and Nayar 1994, Generalization of Lambert's Reflectance Model, the full model: L1 (C1, C2, C3) plus the
// interreflection term L2, sigma the facets' slope-angle deviation (radians); alpha' = max(theta_i, theta_o) and
// beta = min from their sines and cosines; max(0, f) (it dips below 0 at sigma >~ 0.7, both grazing, forward).
float smithlab_oren_nayar(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float s2 = sigma * sigma;
    float cos_i = dot(N, L), cos_o = dot(N, V);
    vec3 Lt = L - cos_i * N, Vt = V - cos_o * N;
    float ri = length(Lt), ro = length(Vt);
    float sin_a = max(ri, ro), sin_b = min(ri, ro);
    float cos_a = min(cos_i, cos_o), cos_b = max(cos_i, cos_o);
    float a = atan(sin_a, cos_a), b = atan(sin_b, cos_b);
    float tan_b = sin_b / cos_b, tan_half_sum = (sin_a + sin_b) / (cos_a + cos_b);
    // cos(phi) is undefined with either direction along N, where every term it multiplies vanishes: 0 there.
    float rr = ri * ro;
    float cos_phi = rr > 0.0 ? clamp(dot(Lt, Vt) / rr, -1.0, 1.0) : 0.0;
    float b2 = 2.0 * b / smithlab_pi;
    float c1 = 1.0 - 0.5 * s2 / (s2 + 0.33);
    float c2 = 0.45 * s2 / (s2 + 0.09) * (cos_phi >= 0.0 ? sin_a : sin_a - b2 * b2 * b2);
    float c3_root = 4.0 * a * b / (smithlab_pi * smithlab_pi), c3 = 0.125 * s2 / (s2 + 0.09) * c3_root * c3_root;
    float l1 = c1 + cos_phi * c2 * tan_b + (1.0 - abs(cos_phi)) * c3 * tan_half_sum;
    float l2 = 0.17 * albedo * s2 / (s2 + 0.13) * (1.0 - cos_phi * b2 * b2);
    return max(0.0, albedo * smithlab_inv_pi * (l1 + l2));
}
)";

/// "oren-nayar": sigma = s alpha, s free (published 0.5: Hammon 2017's comparison).
inline DiffuseModel oren_nayar_model() {
    return {.name = "oren-nayar",
            .parameters = {"sigma_scale"},
            .published = {0.5},
            .source =
                "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, full model with L2; sigma = "
                "s alpha, s = 0.5 as in Hammon 2017's comparison",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double* c) { return oren_nayar(wi, wo, c[0] * alpha, albedo); },
            .glsl = Glsl{{oren_nayar_glsl}, "smithlab_oren_nayar(L, V, N, {0} * alpha, albedo)"},
            .ranges = {{0.0, std::numbers::pi / 2.0,
                        "sigma = s alpha, the standard deviation of the facets' slope angle (Oren & Nayar 1994 sec. "
                        "3), an angle within (-pi/2, pi/2): at most pi/2 at alpha = 1"}}};
}

/// "oren-nayar-sqrt2": sigma = alpha/sqrt(2), no constants.
inline DiffuseModel oren_nayar_sqrt2_model() {
    return {.name = "oren-nayar-sqrt2",
            .source =
                "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, full model with L2; sigma = "
                "alpha/sqrt(2)",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double*) { return oren_nayar(wi, wo, alpha * std::numbers::sqrt2 * 0.5, albedo); },
            // sqrt(2) to 9 digits, a float's round trip
            .glsl = Glsl{{oren_nayar_glsl}, "smithlab_oren_nayar(L, V, N, alpha * 1.41421356 * 0.5, albedo)"}};
}

}  // namespace smithlab::fit
