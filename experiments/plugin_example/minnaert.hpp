// A diffuse model of one's own for `smithlab fit`, in one file: its formula with its source, its free constant and
// its GLSL. main.cpp registers it (one line); tests/extending_diffuse.cpp checks it.
//
// Minnaert 1941, "The reciprocity principle in lunar photometry", ApJ 93, 403: radiance cos^k(i) cos^(k-1)(e), as a
// BRDF scaled so that its directional albedo at normal incidence is the albedo (the hemisphere integral of
// (mu_i mu_o)^(k-1) mu_o is 2 pi mu_i^(k-1) / (k + 1)):
//     f = albedo (k + 1)/(2 pi) (mu_i mu_o)^(k - 1),   k = 1 + s alpha,  s free (start 0: Lambert).
#pragma once

#include <cmath>
#include <numbers>
#include <string_view>

#include <smithlab/fit/diffuse_model.hpp>

// f(wi, wo) in the fitter's shape: c[0] = s.
inline double minnaert(const smithlab::Vec3& wi, const smithlab::Vec3& wo, double alpha, double albedo,
                       const double* c) {
    const double k = 1.0 + c[0] * alpha;
    return albedo * (k + 1.0) / (2.0 * std::numbers::pi) * std::pow(wi.z() * wo.z(), k - 1.0);
}

// The same in GLSL 3.30; smithlab_inv_pi is one of smithlab's common helpers (smithlab/fit/diffuse/common.hpp).
inline constexpr std::string_view minnaert_glsl = R"(// Minnaert 1941: albedo (k + 1)/(2 pi) (N.L N.V)^(k - 1).
float minnaert_brdf(vec3 L, vec3 V, vec3 N, float k, float albedo)
{
    return albedo * (k + 1.0) * (0.5 * smithlab_inv_pi) * pow(dot(N, L) * dot(N, V), k - 1.0);
}
)";

inline smithlab::fit::DiffuseModel minnaert_model() {
    return {.name = "minnaert",
            .parameters = {"k_scale"},
            .published = {0.0},
            .source =
                "Minnaert 1941, The reciprocity principle in lunar photometry, ApJ 93; k = 1 + s alpha, start "
                "s = 0 (Lambert)",
            .f = minnaert,
            .glsl = smithlab::fit::Glsl{{minnaert_glsl}, "minnaert_brdf(L, V, N, 1.0 + {0} * alpha, albedo)"},
            .own_baseline = false};  // at its start it is lambert: not measured again as a model of its own
}
