// The report's scene file (TOML): which grid, which NDFs, which variants, how long to time them.
// experiments/scenes/g1_report.toml documents every key and is the embedded default.
#pragma once

#include <string>
#include <vector>

namespace smithlab::report {

struct NdfFamily {
    std::string family;          // a registered NDF with an `alpha` parameter
    std::vector<double> gammas;  // for gtr; empty otherwise
};

struct Scene {
    std::string title;
    std::vector<double> alphas, mus;
    std::vector<NdfFamily> ndfs;
    std::vector<std::string> include, exclude;  // glob patterns over variant names
    double min_time = 0.05;                     // seconds of Google Benchmark per variant
};

// Throws input_error naming the scene (source) and the offending key.
Scene parse_scene(const std::string& text, const std::string& source);

// The default scene, embedded at build time from experiments/scenes/g1_report.toml.
const std::string& default_scene_text();

// '*' matches any run of characters, everything else itself.
bool glob_match(const std::string& pattern, const std::string& name);

}  // namespace smithlab::report
