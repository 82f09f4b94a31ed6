/// @file
/// smithlab/fit/diffuse/oren_nayar_qualitative.hpp -- Oren and Nayar 1994, "Generalization of Lambert's Reflectance
/// Model" (SIGGRAPH), its qualitative model (the full model's L2 and C3 dropped, C2 simplified):
///     f = albedo/pi (A + B max(0, cos(phi)) sin(alpha') tan(beta)),
///     A = 1 - 0.5 sigma^2/(sigma^2 + 0.33), B = 0.45 sigma^2/(sigma^2 + 0.09),
/// alpha' = max(theta_i, theta_o), beta = min, phi the azimuth between them, sigma the facets' slope-angle deviation.
#pragma once

#include <algorithm>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Oren and Nayar 1994's qualitative model, albedo/pi (A + B max(0, cos(phi)) sin(alpha') tan(beta)), sigma the
/// facets' slope-angle standard deviation (radians), albedo in [0, 1].
inline double oren_nayar_qualitative(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    const double s2 = sigma * sigma;
    const double a = 1.0 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    // max(0, cos(phi)) sin(alpha') tan(beta) = max(0, s) / max(n.wi, n.wo): cos(beta) = max of the cosines.
    const double s = std::max(0.0, common::tangential_dot(wi, wo));
    return albedo * common::inv_pi * (a + b * (s / std::max(wi.z(), wo.z())));
}

/// GLSL transcription of oren_nayar_qualitative: smithlab_oren_nayar_qualitative(L, V, N, sigma, albedo).
inline constexpr std::string_view oren_nayar_qualitative_glsl =
    R"(// Oren and Nayar 1994, the qualitative model: albedo/pi (A + B max(0, cos(phi)) sin(alpha') tan(beta)).
float smithlab_oren_nayar_qualitative(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float s2 = sigma * sigma;
    float a = 1.0 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    float s = max(0.0, smithlab_tangential_dot(L, V, N));
    return albedo * smithlab_inv_pi * (a + b * (s / max(dot(N, L), dot(N, V))));
}
)";

/// "oren-nayar-qualitative": sigma = 0.5 alpha, no constants.
inline DiffuseModel oren_nayar_qualitative_model() {
    return {
        .name = "oren-nayar-qualitative",
        .source =
            "Oren & Nayar 1994, Generalization of Lambert's Reflectance Model, qualitative model; sigma = "
            "0.5 alpha",
        .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                const double*) { return oren_nayar_qualitative(wi, wo, 0.5 * alpha, albedo); },
        .glsl = Glsl{{oren_nayar_qualitative_glsl}, "smithlab_oren_nayar_qualitative(L, V, N, 0.5 * alpha, albedo)"}};
}

}  // namespace smithlab::fit
