// The energy-compensation tables of a [compensation] table (compensation/settings.hpp) for each NDF family and G2
// form (no tracing but the scattering orders': quadrature of the single-scattering albedos,
// smithlab/compensation/compensation.hpp, on the warped grid of compensation/albedo_grid.hpp, each table measured on
// its check grid): mirror facets' E and E_avg, and for each eta a dielectric's E_R, E_T and their sum from outside and
// from inside; with order_walks, the walk's scattering orders of mirror facets for conductors
// (compensation/scattering_orders.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "scene/alpha_family.hpp"
#include "smithlab/compensation/albedo_grid.hpp"
#include "smithlab/compensation/compensation.hpp"
#include "smithlab/compensation/scattering_orders.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::compensation {

// How the stage runs: `command` names it on stderr ("fit", "tables"), `seed` keys its walks' random streams, on
// `threads` threads (0: all cores).
struct StageRun {
    std::string command;
    std::uint64_t seed = 1;
    unsigned threads = 0;
};

// The furnace's least cosine: theta_i up to 85 degrees.
inline constexpr double furnace_theta_max = 85.0;

// One table over (alpha, x) with what was measured of it.
struct MeasuredTable {
    std::string name;  // "E", or "E_R+E_T eta=1.5 outside"
    compensation::CheckedTable table;
    compensation::InterpolationError below;                 // below the first alpha
    std::vector<compensation::InterpolationError> furnace;  // |compensated - 1| per alpha of the check grid
};

// A dielectric of relative index eta seen from one side: E_R and E_T, and the table of their sum.
struct DielectricTables {
    double eta = 1.5;  // the scene's eta (index inside over outside)
    bool inside = false;
    compensation::CheckedTable R, T;
    MeasuredTable sum;
    double relative_eta() const { return inside ? 1.0 / eta : eta; }  // below over above, as the walk's facets
    // A table's name: "E_R+E_T eta=1.5 inside" for what = "E_R+E_T".
    std::string name(const std::string& what) const;
};

// One NDF family and G2 form.
struct FamilyTables {
    const scene::AlphaFamily* family = nullptr;
    G2Form g2 = G2Form::height_correlated;
    MeasuredTable E;
    std::vector<double> exact_missing;  // 1 - E_avg at E's alphas, each by its own quadrature (of 1 - E)
    std::vector<double> missing;        // the table's own 1 - E_avg there (compensation::table_missing): the formats'
    std::vector<DielectricTables> dielectrics;
    // The walk's scattering orders of mirror facets (compensation/scattering_orders.hpp): one walk per family,
    // whatever G2 a renderer computes, with the separable G2's q_1 beside it; null without order_walks.
    std::shared_ptr<const compensation::OrderTables> orders;
};

// "height-correlated" or "separable".
std::string g2_name(G2Form form);
// The albedo options of every table: tolerance compensation::table_tolerance (smithlab/compensation/compensation.hpp).
compensation::AlbedoOptions table_options(G2Form form);

// The tables of every family, each family's G2 forms in the settings' order, saying on stderr what each one is and how
// far it has come.
std::vector<FamilyTables> make_tables(const std::vector<scene::AlphaFamily>& families, const Settings& c,
                                      const NdfRegistry& registry, const StageRun& run);

// Every measured table of a family and G2 form: E, then each dielectric's sum.
template <class F>
void for_each_table(const FamilyTables& t, const F& f) {
    f(t.E);
    for (const DielectricTables& d : t.dielectrics) f(d.sum);
}

// Each dielectric side's E_R and E_T alone (compensation_dielectric.csv's columns, on the sum's axis), with its name.
template <class F>
void for_each_alone(const FamilyTables& t, const F& f) {
    for (const DielectricTables& d : t.dielectrics) {
        f(d.name("E_R"), d.R);
        f(d.name("E_T"), d.T);
    }
}

}  // namespace smithlab::compensation
