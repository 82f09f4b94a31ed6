/// @file
/// smithlab/fit/glsl.hpp -- the diffuse models (fit/diffuse_models.hpp) as GLSL at given constants: a
/// library a renderer pastes in (one function per model and NDF family, the constants inlined) and Disney's BRDF
/// Explorer's analytic .brdf format. Pure text: nothing is written here.
///
/// The GLSL is GLSL 3.30 (also 4.10, BRDF Explorer's), no extensions, no `#version` line (it goes after the
/// includer's). Each function is float f(vec3 L, vec3 V, vec3 N, float alpha, float albedo): the BRDF without the
/// cosine, L toward the light, V toward the viewer, N the normal, all unit vectors with dot(N, L) > 0 and dot(N, V) > 0
/// (the C++ models' domain: none of them guards the lower hemisphere; the .brdf wrapper returns 0 there).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "smithlab/fit/diffuse_models.hpp"

namespace smithlab::fit {

/// A model at the constants to export: `name` as in the outputs ("hammon-2017" at the published constants,
/// "hammon-2017-fitted" refitted), `ndf` the NDF family's label ("gtr(gamma=1.5)"), `constants` one per
/// model.parameters, `stderrs` their standard errors (empty when not fitted).
struct ShaderModel {
    /// `name` as in the outputs, `ndf` the NDF family's label.
    /// @{
    std::string_view name, ndf;
    /// @}
    /// The model (diffuse_models.hpp) whose GLSL is written.
    const DiffuseModel* model;
    /// The constants, one per model.parameters, and their standard errors (empty when not fitted).
    /// @{
    std::span<const double> constants, stderrs;
    /// @}
};

/// `text` as a GLSL identifier or file-name part: lower-case letters and digits kept, '.' -> 'p', every other run of
/// characters -> one '_', none at either end ("gtr(gamma=1.5)" -> "gtr_gamma_1p5", "hammon-2017" -> "hammon_2017").
std::string glsl_identifier(std::string_view text);
/// The function's name: smithlab_<name>_<ndf>, both as glsl_identifier ("smithlab_hammon_2017_fitted_ggx").
std::string glsl_function_name(const ShaderModel& m);
/// v as a GLSL float literal, 9 significant digits (a float's exact round trip), never an int literal ("1.0", not
/// "1"); negative values in parentheses. input_error on NaN or infinity.
std::string glsl_float(double v);

/// The helpers every function calls (pow5, each model's formula in its physical parameters, as the C++ has them):
/// once, before the functions.
std::string glsl_helpers();
/// One model's function with a comment citing its source and giving its constants and their standard errors.
/// input_error naming the model when it has no GLSL transcription or the constants do not match its parameters.
std::string glsl_function(const ShaderModel& m);
/// The whole library: a header comment, glsl_helpers(), then glsl_function of each (DIR/models.glsl).
std::string glsl_library(std::span<const ShaderModel> models);
/// BRDF Explorer's analytic format: albedo and alpha as sliders (albedo 0..1, default 0.75; alpha 0.001..1, default
/// 0.25), the helpers and the function, and BRDF(L, V, N, X, Y) calling it (0 where L or V is below the surface).
std::string brdf_explorer_file(const ShaderModel& m);

}  // namespace smithlab::fit
