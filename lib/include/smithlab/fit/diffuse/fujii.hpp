/// @file
/// smithlab/fit/diffuse/fujii.hpp -- Fujii 2012/2013, "A tiny improvement of Oren-Nayar reflectance model"
/// (mimosa-pudica.net/improved-oren-nayar.html):
///     f = albedo/pi (A + B s/t),  s = wi.wo - (n.wi)(n.wo),  t = 1 if s <= 0 else max(n.wi, n.wo),
///     A = 1/(1 + (1/2 - 2/(3 pi)) sigma),  B = sigma A.
/// Negative where sigma > 1 and s < 0 (A + B s >= A (1 - sigma)): smithlab returns max(0, f) (a guard, not Fujii's).
#pragma once

#include <algorithm>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Fujii's improved Oren-Nayar BRDF, albedo/pi (A + B s/t), sigma the roughness, albedo in [0, 1]; max(0, f).
inline double fujii(const Vec3& wi, const Vec3& wo, double sigma, double albedo) {
    const double a = 1.0 / (1.0 + common::eon_c1 * sigma), b = sigma * a;
    return std::max(0.0, albedo * common::inv_pi * (a + b * common::s_over_t(wi, wo)));
}

/// GLSL transcription of fujii: smithlab_fujii(L, V, N, sigma, albedo).
inline constexpr std::string_view fujii_glsl =
    R"(// Fujii 2013, A tiny improvement of Oren-Nayar reflectance model: albedo/pi (A + B s/t), A = 1/(1 + c1 sigma),
// B = sigma A; max(0, f) (smithlab's guard, not Fujii's).
float smithlab_fujii(vec3 L, vec3 V, vec3 N, float sigma, float albedo)
{
    float a = 1.0 / (1.0 + smithlab_eon_c1 * sigma), b = sigma * a;
    return max(0.0, albedo * smithlab_inv_pi * (a + b * smithlab_s_over_t(L, V, N)));
}
)";

/// "fujii": sigma = s alpha, s free, start 1 (not published).
inline DiffuseModel fujii_model() {
    return {.name = "fujii",
            .parameters = {"sigma_scale"},
            .published = {1.0},
            .source =
                "Fujii 2013, A tiny improvement of Oren-Nayar reflectance model; sigma = s alpha, start s = 1 "
                "(not published)",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double* c) { return fujii(wi, wo, c[0] * alpha, albedo); },
            .glsl = Glsl{{fujii_glsl}, "smithlab_fujii(L, V, N, {0} * alpha, albedo)"},
            .ranges = {{0.0, 1.0,
                        "sigma = s alpha: above sigma = 1 Fujii's f turns negative (A + B s >= A (1 - sigma)), held at "
                        "0 here"}}};
}

}  // namespace smithlab::fit
