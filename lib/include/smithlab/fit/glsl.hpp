/// @file
/// smithlab/fit/glsl.hpp -- diffuse models (fit/diffuse_model.hpp) as GLSL at given constants, from the transcription
/// each model carries (DiffuseModel::glsl): a library a renderer pastes in (one function per model and NDF family, the
/// constants inlined) and Disney's BRDF Explorer's analytic .brdf format. Pure text: nothing is written here.
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

#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// A model at the constants to export: `name` as in the outputs ("hammon-2017" at the published constants,
/// "hammon-2017-fitted" refitted), `ndf` the NDF family's label ("gtr(gamma=1.5)"), `constants` one per
/// model.parameters, `stderrs` their standard errors (empty when not fitted).
struct ShaderModel {
    /// The model's name in the outputs and the NDF family's label.
    ///@{
    std::string_view name, ndf;
    ///@}
    const DiffuseModel* model;  ///< the model exported, with its GLSL transcription (DiffuseModel::glsl)
    /// The constants, one per model.parameters, and their standard errors (empty when not fitted).
    ///@{
    std::span<const double> constants, stderrs;
    ///@}
};

/// `text` as a GLSL identifier or file-name part: lower-case letters and digits kept, '.' -> 'p', every other run of
/// characters -> one '_', none at either end ("gtr(gamma=1.5)" -> "gtr_gamma_1p5", "hammon-2017" -> "hammon_2017").
std::string glsl_identifier(std::string_view text);
/// The function's name: smithlab_<name>_<ndf>, both as glsl_identifier ("smithlab_hammon_2017_fitted_ggx").
std::string glsl_function_name(const ShaderModel& m);
/// v as a GLSL float literal, 9 significant digits (a float's exact round trip), never an int literal ("1.0", not
/// "1"); negative values in parentheses. input_error on NaN or infinity.
std::string glsl_float(double v);

/// Why m's transcription cannot be exported: its call does not start with a call of a function that its functions or
/// the common helpers define ("float NAME("), or a brace in it opens no {i} of a constant m has, or it leaves a
/// constant out. Empty when it can be, and when m has none (no_glsl).
std::string glsl_transcription_problem(const DiffuseModel& m);

/// What the functions of `models` call, once, before them: the common helpers (fit/diffuse/common.hpp: smithlab_pi,
/// smithlab_inv_pi, smithlab_eon_c1, smithlab_eon_c2, smithlab_pow5, ..., smithlab_eon_rho_ms), then each model's own
/// functions (Glsl::functions), each text once, in the order the models first name them.
std::string glsl_helpers(std::span<const ShaderModel> models);
/// One model's function with a comment citing its source and giving its constants and their standard errors.
/// input_error naming the model when it has no GLSL transcription or the constants do not match its parameters.
std::string glsl_function(const ShaderModel& m);
/// The whole library: a header comment, glsl_helpers(models), then glsl_function of each, or for a model without
/// GLSL a comment line saying that it has none (DIR/models.glsl).
std::string glsl_library(std::span<const ShaderModel> models);
/// BRDF Explorer's analytic format: albedo and alpha as sliders (albedo 0..1, default 0.75; alpha 0.001..1, default
/// 0.25), `helpers` (glsl_helpers of the models exported together: every file of one export holds the same) and the
/// function, and BRDF(L, V, N, X, Y) calling it (0 where L or V is below the surface). input_error as glsl_function.
std::string brdf_explorer_file(const ShaderModel& m, std::string_view helpers);

}  // namespace smithlab::fit
