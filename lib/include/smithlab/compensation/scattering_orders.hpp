/// @file
/// smithlab/compensation/scattering_orders.hpp -- the compensation of conductor facets from the walk's scattering
/// orders.
///
/// Light that leaves a microsurface of conductor facets after k hits keeps the product of the k facets' Fresnel
/// reflectances. Single scattering (k = 1) is E_F(mu), exact by quadrature (compensation.hpp). For mirror facets the
/// rest, 1 - E(mu), leaves after k >= 2 hits; a fraction q_k(mu) of it after exactly k. With every further hit's
/// reflectance taken as F_avg = 2 integral_0^1 F(mu) mu dmu,
///     A_ms(mu) = (1 - E(mu)) sum_{k >= 2} q_k(mu) F_avg^k.
/// Kulla and Conty 2017 (compensation.hpp, fresnel_ms) give every bounce the same escape chance E_avg, q_k = E_avg
/// (1 - E_avg)^(k - 2), for every mu. The walk's light escapes more easily at each bounce (GGX, alpha 1, normal
/// incidence: 0.41, 0.55, 0.63, 0.69, 0.73 for hits 1 to 5), so their series holds too many bounces and comes out low.
/// Here q_2 and q_3 are the walk's own (Heitz et al. 2016's random walk of mirror facets, walk/walk.hpp), per alpha and
/// mu, and the orders k >= 4 a geometric series of the walk's own mean length: q_k = q_4+ p (1 - p)^(k - 4), with
/// 1 / p the mean number of hits past the third, so that
///     sum_{k >= 4} q_k F^k = q_4+ F^4 p / (1 - F (1 - p)),  q_4+ = 1 - q_2 - q_3.
/// The walk's single scattering is the height-correlated G2's (Heitz 2014). A renderer whose single scattering uses the
/// separable G2 = G1 G1 misses E_hc - E_sep of light that leaves after one hit as well: its share of 1 - E_sep, q_1 =
/// (E_hc - E_sep) / (1 - E_sep), keeps one factor F_avg and the rest is shared as above:
///     A_ms(mu) = (1 - E(mu)) (q_1 F_avg + (1 - q_1) sum_{k >= 2} q_k F_avg^k),  q_1 = 0 for the height-correlated G2.
/// At F_avg = 1 the sum is 1 - E(mu): a white furnace whatever the walk's noise. Measured against the walk of conductor
/// facets (GGX, gold, copper, iron, aluminium and conductor(eta 0.2, k 3), docs/compensation.md): within 4e-3 at
/// alpha 1, where Kulla and Conty's form misses by 0.044. At small alpha the further hits meet facets near grazing,
/// where F exceeds F_avg, and the form comes out low like theirs (2.4e-2 at alpha 0.1, 85 degrees).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "smithlab/compensation/albedo_grid.hpp"
#include "smithlab/walk/tally.hpp"

namespace smithlab::compensation {

/// The shares of the light single scattering misses by order: q_1 (the separable G2's), then of the rest q_2, q_3,
/// and p, the escape chance of each hit past the third.
struct ScatteringOrders {
    /// q_2 and q_3, the shares of the light that leaves after exactly 2 and 3 hits; p, the escape chance of each hit
    /// past the third; q_1, the separable G2's share (0 for the height-correlated one).
    ///@{
    double q2 = 1.0, q3 = 0.0, p = 1.0, q1 = 0.0;
    ///@}
};

/// The orders of one cell of mirror-facet walks (walk/trace.hpp, walk::Mirror; every walk leaves with weight 1), with
/// the standard errors of q_2 and q_3 (multinomial, over the walks that hit twice or more). Where none hit twice (alpha
/// -> 0 at normal incidence, 1 - E ~ 0), all of it is order 2. input_error for a tally of no walks, capped walks, or
/// walks that did not all leave with weight 1 (not mirror facets).
struct OrderEstimate {
    ScatteringOrders orders;  ///< q_2, q_3 and p of the cell (q_1 = 0: the walk's G2 is the height-correlated one)
    /// The standard errors of q_2 and q_3 (multinomial, over the walks that hit twice or more).
    ///@{
    double q2_stderr = 0.0, q3_stderr = 0.0;
    ///@}
    std::int64_t multiple = 0;  ///< walks that hit twice or more
};
/// The orders of the mirror-facet walks tallied in `mirror`, with their standard errors (OrderEstimate's rules).
OrderEstimate scattering_orders(const walk::AlbedoTally& mirror);

/// A_ms = (1 - E) (q_1 F + (1 - q_1) (F^2 q_2 + F^3 q_3 + (1 - q_2 - q_3) F^4 p / (1 - F (1 - p)))), F = F_avg in
/// [0, 1], E = E(mu) of mirror facets in [0, 1] (a rounding above 1 reads as 1) with the G2 that q_1 belongs to.
double multiple_scattering_albedo(double E, const ScatteringOrders& q, double F_avg);

/// q_2, q_3 and p over (alpha, mu): tables on one grid (albedo_grid.hpp), looked up bilinearly (below the first alpha,
/// its row); q_1 a table on the same grid for the separable G2, none (0) for the height-correlated one.
struct OrderTables {
    /// The tables of q_2, q_3, p and q_1 (q_1 without values: none, 0), stored as values on one grid.
    ///@{
    AlbedoTable q2, q3, p, q1;
    ///@}
    /// The standard errors of q_2 and q_3 at each node, as the tables' values.
    ///@{
    std::vector<double> q2_stderr, q3_stderr;
    ///@}
    /// The orders at (alpha, mu): each table's AlbedoTable::lookup, q_1 = 0 where its table has no values.
    ScatteringOrders lookup(double alpha, double mu) const;
};

/// The tables on `grid` from trace(node, alpha, mu), a cell of mirror-facet walks from mu at alpha, node = i n_x + j
/// the node's index (for its random stream); a node at mu < grazing_mu (albedo_grid.hpp) is traced from grazing_mu, as
/// a walk cannot start horizontal. The nodes run on `threads` threads (0: all cores), each node's walks in the thread
/// that runs it.
using OrderCell = std::function<walk::AlbedoTally(std::size_t node, double alpha, double mu)>;
/// Traces every node of `grid` with `trace` on `threads` threads (0: all cores) and returns q_2, q_3 and p with their
/// standard errors (q_1 left empty: the walk's G2 is the height-correlated one).
OrderTables tabulate_orders(const AlbedoGrid& grid, const OrderCell& trace, unsigned threads = 0);

}  // namespace smithlab::compensation
