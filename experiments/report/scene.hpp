// The report's scene file (TOML): its settings (settings.hpp) and its sections (section.hpp), each reading its own
// keys. experiments/scenes/g1_report.toml documents every key of the built-in sections and is the embedded default.
#pragma once

#include <string>

#include "report/section.hpp"
#include "report/settings.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::report {

struct Scene {
    Settings settings;
    Sections sections;  // in the order they run and write
};

// Read strictly (strict_table.hpp): an unknown key or section (one neither the settings nor a section reads), a
// value of the wrong type (an integer is taken for a real), an integer out of its bounds (an axis's n in [2, 1e7],
// sampling.samples in [100, 1e8], walk.walks in [100, 1e9]), a walk material its parser refuses, a walk.theta_i
// outside [0, 90) are refused with an input_error "SOURCE:LINE: key ..." naming the nearest known key or the
// expected type. The [[ndf]] tables are read by scene_ndf.hpp against the registry (a family it lacks, a parameter
// the family lacks); each NDF's values are checked by the registry, and the size of the work is estimated
// (work_estimate.hpp), before anything is computed. `sections` are the built-in ones unless given; `scale` is
// --scale (Settings::scale).
Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry, double scale = 1.0);
Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry, Sections sections,
                  double scale = 1.0);

// The default scene, embedded at build time from experiments/scenes/g1_report.toml.
const std::string& default_scene_text();

// '*' matches any run of characters, everything else itself.
bool glob_match(const std::string& pattern, const std::string& name);

// Refuses, naming key and its FILE:LINE, a mu that is not finite and > 0 (grid.mu, g2.mu: directions above).
void require_positive_mus(const scene::StrictTable& table, const std::string& key, const std::vector<double>& mus);

// Refuses a pattern that matches none of `names`: input_error "WHERE: pattern 'P' matches no name (did you mean
// 'N'?)", `where` being the key's "FILE:LINE: variants.include" (scene::StrictTable::where).
void require_matches(const std::vector<std::string>& patterns, const std::vector<std::string>& names,
                     const std::string& where);

}  // namespace smithlab::report
