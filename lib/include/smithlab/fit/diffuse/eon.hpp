/// @file
/// smithlab/fit/diffuse/eon.hpp -- Portsmouth, Kutz and Hill 2025, "EON: A Practical Energy-Preserving Rough Diffuse
/// BRDF", JCGT 14(1) (the OpenPBR diffuse lobe), roughness r in [0, 1]: the FON single-scattering lobe (Fujii's model
/// at sigma = r, rho = albedo) plus the paper's energy-compensation lobe
///     f_ms = rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) / (1 - `<E_F>`),
///     rho_ms = rho^2 `<E_F>` / (1 - rho (1 - `<E_F>`)),
/// with the paper's exact E_F (eon_fon_albedo) and its closed-form average `<E_F>` (eon_fon_average_albedo).
#pragma once

#include <algorithm>
#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// E_F(mu), the FON lobe's directional albedo at rho = 1 (the paper's exact, analytic form; not its fitted
/// approximation): A (1 + r G(mu)/pi), G(mu) = S (acos(mu) - S mu) + (2/3)((S/mu)(1 - S^3) - S), S = sqrt(1 - mu^2).
inline double eon_fon_albedo(double mu, double r) {
    const double a = 1.0 / (1.0 + common::eon_c1 * r);
    return a * (1.0 + r * common::eon_g(mu) * common::inv_pi);
}

/// `<E_F>` = 2 int_0^1 E_F(mu) mu dmu = A (1 + (2/3 - 28/(15 pi)) r).
inline double eon_fon_average_albedo(double r) { return common::eon_average_albedo(r); }

/// EON's directional albedo (the paper's E_EON): rho E_F(mu) + rho_ms (1 - E_F(mu)); exactly 1 at rho = 1.
inline double eon_albedo(double mu, double r, double albedo) {
    return albedo * eon_fon_albedo(mu, r) + common::eon_rho_ms(r, albedo) * common::eon_one_minus_fon_albedo(mu, r);
}

/// The EON BRDF (Portsmouth, Kutz and Hill 2025): the FON lobe max(0, f_ss) plus the compensation lobe f_ms,
/// roughness r in [0, 1], albedo rho in [0, 1].
inline double eon(const Vec3& wi, const Vec3& wo, double r, double albedo) {
    using common::eon_c1, common::eon_c2, common::inv_pi;
    const double a = 1.0 / (1.0 + eon_c1 * r);
    const double f_ss = albedo * inv_pi * a * (1.0 + r * common::s_over_t(wi, wo));
    // f_ms = rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) / (1 - <E_F>), with 1 - <E_F> = A r (c1 - c2): one factor
    // A r cancels, no 0/0 at r = 0.
    const double one_minus_i = std::max(0.0, eon_c1 - common::eon_g(wi.z()) * inv_pi);
    const double one_minus_o = std::max(0.0, eon_c1 - common::eon_g(wo.z()) * inv_pi);
    const double f_ms =
        common::eon_rho_ms(r, albedo) * inv_pi * (a * r) * (one_minus_i * one_minus_o) / (eon_c1 - eon_c2);
    return std::max(0.0, f_ss) + f_ms;
}

/// GLSL transcription of eon: smithlab_eon(L, V, N, r, albedo).
inline constexpr std::string_view eon_glsl =
    R"(// Portsmouth, Kutz and Hill 2025, EON, JCGT 14(1): the FON lobe plus rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) /
// (1 - <E_F>), the factor A r of 1 - E_F cancelled against 1 - <E_F> = A r (c1 - c2): no 0/0 at r = 0.
float smithlab_eon(vec3 L, vec3 V, vec3 N, float r, float albedo)
{
    float a = 1.0 / (1.0 + smithlab_eon_c1 * r);
    float f_ss = albedo * smithlab_inv_pi * a * (1.0 + r * smithlab_s_over_t(L, V, N));
    float one_minus_i = max(0.0, smithlab_eon_c1 - smithlab_eon_g(dot(N, L)) * smithlab_inv_pi);
    float one_minus_o = max(0.0, smithlab_eon_c1 - smithlab_eon_g(dot(N, V)) * smithlab_inv_pi);
    float f_ms = smithlab_eon_rho_ms(r, albedo) * smithlab_inv_pi * (a * r) * (one_minus_i * one_minus_o) /
                 (smithlab_eon_c1 - smithlab_eon_c2);
    return max(0.0, f_ss) + f_ms;
}
)";

/// "eon": r = clamp(c alpha, 0, 1), c free, start 1 (not published).
inline DiffuseModel eon_model() {
    return {.name = "eon",
            .parameters = {"r_scale"},
            .published = {1.0},
            .source =
                "Portsmouth, Kutz & Hill 2025, EON: A Practical Energy-Preserving Rough Diffuse BRDF, JCGT "
                "14(1), exact E_FON; r = clamp(c alpha, 0, 1), start c = 1 (not published)",
            .f = [](const Vec3& wi, const Vec3& wo, double alpha, double albedo,
                    const double* c) { return eon(wi, wo, std::clamp(c[0] * alpha, 0.0, 1.0), albedo); },
            .glsl = Glsl{{eon_glsl}, "smithlab_eon(L, V, N, clamp({0} * alpha, 0.0, 1.0), albedo)"},
            .ranges = {{0.0, 1.0,
                        "r = clamp(c alpha, 0, 1): above c = 1 EON's roughness r (in [0, 1]) is held at 1 from "
                        "alpha = 1/c on"}}};
}

}  // namespace smithlab::fit
