/// @file
/// smithlab/fit/diffuse/chan_2018.hpp -- Chan 2018, "Material Advances in Call of Duty: WWII" (SIGGRAPH course,
/// Physically Based Shading), as Unreal Engine 5 writes it (Engine/Shaders/Private/BRDF.ush, Diffuse_Chan),
/// a2 = alpha^2:
///     g = saturate(log2(2/a2 - 1)/18),  Fd = lerp(F0, FdV FdL, saturate(2.2 g - 0.5)),
///     F0 = VoH + (1 - VoH)^5,  FdX = 1 - 0.75 (1 - NoX)^5,
///     Fb = ((34.5 g - 59) g + 24.5) VoH 2^(-max(73.2 g - 21.2, 8.9) sqrt(NoH)) * retro_weight,
///     f = albedo/pi (Fd + Fb).
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Chan 2018 diffuse BRDF as UE5's Diffuse_Chan (file comment), alpha the GGX roughness (a2 = alpha^2), albedo in
/// [0, 1]; retro_weight scales the retro-reflective term Fb (1: as published).
inline double chan_2018(const Vec3& wi, const Vec3& wo, double alpha, double albedo, double retro_weight = 1.0) {
    using common::pow5;
    const Vec3 sum = wi + wo;
    const double len = sum.norm();
    const double voh = std::clamp(0.5 * len, 0.0, 1.0);                // V.H = |L + V| / 2
    const double noh = std::clamp((wi.z() + wo.z()) / len, 0.0, 1.0);  // N.H = (N.L + N.V) / |L + V|
    const double nol = std::clamp(wi.z(), 0.0, 1.0), nov = std::clamp(wo.z(), 0.0, 1.0);
    // a2 = 2 / (1 + 2^(18 g)) inverted; 2/a2 - 1 kept positive so that alpha > sqrt(2) reads as g = 0, not NaN.
    const double a2 = alpha * alpha;
    const double g = std::clamp(std::log2(std::max(2.0 / a2 - 1.0, 1e-300)) / 18.0, 0.0, 1.0);
    const double f0 = voh + pow5(1.0 - voh);
    const double fdv = 1.0 - 0.75 * pow5(1.0 - nov), fdl = 1.0 - 0.75 * pow5(1.0 - nol);
    const double t = std::clamp(2.2 * g - 0.5, 0.0, 1.0);
    const double fd = f0 + t * (fdv * fdl - f0);
    const double fb =
        ((34.5 * g - 59.0) * g + 24.5) * voh * std::exp2(-std::max(73.2 * g - 21.2, 8.9) * std::sqrt(noh));
    return albedo * common::inv_pi * (fd + retro_weight * fb);
}

/// GLSL transcription of chan_2018: smithlab_chan_2018(L, V, N, alpha, albedo, retro_weight).
inline constexpr std::string_view chan_2018_glsl =
    R"(// Chan 2018, Material Advances in Call of Duty: WWII, as Unreal Engine 5's BRDF.ush Diffuse_Chan (a2 = alpha^2).
float smithlab_chan_2018(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float retro_weight)
{
    vec3 sum = L + V;
    float len = length(sum);
    float voh = clamp(0.5 * len, 0.0, 1.0);
    float noh = clamp((dot(N, L) + dot(N, V)) / len, 0.0, 1.0);
    float nol = clamp(dot(N, L), 0.0, 1.0), nov = clamp(dot(N, V), 0.0, 1.0);
    // 2/a2 - 1 kept positive so that alpha > sqrt(2) reads as g = 0, not NaN: the C++ floors it at 1e-300, below
    // float's range; float's smallest normal gives the same g (0).
    float a2 = alpha * alpha;
    float g = clamp(log2(max(2.0 / a2 - 1.0, 1.17549435e-38)) / 18.0, 0.0, 1.0);
    float f0 = voh + smithlab_pow5(1.0 - voh);
    float fdv = 1.0 - 0.75 * smithlab_pow5(1.0 - nov), fdl = 1.0 - 0.75 * smithlab_pow5(1.0 - nol);
    float t = clamp(2.2 * g - 0.5, 0.0, 1.0);
    float fd = f0 + t * (fdv * fdl - f0);
    float fb = ((34.5 * g - 59.0) * g + 24.5) * voh * exp2(-max(73.2 * g - 21.2, 8.9) * sqrt(noh));
    return albedo * smithlab_inv_pi * (fd + retro_weight * fb);
}
)";

/// "chan-2018": retro-reflectivity weight 1, no constants.
inline DiffuseModel chan_2018_model() {
    return {.name = "chan-2018",
            .source =
                "Chan 2018, Material Advances in Call of Duty: WWII (SIGGRAPH course), as UE5 BRDF.ush "
                "Diffuse_Chan, a2 = alpha^2, retro-reflectivity weight 1",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double*) { return chan_2018(wi, wo, alpha, albedo, 1.0); },
            .glsl = Glsl{{chan_2018_glsl}, "smithlab_chan_2018(L, V, N, alpha, albedo, 1.0)"}};
}

}  // namespace smithlab::fit
