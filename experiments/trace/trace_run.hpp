// Running a trace scene into an output directory, resumably.
//
// Every finished cell is written at once, atomically, to OUT/cells/cell-NNNNNN.csv (trace/cell_file.hpp): its rows of
// albedo.csv and brdf.csv as they will appear there but for the NDF parameter columns (trace/trace_rows.hpp; 17
// digits: they round-trip), its bounces, and a key line naming all that defines it (version, NDF, material,
// direction, walks, seed, cell index, max_order, downward, hit_normal, brdf bins; not the thread count, which changes
// no bit). A run first reads the cells whose key matches and traces only the rest,
// so a killed run resumes from its last finished cell, and the same scene run again traces nothing. A cell file
// that does not parse, or whose key differs, is traced again. When every cell is there, albedo.csv, brdf.csv (when
// the scene asks) and meta.json are assembled from the cell files and published together (StagedDirectory): the
// same scene and seed give the same bits for any --threads, resumed or not.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "smithlab/registry.hpp"
#include "trace/trace_scene.hpp"

namespace smithlab::trace {

struct RunSummary {
    std::int64_t cells = 0, traced = 0, reused = 0, bounces = 0;
    double seconds = 0.0;
    std::vector<walk::Estimate> total;  // per cell: the albedo over every hemisphere, order and component
};

// Every NDF and material spec of the scene is checked (and every microsurface prepared once) before anything is
// written: a bad one is an input_error naming it, and OUT is left as it was.
RunSummary run_scene(const TraceScene& scene, const std::string& source, const NdfRegistry& registry,
                     const std::filesystem::path& out, unsigned threads);

}  // namespace smithlab::trace
