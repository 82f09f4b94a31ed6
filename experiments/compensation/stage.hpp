// The energy-compensation stage: the tables a [compensation] table asks for (compensation/settings.hpp) for every NDF
// family and G2 form, each measured on its check grid (compensation/tables.hpp) and in the furnace against the walk
// (compensation/walk_furnace.hpp), written into an output directory (compensation/table_files.hpp) with the furnace's
// figure (plots/compensation_plots.py: furnace.png). `smithlab fit` runs it after its fit where its scene has
// [compensation]; `smithlab tables` runs it alone (compensation/tables_run.hpp). The same settings, families and seed
// give the same bytes from either.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "compensation/tables.hpp"
#include "scene/alpha_family.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::compensation {

struct StageOutput {
    std::vector<FamilyTables> tables;  // of `families`, which they point to
    std::string markdown;              // report.md's section
};

// Runs the stage into dir; nothing (no file, no section) unless c.enabled.
StageOutput run_compensation(const std::filesystem::path& dir, const std::vector<scene::AlphaFamily>& families,
                             const Settings& c, const NdfRegistry& registry, const StageRun& run);

}  // namespace smithlab::compensation
