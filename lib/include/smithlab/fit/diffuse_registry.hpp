/// @file
/// smithlab/fit/diffuse_registry.hpp -- diffuse models by name (fit/diffuse_model.hpp): the models `smithlab fit`
/// fits, lists and exports as GLSL.
///
/// A registry is a value, not a global: every NdfRegistry holds one, with the built-in models
/// (registry.diffuse_models(); builtin_diffuse_registry(), fit/diffuse_models.hpp); a program of one's own adds to it
/// and hands the NdfRegistry to run_cli (smithlab/cli.hpp).
/// Registering a model is one call, of a DiffuseModel that names its GLSL transcription or says it has none:
///     registry.diffuse_models().add({.name = "mine", .parameters = {"k"}, .published = {1.0}, .source = "...", .f =
///     mine_f,
///                 .glsl = smithlab::fit::Glsl{{mine_glsl}, "smithlab_mine(L, V, N, {0}, albedo)"}});
/// The model is then fitted (by every scene that names no `models`, and by those that name it), listed
/// (`smithlab list`, `smithlab fit --list-models`) and exported (models.glsl and brdf/, unless it has no GLSL).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "smithlab/fit/diffuse_model.hpp"

namespace smithlab::fit {

/// Diffuse models by name, in registration order: each checked when added, so that every one can be fitted, listed and
/// exported.
class DiffuseRegistry {
public:
    /// Adds a model; input_error naming it where its name is not lower-case letters, digits and '-' from a letter or
    /// digit on (or ends in
    /// "-fitted", the outputs' suffix of a refitted model), is registered already or has another's GLSL name
    /// (glsl_identifier), or where it has no source, no f, not one published value per constant, a constant's name
    /// empty or repeated, ranges neither empty nor one per constant, or a GLSL transcription that cannot be exported
    /// (glsl_transcription_problem, fit/glsl.hpp).
    void add(DiffuseModel model);
    const DiffuseModel* find(std::string_view name) const;  ///< nullptr where none has that name
    /// The model named `name`; input_error naming it and listing the known names otherwise.
    const DiffuseModel& at(std::string_view name) const;
    const std::vector<DiffuseModel>& list() const { return models_; }  ///< in registration order
    std::string names() const;                                         ///< "lambert, disney, ..."

private:
    std::vector<DiffuseModel> models_;
};

}  // namespace smithlab::fit
