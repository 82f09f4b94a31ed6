// Every fitted model as code a renderer or BRDF Explorer loads: OUT/models.glsl (a GLSL function per fitted model and
// NDF, its constants inlined) and OUT/brdf/MODEL-NDF.brdf (Disney's BRDF Explorer's analytic format, with albedo and
// alpha as sliders). A model that has no GLSL transcription (fit::no_glsl) is named in models.glsl as having none.
#pragma once

#include <filesystem>

#include "fit/fit_results.hpp"

namespace smithlab::fit {

void write_shaders(const std::filesystem::path& dir, const Results& results);

}  // namespace smithlab::fit
