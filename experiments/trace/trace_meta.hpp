// trace/trace_meta.hpp -- trace's meta.json: the run's recipe (the scene as TOML, seed, version) and what it did.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "trace/trace_scene.hpp"

namespace smithlab::trace {

// The scene as TOML that parse_trace_scene reads back to the same cells (meta.json keeps it: the run's recipe).
std::string format_trace_scene(const TraceScene& scene);

// A cell's entry in meta.json's "cells".
struct CellMeta {
    std::uint64_t index;
    std::string ndf, material;
    double theta_i, phi_i;
    std::int64_t bounces, capped_walks;
};

// What a run did: its cells, how many it traced and reused, their bounces, its seconds and threads (per rank on
// several ranks).
struct RunMeta {
    std::vector<CellMeta> cells;
    std::int64_t traced = 0, reused = 0, bounces = 0;
    double seconds = 0.0;
    unsigned threads = 0;
};

// meta.json's object, keys in this order: title, source, scene, version, seed, walks, max_order, downward, hit_normal,
// cells, cells_traced, cells_reused, bounces, seconds, threads (a run on several ranks adds "mpi" after them).
nlohmann::ordered_json trace_meta(const TraceScene& scene, const std::string& source, const RunMeta& run);

}  // namespace smithlab::trace
