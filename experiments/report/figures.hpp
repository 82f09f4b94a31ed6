// The report's figures: the Dimov 2015 reproductions' data and numbers, then every PNG the scene names, drawn by
// experiments/plots/report_plots.py (Debian's python3-matplotlib) from the CSV files beside report.md.
#pragma once

#include <filesystem>

#include "report/scene.hpp"

namespace smithlab::report {

// Appends the figure sections to DIR/report.md; the per-variant points/*.csv must already be written.
void write_figures(const Scene& scene, const std::filesystem::path& dir);

}  // namespace smithlab::report
