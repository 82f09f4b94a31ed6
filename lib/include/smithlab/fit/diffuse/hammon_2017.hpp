/// @file
/// smithlab/fit/diffuse/hammon_2017.hpp -- Hammon 2017, "PBR Diffuse Lighting for GGX+Smith Microsurfaces" (GDC),
/// slide "GGX Diffuse Approximation":
///     facing = 0.5 + 0.5 L.V,  rough = facing (a - b facing)(c + N.H)/N.H,
///     smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5),  single = (1/pi) lerp(smooth, rough, alpha),  multi = m alpha,
/// with the published (a, b, c, k, m) = (0.9, 0.4, 0.5, 1.05, 0.1159). The slide's last line lost its superscripts;
/// its two readings are hammon_2017, albedo (single + albedo multi), and hammon_2017_linear, albedo (single + multi).
/// Read as the BRDF f (no N.L): k = 1.05 = 21/20 is what makes smooth/pi integrate against cos to exactly
/// 1 - (1 - N.V)^5 <= 1 (his normalisation k = 21/(20 pi)); an f cos reading would need N.L on the slide.
#pragma once

#include <cmath>
#include <string_view>
#include <vector>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Hammon 2017's constants (a, b, c, k, m) of his GGX diffuse approximation, defaulting to the published values.
struct HammonConstants {
    /// a, b, c of the rough term, k of the smooth term, m of the multiple-scattering term multi = m alpha.
    ///@{
    double rough_a = 0.9, rough_b = 0.4, rough_c = 0.5, smooth = 1.05, multi = 0.1159;
    ///@}
};

/// Hammon 2017's single-scattering term (1/pi) lerp(smooth, rough, alpha), without albedo; alpha the GGX
/// roughness, or the blend weight that replaces it (smithlab-2026 passes alpha^p).
inline double hammon_2017_single(const Vec3& wi, const Vec3& wo, double alpha, const HammonConstants& k) {
    using common::pow5;
    const Vec3 sum = wi + wo;
    const double len2 = sum.squaredNorm();
    const double facing = 0.25 * len2;                       // 0.5 + 0.5 L.V = |L + V|^2 / 4 (the slide's identity)
    const double noh = (wi.z() + wo.z()) / std::sqrt(len2);  // N.H = (N.L + N.V) / |L + V|, > 0 for z > 0
    const double rough = facing * (k.rough_a - k.rough_b * facing) * ((k.rough_c + noh) / noh);
    const double smooth = k.smooth * ((1.0 - pow5(1.0 - wi.z())) * (1.0 - pow5(1.0 - wo.z())));
    return common::inv_pi * (smooth + alpha * (rough - smooth));
}

/// Hammon 2017 read as albedo (single + albedo multi), multi = m alpha.
inline double hammon_2017(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const HammonConstants& k = {}) {
    return albedo * (hammon_2017_single(wi, wo, alpha, k) + albedo * (k.multi * alpha));
}

/// Hammon 2017 read as albedo (single + multi), multi = m alpha.
inline double hammon_2017_linear(const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                                 const HammonConstants& k = {}) {
    return albedo * (hammon_2017_single(wi, wo, alpha, k) + k.multi * alpha);
}

/// The constants (rough_a, rough_b, rough_c, smooth, multi) from the fitter's array.
inline HammonConstants hammon_constants(const double* c) { return {c[0], c[1], c[2], c[3], c[4]}; }

/// The ranges of Hammon 2017's constants (his slide's terms): the rough term's shape a - b facing is left free; the
/// others are non-negative where the term they scale is.
inline std::vector<ParameterRange> hammon_ranges() {
    constexpr double inf = INFINITY;
    return {{},
            {},
            {0.0, inf, "rough = facing (a - b facing)(c + N.H)/N.H: below c = 0 it changes sign toward grazing N.H"},
            {0.0, inf, "smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5): negative light below k = 0"},
            {0.0, inf, "multi = m alpha, the light scattered more than once: negative below m = 0"}};
}

