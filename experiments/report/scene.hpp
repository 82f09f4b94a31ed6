// The report's scene file (TOML): which grid, which NDFs, which variants, how long to time them.
// experiments/scenes/g1_report.toml documents every key and is the embedded default.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_ndf.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::report {

struct Scene {
    std::string title;
    std::vector<double> alphas, mus;
    std::vector<NdfEntry> ndfs;                 // each swept over alphas unless it gives its own roughness axis
    std::vector<std::string> include, exclude;  // glob patterns over variant names
    double min_time = 0.05;                     // seconds of Google Benchmark per variant
    // The G2 table (Hammon's lerp and the uncorrelated forms against the exact height-correlated G2), over
    // alpha x mu_i x mu_o for the named families. Empty include: no G2 table.
    struct G2Table {
        std::vector<std::string> include;
        std::vector<std::string> families = {"ggx"};
        std::vector<double> mus;
    } g2;
    // The sampling-efficiency experiment (sampling_experiment.hpp): absent (families empty) unless named.
    struct Sampling {
        std::vector<std::string> families;
        std::vector<double> alphas;
        double theta_o = 45.0;           // degrees
        std::size_t samples = 100000;    // per estimate
        unsigned long long seed = 1;
    } sampling;
    // The walk section (walk_section.hpp): albedo by scattering order against alpha on the Smith microsurface,
    // traced for each family x material x alpha x theta_i. Absent (ndfs empty) unless named.
    struct Walk {
        std::vector<NdfEntry> ndfs;
        std::vector<std::string> materials = {"mirror", "lambert(albedo=1)"};  // facet specs (walk/facets.hpp)
        std::vector<double> alphas;
        std::vector<double> theta_i = {45.0};  // degrees, in [0, 90)
        std::int64_t walks = 20000;            // per cell
        unsigned long long seed = 1;
    } walk;
    struct Figures {
        bool pareto = false;              // error against ns/eval, log-log, every variant
        bool error_maps = false;          // |dG1| over (alpha, mu), worst over gamma, one map per variant
        bool dimov_heightfields = false;  // Dimov 2015 sec. 4: G1 for gamma = 0..4, alpha in (0.1, 0.5), mu in (0, 5)
        bool dimov_spline_mean = false;   // Dimov 2015 sec. 5: the spline's mean |dG1| (published: about 0.001)
        bool dimov_gamma4_vs_10 = false;  // Dimov 2015 sec. 6: |G1(gamma=4) - G1(gamma=10)|, alpha in (0,1), mu in (0,2)
    } figures;
};

// Read strictly (strict_table.hpp): an unknown key or section, a value of the wrong type (an integer is taken for
// a real), an integer out of its bounds (an axis's n in [2, 1e7], sampling.samples in [100, 1e8], walk.walks in
// [100, 1e9]), a walk material its parser refuses, a walk.theta_i outside [0, 90) are refused with an input_error
// "SOURCE:LINE: key ..." naming the nearest known key or the expected type. The [[ndf]] tables are read by
// scene_ndf.hpp against the registry (a family it lacks, a parameter the family lacks); each NDF's values are checked
// by the registry, and the size of the work is estimated (work_estimate.hpp), before anything is computed.
Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry);

// The default scene, embedded at build time from experiments/scenes/g1_report.toml.
const std::string& default_scene_text();

// '*' matches any run of characters, everything else itself.
bool glob_match(const std::string& pattern, const std::string& name);

}  // namespace smithlab::report
