// Kulla-Conty energy compensation for each NDF family of a fit scene over compensation.alpha (no tracing: quadrature
// of the single-scattering BRDF of mirror facets, smithlab/fit/compensation.hpp): compensation.csv,
// compensation_avg.csv (one column per NDF parameter after the ndf column) and a C header per family.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_scene.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fitrun {

// Writes the files into dir and returns report.md's section (the table of E_avg); "" without compensation alphas.
std::string write_compensation(const std::filesystem::path& dir, const std::vector<FitFamily>& families,
                               const FitScene::Compensation& compensation, const NdfRegistry& registry);

}  // namespace smithlab::fitrun