/// GLSL transcription of hammon_2017_single: smithlab_hammon_2017_single(L, V, N, alpha, rough_a, rough_b,
/// rough_c, smooth_k).
inline constexpr std::string_view hammon_2017_single_glsl =
    R"(// Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), slide "GGX Diffuse Approximation":
// facing = 0.5 + 0.5 L.V = |L + V|^2 / 4, rough = facing (a - b facing)(c + N.H)/N.H,
// smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5), single = (1/pi) lerp(smooth, rough, alpha). (smooth_k: `smooth`
// is a GLSL keyword.)
float smithlab_hammon_2017_single(vec3 L, vec3 V, vec3 N, float alpha, float rough_a, float rough_b, float rough_c,
                                  float smooth_k)
{
    vec3 sum = L + V;
    float len2 = dot(sum, sum);
    float facing = 0.25 * len2;
    float noh = (dot(N, L) + dot(N, V)) / sqrt(len2);
    float rough = facing * (rough_a - rough_b * facing) * ((rough_c + noh) / noh);
    float smooth_term = smooth_k * ((1.0 - smithlab_pow5(1.0 - dot(N, L))) * (1.0 - smithlab_pow5(1.0 - dot(N, V))));
    return smithlab_inv_pi * (smooth_term + alpha * (rough - smooth_term));
}
)";

/// GLSL transcription of hammon_2017 (calls smithlab_hammon_2017_single).
inline constexpr std::string_view hammon_2017_glsl =
    R"(// Hammon 2017 read as albedo (single + albedo multi), multi = m alpha.
float smithlab_hammon_2017(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b,
                           float rough_c, float smooth_k, float multi)
{
    float single = smithlab_hammon_2017_single(L, V, N, alpha, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + albedo * (multi * alpha));
}
)";

/// GLSL transcription of hammon_2017_linear (calls smithlab_hammon_2017_single).
inline constexpr std::string_view hammon_2017_linear_glsl =
    R"(// Hammon 2017 read as albedo (single + multi), multi = m alpha.
float smithlab_hammon_2017_linear(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b,
                                  float rough_c, float smooth_k, float multi)
{
    float single = smithlab_hammon_2017_single(L, V, N, alpha, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + multi * alpha);
}
)";

/// "hammon-2017": rough_a, rough_b, rough_c, smooth and multi free, from the published values.
inline DiffuseModel hammon_2017_model() {
    return {.name = "hammon-2017",
            .parameters = {"rough_a", "rough_b", "rough_c", "smooth", "multi"},
            .published = {0.9, 0.4, 0.5, 1.05, 0.1159},
            .source =
                "Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), GGX Diffuse "
                "Approximation: albedo (single + albedo multi)",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double* c) { return hammon_2017(wi, wo, alpha, albedo, hammon_constants(c)); },
            .glsl = Glsl{{hammon_2017_single_glsl, hammon_2017_glsl},
                         "smithlab_hammon_2017(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4})"},
            .ranges = hammon_ranges()};
}

/// "hammon-2017-linear": the same constants.
inline DiffuseModel hammon_2017_linear_model() {
    return {.name = "hammon-2017-linear",
            .parameters = {"rough_a", "rough_b", "rough_c", "smooth", "multi"},
            .published = {0.9, 0.4, 0.5, 1.05, 0.1159},
            .source =
                "Hammon 2017, PBR Diffuse Lighting for GGX+Smith Microsurfaces (GDC), GGX Diffuse "
                "Approximation: albedo (single + multi)",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double* c) { return hammon_2017_linear(wi, wo, alpha, albedo, hammon_constants(c)); },
            .glsl = Glsl{{hammon_2017_single_glsl, hammon_2017_linear_glsl},
                         "smithlab_hammon_2017_linear(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4})"},
            .ranges = hammon_ranges()};
}

}  // namespace smithlab::fit
