// Running a fit scene into an output directory: trace (or reuse) the data, fit every model to every NDF family,
// measure each on the validation set, flag the fits that look wrong, and write the constants, errors, tables and
// pictures. The traced points (the data's and the pictures') are cached in OUT/cache/ as they finish
// (fit/point_cache.hpp); the outputs are staged and moved in together when all are written (StagedDirectory), so a
// failed or killed run leaves the previous ones whole.
//
// The pieces: fit/fit_data.hpp (the traced data), fit/fit_models.hpp (fitting and measuring), fit/fit_flags.hpp,
// fit/fit_tables.hpp (the CSV and JSON tables), fit/fit_shaders.hpp, compensation/stage.hpp, fit/fit_trends.hpp,
// fit/fit_pictures.hpp, fit/fit_report.hpp (report.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_results.hpp"
#include "fit/fit_scene.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fit {

struct FitSummary {
    std::int64_t points = 0, traced = 0, reused = 0;
    double seconds = 0.0;
    std::vector<ErrorRow> errors;
};

FitSummary run_fit(const FitScene& scene, const std::string& source, const std::string& scene_text,
                   const NdfRegistry& registry, const std::filesystem::path& out, unsigned threads);

}  // namespace smithlab::fit
