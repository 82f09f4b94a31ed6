// The white furnace of the compensation tables against the walk (walk/trace.hpp): at each furnace alpha and theta_i,
// the total albedo the Smith microsurface's random walk scatters (every order) beside the albedo a renderer gets from
// the tables, E looked up, single scattering (E_F, E_R, E_T) exact:
//   mirror facets: E + Kulla and Conty's lobe (form "kulla-conty");
//   each conductor, three published forms and the walk's own orders:
//     "kulla-conty": E_F + F_ms times their lobe (Kulla and Conty 2017, compensation.hpp);
//     "turquin":     E_F (1 + F0 (1 - E) / E), F0 = F(1) (Turquin 2019);
//     "fdez-aguera": E_F / (1 - F_avg (1 - E)) (Fdez-Aguera 2019, compensation::fdez_aguera_albedo; F_avg the exact
//                    2 int F mu dmu, not its Schlick fit);
//     "walk-orders": E_F + (1 - E) sum_k q_k F_avg^k, the walk's scattering orders of mirror facets
//                    (compensation/scattering_orders.hpp), with order_walks;
//   a dielectric: its single scattering divided by the table of E_R + E_T (form "turquin", Turquin 2019), the total
//   and its reflected and transmitted parts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compensation/settings.hpp"
#include "compensation/tables.hpp"

namespace smithlab::compensation {

struct FurnaceRow {
    std::string ndf, g2, material, part;  // part: "total", "R" or "T"
    std::string form;                     // "kulla-conty", "turquin", "fdez-aguera" or "walk-orders"
    double alpha = 0.0, theta = 0.0, compensated = 0.0, traced = 0.0, traced_stderr = 0.0;
};

// One cell of furnace_walks walks per family, furnace alpha, theta and material; each G2 form's tables read against
// it. Cell k's walks draw from (run.seed, k).
std::vector<FurnaceRow> trace_furnace(const std::vector<FamilyTables>& tables, const Settings& c,
                                      const NdfRegistry& registry, const StageRun& run);

}  // namespace smithlab::compensation
