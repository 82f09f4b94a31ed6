// The scene of `smithlab tables` (TOML, read strictly: scene/strict_table.hpp): a title, the random streams' seed, the
// NDF families ([[ndf]], each swept over compensation.alpha) and [compensation] (compensation/settings.hpp), the same
// table as a fit scene's. experiments/scenes/tables_default.toml documents every key and is the embedded default.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "scene/alpha_family.hpp"
#include "scene/limits.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::compensation {

struct TablesScene {
    std::string title = "smithlab tables";
    std::uint64_t seed = 1;
    std::vector<scene::AlphaFamily> ndfs;  // the [[ndf]] axes expanded: one entry per family
    Settings compensation;
};

// Refuses (input_error "SOURCE:LINE: key ...") an unknown key or section, a value of the wrong type, a seed out of
// [0, 2^63), an [[ndf]] whose family is not registered, a parameter the family does not have, an axis for its
// roughness (alpha is compensation.alpha's), no [[ndf]] or no [compensation], and what read_settings refuses (the
// size against limits.max_walks included).
TablesScene parse_tables_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                               const scene::SizeLimits& limits = {});

const std::string& default_tables_scene_text();

}  // namespace smithlab::compensation
