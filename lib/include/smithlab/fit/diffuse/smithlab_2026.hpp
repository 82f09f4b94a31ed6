/// @file
/// smithlab/fit/diffuse/smithlab_2026.hpp -- smithlab's own family (designed from the traced data, `smithlab fit`):
/// Hammon's single term (fit/diffuse/hammon_2017.hpp) with the roughness blend t = alpha^p instead of alpha (the traced
/// single-event light turns rough faster than linearly in alpha), and a multiple-scattering lobe that grows as alpha^q
/// with a term in 1 - facing, so that it can lean toward or away from forward scattering (the traced k >= 2 light of
/// GGX alpha = 1 is 1.85x brighter toward forward grazing than at normal incidence, and dimmer toward grazing
/// retro-reflection):
///     single = (1/pi) lerp(smooth, rough, alpha^p)   (smooth, rough as Hammon's, constants a, b, c, k),
///     multi  = m alpha^q (1 + u (1 - facing)),  facing = 0.5 + 0.5 L.V,
///     f = albedo (single + albedo multi).
/// At (p, q, u) = (1, 1, 0) it is Hammon 2017: those are its starting constants.
#pragma once

#include <cmath>
#include <string_view>
#include <vector>

#include "smithlab/fit/diffuse/hammon_2017.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// The constants of smithlab-2026: Hammon's (a, b, c, k, m) and (p, q, u); the defaults make it Hammon 2017.
struct Smithlab2026Constants {
    /// Hammon 2017's constants: the single term's a, b, c, k and the multiple-scattering scale m.
    HammonConstants hammon;
    /// p: the roughness blend t = alpha^p; q: multi grows as alpha^q; u: the multi term's lean 1 + u (1 - facing).
    ///@{
    double p = 1.0, q = 1.0, u = 0.0;
    ///@}
};

/// smithlab-2026 (file comment): albedo (single + albedo multi), single Hammon's blended by alpha^p, multi =
/// m alpha^q (1 + u (1 - facing)); alpha the GGX roughness, albedo in [0, 1].
inline double smithlab_2026(const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                            const Smithlab2026Constants& k) {
    const double t = std::pow(alpha, k.p);
    const double facing = 0.25 * (wi + wo).squaredNorm();
    const double multi = k.hammon.multi * std::pow(alpha, k.q) * (1.0 + k.u * (1.0 - facing));
    return albedo * (hammon_2017_single(wi, wo, t, k.hammon) + albedo * multi);
}

/// The ranges of smithlab-2026's eight constants: Hammon's (hammon_ranges), then p and q positive, u above -1.
inline std::vector<ParameterRange> smithlab_2026_ranges() {
    constexpr double inf = INFINITY;
    std::vector<ParameterRange> r = hammon_ranges();
    r.push_back({0.0, inf, "the roughness blend alpha^p: at p <= 0 it does not vanish as alpha -> 0"});
    r.push_back({0.0, inf, "multi = m alpha^q: at q <= 0 it does not vanish as alpha -> 0"});
    r.push_back({-1.0, inf, "1 + u (1 - facing), facing in [0, 1]: negative below u = -1"});
    return r;
}

/// GLSL transcription of smithlab_2026 (calls smithlab_hammon_2017_single).
inline constexpr std::string_view smithlab_2026_glsl =
    R"(// smithlab 2026 (this tool's own family, from the traced data): Hammon's single term blended by t = alpha^p,
// multi = m alpha^q (1 + u (1 - facing)), f = albedo (single + albedo multi).
float smithlab_2026(vec3 L, vec3 V, vec3 N, float alpha, float albedo, float rough_a, float rough_b, float rough_c,
                    float smooth_k, float multi, float blend_power, float multi_power, float multi_forward)
{
    float t = pow(alpha, blend_power);
    float facing = 0.25 * dot(L + V, L + V);
    float multi_term = multi * pow(alpha, multi_power) * (1.0 + multi_forward * (1.0 - facing));
    float single = smithlab_hammon_2017_single(L, V, N, t, rough_a, rough_b, rough_c, smooth_k);
    return albedo * (single + albedo * multi_term);
}
)";

/// "smithlab-2026": Hammon's constants and p, q, u free; it starts at hammon-2017, so it is no baseline of its own.
inline DiffuseModel smithlab_2026_model() {
    return {.name = "smithlab-2026",
            .parameters = {"rough_a", "rough_b", "rough_c", "smooth", "multi", "blend_power", "multi_power",
                           "multi_forward"},
            .published = {0.9, 0.4, 0.5, 1.05, 0.1159, 1.0, 1.0, 0.0},
            .source =
                "smithlab 2026 (this tool's own, from the traced data): Hammon 2017's single term blended by "
                "alpha^p, multi = m alpha^q (1 + u (1 - facing)); starts at Hammon's constants",
            .f =
                [](const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c) {
                    return smithlab_2026(wi, wo, alpha, albedo, {hammon_constants(c), c[5], c[6], c[7]});
                },
            .glsl = Glsl{{hammon_2017_single_glsl, smithlab_2026_glsl},
                         "smithlab_2026(L, V, N, alpha, albedo, {0}, {1}, {2}, {3}, {4}, {5}, {6}, {7})"},
            .own_baseline = false,
            .ranges = smithlab_2026_ranges()};
}

}  // namespace smithlab::fit
