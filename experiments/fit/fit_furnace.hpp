// The white furnace of the compensation tables against the walk (walk/trace.hpp): at each furnace alpha and theta_i,
// the total albedo the Smith microsurface's random walk scatters (every order) beside the albedo a renderer gets from
// the tables: single scattering exact plus Kulla and Conty's lobe from the tables (mirror facets and each conductor,
// the lobe times F_ms), a dielectric's single scattering divided by the table of E_R + E_T (Turquin 2019), its
// reflected and transmitted parts too.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fit/fit_compensation.hpp"

namespace smithlab::fitrun {

struct FurnaceRow {
    std::string ndf, g2, material, part;  // part: "total", "R" or "T"
    double alpha = 0.0, theta = 0.0, compensated = 0.0, traced = 0.0, traced_stderr = 0.0;
};

// One cell of furnace_walks walks per family, furnace alpha, theta and material; each G2 form's tables read against
// it. Cell k's walks draw from (seed, k).
std::vector<FurnaceRow> trace_furnace(const std::vector<FamilyTables>& tables, const FitScene::Compensation& c,
                                      const NdfRegistry& registry, std::uint64_t seed, unsigned threads);

}  // namespace smithlab::fitrun
