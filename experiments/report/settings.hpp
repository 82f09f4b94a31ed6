// The report scene's settings, read before its sections (section.hpp) and shared by them: the title, the grid of
// the G1 and G2 tables ([grid]), the timing ([timing]) and the figures to draw ([figures]).
// experiments/scenes/g1_report.toml documents every key.
#pragma once

#include <string>
#include <vector>

namespace smithlab::report {

struct Settings {
    std::string title;
    std::vector<double> alphas, mus;  // [grid]
    double min_time = 0.05;           // seconds of Google Benchmark per timed item, times the scale
    double scale = 1.0;               // --scale (scene/limits.hpp): the walks and samples a section reads times it
    struct Figures {
        bool pareto = false;              // error against ns/eval, log-log, every variant
        bool error_maps = false;          // |dG1| over (alpha, mu), worst over gamma, one map per variant
        bool dimov_heightfields = false;  // Dimov 2015 sec. 4: G1 for gamma = 0..4, alpha in (0.1, 0.5), mu in (0, 5)
        bool dimov_spline_mean = false;   // Dimov 2015 sec. 5: the spline's mean |dG1| (published: about 0.001)
        bool dimov_gamma4_vs_10 =
            false;  // Dimov 2015 sec. 6: |G1(gamma=4) - G1(gamma=10)|, alpha in (0,1), mu in (0,2)
    } figures;
};

}  // namespace smithlab::report
