// Running a fit scene into an output directory: trace (or reuse) the data, fit every model to every NDF family,
// measure each on the validation set, and write the constants, errors, tables and pictures. The traced points are
// cached in OUT/cache/ as they finish (fit_data.hpp); the outputs are staged and moved in together when all are
// written (StagedDirectory), so a failed or killed run leaves the previous ones whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_scene.hpp"
#include "smithlab/fit/fit_model.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fitrun {

// One row of errors.csv: a model (a fixed baseline, a model at its published constants, or "<model>-fitted") on one
// NDF family, measured on the validation set.
struct ErrorRow {
    std::string model, ndf;
    double rms_rel, max_rel, albedo_rms, chi2_dof;
    fit::AlbedoPeak peak;  // the largest directional albedo at albedo 1 (training alphas x theta_i 0..89)
    fit::GridCheck grid;   // the largest relative |f(l, v) - f(v, l)|, the smallest f
};

struct FitSummary {
    std::int64_t points = 0, traced = 0, reused = 0;
    double seconds = 0.0;
    std::vector<ErrorRow> errors;
};

FitSummary run_fit(const FitScene& scene, const std::string& source, const std::string& scene_text,
                   const NdfRegistry& registry, const std::filesystem::path& out, unsigned threads);

}  // namespace smithlab::fitrun
