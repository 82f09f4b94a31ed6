// The report's walk section: the albedo of the Smith microsurface by scattering order (1, 2, 3, 4+) against alpha,
// path-traced (smithlab/walk/trace.hpp: Heitz, Hanika, d'Eon and Dachsbacher 2016, "Multiple-Scattering Microfacet
// BSDFs with the Smith Model", alg. 1-3) for each NDF x facet material x alpha x theta_i of the scene's [walk], and
// the energy single scattering loses: the albedo of orders 2 and up, which is 1 - (order 1) where the facets absorb
// nothing (mirror, lambert(albedo=1)), what a multiple-scattering model must restore (Heitz et al. 2016, fig. 1).
// Writes walk_albedo.csv, a section of report.md, and the data of walk_albedo.png (report_plots.py). The section
// that runs it: sections/walk.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene_ndf.hpp"
#include "smithlab/any_ndf.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/tally.hpp"

namespace smithlab::report {

// The scene's [walk]: absent (ndfs empty) unless named.
struct WalkScene {
    std::vector<scene::NdfEntry> ndfs;
    std::vector<std::string> materials = {"mirror", "lambert(albedo=1)"};  // facet specs (walk/facets.hpp)
    std::vector<double> alphas;
    std::vector<double> theta_i = {45.0};  // degrees, in [0, 90)
    std::int64_t walks = 20000;            // per cell
    unsigned long long seed = 1;
};

// One cell of the sweep, checked: NDFs (each [[walk.ndf]]'s points x alpha) outermost, then materials, then theta_i;
// its place in that order keys its random stream (walk::WalkRng(seed, index, walk)).
struct WalkCell {
    std::uint64_t index;
    std::string family;
    scene::ParamPoint params;  // the NDF's parameters but alpha (and but the one alpha sets, when swept over alpha)
    double alpha;              // NaN for an NDF without one, not swept over alpha
    AnyNdf ndf;
    walk::Material material;
    double theta_i;     // degrees
    std::string where;  // "FILE:LINE: walk.ndf.family": its [[walk.ndf]] entry, for refusals
};

// What the section reports per cell, in this order: orders 1, 2, 3, 4+; 2+ (what single scattering loses); all.
inline constexpr std::array<const char*, 6> walk_orders = {"1", "2", "3", "4+", "2+", "all"};

struct WalkResult {
    WalkCell cell;
    std::array<walk::Estimate, walk_orders.size()> albedo;  // leaving in either hemisphere, of the incident energy
    std::int64_t events = 0, capped = 0;
};

// The cells of `walk`, every NDF through the registry's parser and its microsurface built once (a D-only NDF's
// table may refuse it): an input_error "FILE:LINE: walk.ndf.family ..." naming the NDF. Nothing is traced.
std::vector<WalkCell> walk_cells(const WalkScene& walk, const NdfRegistry& ndfs);

// Traces every cell (walk.walks walks each, on all cores; the same bits for any number of threads), under MPI on
// every rank (cluster/block_jobs.hpp): rank 0 gets the results, the other ranks none. Rank 0 says on stderr which
// cells had walks cut short, and refuses (input_error naming the cell's [[walk.ndf]] entry) a cell whose capped walks
// could carry more than its albedo's standard error (trace/capped_walks.hpp).
std::vector<WalkResult> trace_walk_cells(const std::vector<WalkCell>& cells, const WalkScene& walk);

// DIR/walk_albedo.csv (ndf,family,gamma,alpha,material,theta_i,order,albedo,stderr,walks,label, then one column per
// other parameter of the NDFs (abc: b, c); order as walk_orders, label the NDF without the roughness it is swept
// over: "gtr (gamma 1.5)", "abc (c 3)", what the plot's panels show)
// and the section appended to DIR/report.md: its table, and the figure report_plots.py draws from the CSV.
void write_walk_section(const std::vector<WalkResult>& results, const WalkScene& walk, double seconds,
                        const std::filesystem::path& dir);

}  // namespace smithlab::report
