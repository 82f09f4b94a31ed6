// The [compensation] table of a scene (fit's, where it is optional, and tables', where it is the scene): what the
// energy-compensation stage tabulates and measures (compensation/stage.hpp), read strictly (scene/strict_table.hpp).
// experiments/scenes/tables_default.toml documents every key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/alpha_family.hpp"
#include "scene/limits.hpp"
#include "scene/strict_table.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::compensation {

struct Settings {
    bool enabled = false;                          // the scene has [compensation]
    std::vector<double> alpha = default_alphas();  // the tables' alphas, ascending
    std::int64_t cosines = 48;                     // warped cosines a row of E (compensation/albedo_grid.hpp)
    std::int64_t dielectric_cosines = 96;          // a row of the dielectric tables
    std::int64_t refine = 10;                      // the check grid: refine x finer in sqrt(alpha) and the cosine
    std::vector<G2Form> g2{G2Form::height_correlated, G2Form::uncorrelated};
    std::vector<double> eta;              // dielectric tables, each eta from outside and from inside
    std::vector<std::string> conductors;  // conductor facets of the furnace (walk/facets.hpp specs)
    std::vector<double> furnace_alpha{0.01, 0.1, 0.3, 0.6, 1.0};
    std::vector<double> furnace_theta{0.0, 30.0, 60.0, 75.0, 85.0};
    std::int64_t furnace_walks = 200000;
    // The walk's scattering orders of mirror facets for conductors (compensation/scattering_orders.hpp): mirror walks
    // a node (0: none), over order_alpha x order_cosines warped cosines.
    std::int64_t order_walks = 0;
    std::vector<double> order_alpha = default_order_alphas();
    std::int64_t order_cosines = 16;
    // 16 alphas evenly spaced in cbrt(alpha) from 0.01 to 1 (below, the first row's: GGX's 1 - E_avg < 5e-4).
    static std::vector<double> default_order_alphas();
    // 64 alphas evenly spaced in cbrt(alpha) from 1e-4 to 1.
    static std::vector<double> default_alphas();
};

// The scene's [compensation] table, each count scaled by limits.scale; absent: the defaults, enabled false. Refuses
// (input_error "SOURCE:LINE: compensation.KEY ...") an unknown key, alphas that are not two or more ascending values in
// (0, 1] or at which a family cannot be made, a g2 other than height-correlated or separable, an eta outside [1.01,
// 100], a conductor that is not conductor(eta=, k=) facets, a list naming one thing twice, an integer out of its
// bounds; and tables (each value of E counted as the walks of its time, settings.cpp) and walks (the furnace's, the
// scattering orders' and other_walks, the rest of the run's) that pass limits.max_walks.
Settings read_settings(scene::StrictTable& doc, const std::vector<scene::AlphaFamily>& families, double other_walks,
                       const NdfRegistry& registry, const scene::SizeLimits& limits);

}  // namespace smithlab::compensation
