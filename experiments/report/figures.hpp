// The report's figures: the Dimov 2015 reproductions' data and numbers, and the sections of report.md that show the
// PNGs the scene names ([figures]), drawn by experiments/plots/report_plots.py once every section has written its
// files (report.cpp). The section that runs it: sections/figures.cpp.
#pragma once

#include <filesystem>

#include "report/settings.hpp"

namespace smithlab::report {

// Appends the figure sections to DIR/report.md and writes the Dimov reproductions' data (DIR/dimov/*.csv).
void write_figures(const Settings::Figures& fig, const std::filesystem::path& dir);
// Whether any of these figures is drawn (pareto, error_maps, dimov_heightfields, dimov_gamma4_vs_10).
bool draws_figures(const Settings::Figures& fig);

}  // namespace smithlab::report
