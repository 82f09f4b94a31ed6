/// @file
/// smithlab/fit/diffuse/lambert.hpp -- Lambert's diffuse BRDF, the baseline every rough model reduces to at zero
/// roughness: f = albedo / pi (Lambert 1760, Photometria).
#pragma once

#include <string_view>

#include "smithlab/fit/diffuse/common.hpp"
#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Lambert: albedo / pi.
inline double lambert(double albedo) { return albedo * common::inv_pi; }

/// GLSL transcription of lambert: smithlab_lambert(albedo).
inline constexpr std::string_view lambert_glsl =
    R"(// Lambert: albedo / pi.
float smithlab_lambert(float albedo)
{
    return albedo * smithlab_inv_pi;
}
)";

/// "lambert": no constants.
inline DiffuseModel lambert_model() {
    return {.name = "lambert",
            .source = "Lambert 1760, Photometria: albedo/pi",
            .f = [](const Vec3&, const Vec3&, double, double albedo, const double*) { return lambert(albedo); },
            .glsl = Glsl{{lambert_glsl}, "smithlab_lambert(albedo)"}};
}

}  // namespace smithlab::fit
