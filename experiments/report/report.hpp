// smithlab report: every selected Lambda variant on the scene's grid, against an independent reference, with its
// run time from Google Benchmark. Writes DIR/variants.csv, DIR/report.md, DIR/bench.json and a reference cache; with
// the scene's [g2], [sampling] and [walk] sections, their tables (g2_variants.csv, sampling.csv, walk_albedo.csv).
// The work is done by the scene's sections (section.hpp), phase by phase.
#pragma once

#include <string>

#include "report/scene.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

// Returns the process exit code; throws input_error for a scene that names unknown NDFs or selects nothing (before
// anything is computed or written).
int run_report(Scene& scene, const std::string& out_dir, const NdfRegistry& ndfs, const VariantRegistry& variants);

}  // namespace smithlab::report
