// The energy-compensation tables of a fit scene's [compensation] for each NDF family and G2 form (no tracing but the
// furnace's cells: quadrature of the single-scattering albedos, smithlab/fit/compensation.hpp, on the warped grid of
// fit/albedo_grid.hpp, each table measured on its check grid): mirror facets' E and E_avg, and for each eta a
// dielectric's E_R, E_T and their sum from outside and from inside; with order_walks, the walk's scattering orders
// of mirror facets for conductors (fit/scattering_orders.hpp). Written as compensation.csv, compensation_avg.csv,
// compensation_dielectric.csv, compensation_orders.csv, compensation_error.csv (each table's worst interpolation error,
// below-grid error and furnace error, and where), furnace_tables.csv (the furnace by the tables per alpha of the check
// grid), furnace.csv (fit_furnace.hpp: against the walk), and compensation/ (fit/compensation_formats.hpp: a C header,
// GLSL, HLSL, a 16-bit PNG and its axes per table; a C header, GLSL, HLSL and JSON of the scattering orders per family
// and G2 form).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fit/fit_scene.hpp"
#include "smithlab/fit/albedo_grid.hpp"
#include "smithlab/fit/compensation.hpp"
#include "smithlab/fit/scattering_orders.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fitrun {

// The furnace's least cosine: theta_i up to 85 degrees.
inline constexpr double furnace_theta_max = 85.0;

// One table over (alpha, x) with what was measured of it.
struct MeasuredTable {
    std::string name;  // "E", or "E_R+E_T eta=1.5 outside"
    fit::CheckedTable table;
    fit::InterpolationError below;                 // below the first alpha
    std::vector<fit::InterpolationError> furnace;  // |compensated - 1| per alpha of the check grid (fit/furnace.hpp)
};

// A dielectric of relative index eta seen from one side: E_R and E_T, and the table of their sum.
struct DielectricTables {
    double eta = 1.5;  // the scene's eta (index inside over outside)
    bool inside = false;
    fit::CheckedTable R, T;
    MeasuredTable sum;
    double relative_eta() const { return inside ? 1.0 / eta : eta; }  // below over above, as the walk's facets
    // A table's name: "E_R+E_T eta=1.5 inside" for what = "E_R+E_T".
    std::string name(const std::string& what) const;
};

// One NDF family and G2 form.
struct FamilyTables {
    const FitFamily* family = nullptr;
    G2Form g2 = G2Form::height_correlated;
    MeasuredTable E;
    std::vector<double> exact_missing;  // 1 - E_avg at E's alphas, each by its own quadrature (of 1 - E)
    std::vector<double> missing;        // the table's own 1 - E_avg there (fit::table_missing): the formats'
    std::vector<DielectricTables> dielectrics;
    // The walk's scattering orders of mirror facets (fit/scattering_orders.hpp): one walk per family, whatever G2 a
    // renderer computes, with the separable G2's q_1 beside it; null without order_walks.
    std::shared_ptr<const fit::OrderTables> orders;
};

// "height-correlated" or "separable".
std::string g2_name(G2Form form);
// The albedo options of every table: tolerance fit::table_tolerance (smithlab/fit/compensation.hpp).
fit::AlbedoOptions table_options(G2Form form);

// Writes the files into dir and returns report.md's section; "" without [compensation].
std::string write_compensation(const std::filesystem::path& dir, const std::vector<FitFamily>& families,
                               const FitScene::Compensation& compensation, const NdfRegistry& registry,
                               std::uint64_t seed, unsigned threads);

}  // namespace smithlab::fitrun
