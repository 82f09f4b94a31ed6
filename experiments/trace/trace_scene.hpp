// The path tracer's scene file (TOML, read strictly like the report's: strict_table.hpp): which NDFs, materials
// and incident directions, how many walks, and which tallies. experiments/scenes/trace_default.toml documents every
// key and is the embedded default. A scene expands to cells, NDF x material x theta_i x phi_i in that order; a
// cell's position in that order keys its random stream.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "scene/limits.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/walk/tally.hpp"

namespace smithlab::trace {

// An NDF of the scene: a spec as the scene (ndf.spec) or --ndf gives it, or a family at a point of the grid.
struct SceneNdf {
    std::string spec;               // as shown (the scene in meta.json, the cells): a given spec as written
    std::optional<NdfSpec> family;  // a family's name and parameters; none: the NDF is the spec given
    // Through the registry: a family from its parameters (no spec parsed), a given spec from its text.
    AnyNdf make(const NdfRegistry& registry) const {
        return family ? registry.make(family->name, family->params, family->texts) : registry.make(spec);
    }
};

struct TraceScene {
    std::string title = "smithlab trace";
    std::vector<SceneNdf> ndfs;          // the families already expanded over their axes
    std::vector<std::string> materials;  // facet material specs
    std::vector<double> theta_i, phi_i;  // degrees
    std::int64_t walks = 200'000;        // per cell
    std::uint64_t seed = 1;
    int max_order = 0;                   // 0: no limit
    std::string downward = "smith";      // or "hammon"
    std::string hit_normal = "visible";  // or "hammon" (Hammon's D cos facing the ray)
    walk::BrdfBins brdf;                 // empty: no brdf.csv
};

// What every cell of a scene shares and its bits depend on: the [walks] and [brdf] settings.
struct CellSettings {
    std::int64_t walks = 0;
    std::uint64_t seed = 1;
    int max_order = 0;
    std::string downward, hit_normal;
    walk::BrdfBins brdf;
};
inline CellSettings cell_settings(const TraceScene& s) {
    return {s.walks, s.seed, s.max_order, s.downward, s.hit_normal, s.brdf};
}

// One cell of a scene: where it stands in the sweep and what it traces.
struct TraceCell {
    std::uint64_t index;
    std::string ndf, material;
    double theta_i, phi_i;
};

// Refuses (input_error "SOURCE:LINE: key ...") an unknown key or section, a value of the wrong type, an integer out
// of its bounds (walks.n in [1, 1e12], walks.max_order in [0, 1e6], brdf bins in [1, 1e4]), a theta_i outside
// [0, 180] or at 90 (grazing), or a non-finite phi_i; light from below (theta_i > 90) is checked against each
// material when the cells are prepared (only a dielectric takes it). NDF and material specs are checked by their
// parsers when the cells are prepared.
// [[ndf]] tables are read as every scene's (scene/scene_ndf.hpp): a family with an axis for any of its parameters,
// swept over grid.alpha unless it gives its own roughness axis; each point is made (checked) by the registry here.
// The scene's size is checked as its [[ndf]] entries are read, before their NDFs are made: cells (each [brdf] bin
// counted as a cell) beyond limits.max_cells or walks in all beyond limits.max_walks are refused at the entry that
// passes the bound (scene/limits.hpp).
TraceScene parse_trace_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                             const scene::SizeLimits& limits = {});

// The embedded default, from experiments/scenes/trace_default.toml.
const std::string& default_trace_scene_text();

std::vector<TraceCell> cells(const TraceScene& scene);

}  // namespace smithlab::trace
