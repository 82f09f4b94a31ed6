/// @file
/// smithlab/fit/diffuse/disney.hpp -- Burley 2012, "Physically-Based Shading at Disney" (SIGGRAPH course notes),
/// sec. 5.3, Disney's diffuse BRDF:
///     f = albedo/pi (1 + (FD90 - 1)(1 - cos_l)^5)(1 + (FD90 - 1)(1 - cos_v)^5),  FD90 = 0.5 + 2 r cos^2(theta_d),
/// r the perceptual roughness (sqrt(alpha)), theta_d the angle between wi and the half vector.
#pragma once

#include <cmath>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Disney's diffuse BRDF (Burley 2012 sec. 5.3), perceptual_roughness r = sqrt(alpha), albedo in [0, 1].
inline double disney_diffuse(const Vec3& wi, const Vec3& wo, double perceptual_roughness, double albedo) {
    // cos^2(theta_d) = (wi.h)^2 = |wi + wo|^2 / 4 (h = (wi + wo)/|wi + wo|).
    const double cos2_d = 0.25 * (wi + wo).squaredNorm();
    const double fd90_minus_1 = 2.0 * perceptual_roughness * cos2_d - 0.5;
    const double fl = 1.0 + fd90_minus_1 * common::pow5(1.0 - wi.z()),
                 fv = 1.0 + fd90_minus_1 * common::pow5(1.0 - wo.z());
    return albedo * common::inv_pi * (fl * fv);
}

/// GLSL transcription of disney_diffuse: smithlab_disney_diffuse(L, V, N, perceptual_roughness, albedo).
inline constexpr std::string_view disney_diffuse_glsl =
    R"(// Burley 2012, Physically-Based Shading at Disney, sec. 5.3: albedo/pi (1 + (FD90 - 1)(1 - cos_l)^5)
// (1 + (FD90 - 1)(1 - cos_v)^5), FD90 = 0.5 + 2 r cos^2(theta_d), cos^2(theta_d) = |L + V|^2 / 4.
float smithlab_disney_diffuse(vec3 L, vec3 V, vec3 N, float perceptual_roughness, float albedo)
{
    float cos2_d = 0.25 * dot(L + V, L + V);
    float fd90_minus_1 = 2.0 * perceptual_roughness * cos2_d - 0.5;
    float fl = 1.0 + fd90_minus_1 * smithlab_pow5(1.0 - dot(N, L));
    float fv = 1.0 + fd90_minus_1 * smithlab_pow5(1.0 - dot(N, V));
    return albedo * smithlab_inv_pi * (fl * fv);
}
)";

/// "disney": r = sqrt(alpha), no constants.
inline DiffuseModel disney_model() {
    return {.name = "disney",
            .source = "Burley 2012, Physically-Based Shading at Disney, sec. 5.3 (r = sqrt(alpha))",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double*) { return disney_diffuse(wi, wo, std::sqrt(alpha), albedo); },
            .glsl = Glsl{{disney_diffuse_glsl}, "smithlab_disney_diffuse(L, V, N, sqrt(alpha), albedo)"}};
}

}  // namespace smithlab::fit
