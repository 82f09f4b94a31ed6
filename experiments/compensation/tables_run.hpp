// Running a tables scene into an output directory: the energy-compensation stage alone (compensation/stage.hpp), with
// report.md (the scene's title and the stage's section) and meta.json, all staged and moved in together when every one
// is written (output/staged_directory.hpp), so that a failed or killed run leaves the previous ones whole.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "compensation/tables_scene.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::compensation {

// What the run prints: each measured table's worst errors (compensation_error.csv's), and its time.
struct TablesSummary {
    struct Row {
        std::string ndf, g2, table;
        double interpolation = 0.0, furnace = 0.0;
    };
    std::vector<Row> rows;
    double seconds = 0.0;
};

TablesSummary run_tables(const TablesScene& scene, const std::string& source, const std::string& scene_text,
                         const NdfRegistry& registry, const std::filesystem::path& out, unsigned threads);

}  // namespace smithlab::compensation
