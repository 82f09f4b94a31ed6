// The fit's pictures (PNG, drawn by experiments/plots/fit_plots.py from CSV written here): lit spheres as Hammon laid
// them out, Disney-style BRDF slices, the light single scattering misses, and the fitted constants against gamma.
#pragma once

#include <filesystem>
#include <string>

#include "fit_results.hpp"
#include "fit_scene.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fitrun {

// Writes the pictures' data and PNGs into dir when the scene asks (scene.pictures.enabled); returns the Markdown that
// shows them in report.md ("" when none).
std::string write_pictures(const std::filesystem::path& dir, const FitScene& scene, const Results& results,
                           const NdfRegistry& registry, unsigned threads);

}  // namespace smithlab::fitrun
