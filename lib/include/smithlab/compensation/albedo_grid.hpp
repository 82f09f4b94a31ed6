/// @file
/// smithlab/compensation/albedo_grid.hpp -- a table of a directional albedo over (alpha, mu) that linear interpolation
/// can follow, and the measure of how well it does.
///
/// E(mu) of a rough surface falls from its grazing limit to a dip and rises to E(1): a feature in the cosine as narrow
/// as the NDF's slopes are small, which a uniform cosine axis misses entirely at small alpha (32 cosines: 0.09 off at
/// GGX alpha 0.01). The dip lies where masking sets in, near the cosine mu_L at which Lambda(mu_L) = 0.3 (mu_L ~ 0.8
/// alpha for GGX, 0.4 alpha for Beckmann, but 0.13 at alpha 1e-4 for GTR gamma = 1, whose slopes' heavy tail masks
/// far from alpha; for alpha -> 0 a light-tailed NDF's curve is a function of mu / alpha alone), so each row's cosine
/// axis is warped by a scale c = 6 mu_L of its own (warp_scale),
///     x = sqrt((1 + c) mu / (mu + c))   in [0, 1],   mu = c x^2 / (1 + c - x^2),
/// most nodes below mu ~ c at small alpha; the root resolves the first interval, where E leaves its grazing limit with
/// an unbounded slope (without it, 48 cosines miss GGX's E by 3.8e-3 at alpha 1 there). Measured (64 x 48, alphas
/// evenly spaced in cbrt(alpha) from 1e-4 to 1, against the exact values 10x finer in both, either G2): at most
/// 5.9e-4 for GGX and GTR gamma 1, 1.5 and 3, 8.9e-4 for Beckmann (docs/compensation.md); c = alpha instead of 6 mu_L
/// missed GTR gamma 1 by 0.11 and Beckmann by 2.3e-3 (at alpha 0.5, mu 0.94: a warp too strong near mu = 1), and
/// alphas evenly spaced in sqrt(alpha) (a first cell from 1e-4 to 1e-3) missed GTR gamma <= 1.5 by 1.4e-3 there.
///
/// A kink at a cosine that does not move with alpha (a dielectric seen from inside: total internal reflection sets in
/// at mu_c = sqrt(1 - eta^2), where E_T rises like sqrt(mu - mu_c) smoothed over a width ~ alpha sin(theta_c)) takes
/// nodes of its own: a share b of the axis clustered about mu_k (NodeCluster),
///     x = (1 - b) sqrt((1 + c) mu / (mu + c)) + b (asinh((mu - mu_k) / w) + asinh(mu_k / w)) / (asinh((1 - mu_k) / w)
///         + asinh(mu_k / w)),
/// nodes a distance ~w apart near mu_k, spreading out like a logarithm beyond. Measured (height-correlated, inside
/// eta 1.1, 1.5 and 2.5, 64 x 96 from alpha 1e-4, ln(E_R + E_T) tabulated, against the exact values 10x finer in
/// both): on the warp alone GGX misses the kink by 1.7e-3 to 1.9e-3; GTR gamma 1, whose heavy tail keeps the kink as
/// narrow as alpha, missed it by 1.7e-2 at alpha < 7e-3 with w = 0.02; with b = 0.35 and w = 2 alpha_min eta
/// (compensation::dielectric_cluster) the worst error is 7.9e-4 for GGX and 8.3e-4 for GTR gamma 1
/// (docs/compensation.md).
///
/// Lookups are bilinear in (sqrt(alpha), x), x_j = j / (n_x - 1) uniform (a renderer finds the cell without a search
/// in x), x taken with the scale at the asked alpha: ln c linear in ln alpha between the nodes (exact for c ~ alpha),
/// the first interval's power continued below the first alpha, the last c above the last (lookup_power_law). A table
/// may store ln of its albedo (Stored::log): the lookup is then exp of the bilinear value, and its error relative,
/// which is what a division by the table (Turquin's, compensation/furnace.hpp) needs where the albedo is small.
///
/// Outside the alphas: below the first one, that row in the x of the asked alpha (the row the rows tend to; its error
/// there is measured, below_grid_error); above the last one, the last row in the x of the asked alpha. Nothing is
/// clamped silently: both rules are written beside every table (compensation_error.csv, the headers).
///
/// The error is measured, never assumed: the exact values on the grid refined `refine` times in both sqrt(alpha) and x
/// (the table's nodes are every refine-th point of it), against the lookup; at grazing incidence, mu < grazing_mu,
/// apart. There a dielectric seen from outside with the height-correlated G2 transmits a share that vanishes like a
/// small power of mu (GGX, alpha 0.1, eta 1.1: E_R + E_T is 0.25 at mu 1e-12, 0.39 at 1e-6, 0.52 at 1e-3), which no
/// axis of a few nodes follows: its tables miss by ~0.45 there, within 1e-3 above (measured, docs/compensation.md).
/// Mirror facets, a dielectric seen from inside and the separable G2 keep their usual error there.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "smithlab/quadrature.hpp"

namespace smithlab::compensation {

/// x = sqrt((1 + c) mu / (mu + c)) and its inverse, mu = c x^2 / (1 + c - x^2); c > 0, mu and x in [0, 1].
///@{
double warp_cosine(double c, double mu);
double unwarp_cosine(double c, double x);
///@}

/// Nodes clustered about a cosine mu_k: a share `weight` of the axis, spread as asinh((mu - mu_k) / width). The
/// default weight 0 is no cluster.
struct NodeCluster {
    double mu = 0.0;      ///< mu_k in [0, 1]
    double width = 1.0;   ///< > 0
    double weight = 0.0;  ///< b in [0, 1)
    /// The cluster's own coordinate, (asinh((mu - mu_k) / w) + asinh(mu_k / w)) / (asinh((1 - mu_k) / w) + asinh(mu_k
    /// / w)), in [0, 1].
    double coordinate(double mu) const;
    /// input_error unless mu_k in [0, 1], width finite and > 0, weight in [0, 1).
    void check() const;
};

/// Where masking sets in: cot(theta) at which Lambda = 0.3, Lambda a function of cot(theta) (Heitz 2014's mu),
/// decreasing; the NDF's slope scale (0.80 alpha for GGX, 0.41 alpha for Beckmann). By bisection in ln cot(theta) to
/// 1e-12 relative (input_error when Lambda does not cross 0.3 for cot(theta) in [1e-30, 1e30]).
double masking_cot(FunctionRef Lambda);
/// The warp's scale of an NDF whose masking_cot is `cot`: 6 mu_L, mu_L the cosine there.
double warp_scale(double cot);

/// ln v linear in ln alpha between the nodes (alphas ascending, > 0; each v > 0 and finite); below the first alpha the
/// first interval's power of alpha continued, above the last the last value. `what` names v in the messages.
double lookup_power_law(const std::vector<double>& alphas, const std::vector<double>& values, double alpha,
                        const char* what);

/// The nodes of a table over (alpha, mu): the alphas, each row's warp scale, and n_x cosines a row, uniform in the
/// warped cosine x (with a node cluster's share where the grid has one).
struct AlbedoGrid {
    std::vector<double> alphas;  ///< ascending, > 0
    std::vector<double> scales;  ///< the warp's scale c at each alpha (warp_scale of the NDF there), > 0
    int n_x = 32;                ///< cosines a row, x_j = j / (n_x - 1)
    NodeCluster cluster;         ///< none by default
    /// The j-th node of the warped axis, x_j = j / (n_x - 1).
    double x(int j) const { return static_cast<double>(j) / (n_x - 1); }
    /// The axis at scale c: x of mu (the warp, and the cluster's share), and its inverse (by bisection where a cluster
    /// is, to a few ulps).
    ///@{
    double x_of(double c, double mu) const;
    double mu_of(double c, double x) const;
    ///@}
    /// The cosine of node (i, j): mu_of at row i's scale and x_j.
    double mu(std::size_t i, int j) const { return mu_of(scales[i], x(j)); }
    /// The scale at any alpha > 0: lookup_power_law of the scales.
    double scale(double alpha) const;
    /// input_error unless >= 2 alphas, ascending, in (0, inf), one finite scale > 0 each, n_x >= 2 and a valid cluster.
    void check() const;
};

/// What a table holds at its nodes: the albedo, or its natural logarithm.
enum class Stored { value, log };

/// values[i * n_x + j] at (alphas[i], x_j): the albedo, or ln of it.
struct AlbedoTable {
    AlbedoGrid grid;                ///< the nodes
    std::vector<double> values;     ///< n_alpha x n_x, row-major (row i = alphas[i])
    Stored stored = Stored::value;  ///< whether values are the albedo or its natural logarithm
    /// The stored value at node (i, j), as held (ln of the albedo for Stored::log).
    double at(std::size_t i, int j) const { return values[i * static_cast<std::size_t>(grid.n_x) + j]; }
    /// Bilinear in (sqrt(alpha), x) (exp of it for Stored::log), with the rules above outside the alphas; input_error
    /// for alpha <= 0 or NaN, or mu outside [0, 1].
    double lookup(double alpha, double mu) const;
};

/// Grazing incidence: mu below it, theta above 89.885 degrees.
inline constexpr double grazing_mu = 2e-3;

/// The worst |lookup - exact| and where it is.
struct InterpolationError {
    /// The worst |lookup - exact|, and the alpha and mu where it is.
    ///@{
    double max = 0.0, alpha = 0.0, mu = 0.0;
    ///@}
};

/// A table with its measured error: `fine` holds the exact values on the refined grid (alphas at refine steps of
/// sqrt(alpha) between nodes, x at steps of 1 / (refine (n_x - 1))), `table` every refine-th of them (or their logs).
struct CheckedTable {
    /// The table a renderer looks up, and the exact values on the refined grid it is measured against.
    ///@{
    AlbedoTable table, fine;
    ///@}
    InterpolationError error;    ///< at mu >= grazing_mu
    InterpolationError grazing;  ///< at mu < grazing_mu
};

/// A row maker: for one alpha, the exact albedo as a function of mu (built once per alpha: an NDF's Lambda table,
/// say). Called from several threads at once, one alpha each.
using AlbedoRow = std::function<std::function<double(double)>(double alpha)>;

/// Tabulates row(alpha)(mu) on the refined grid with `threads` threads (0: the hardware's), and measures the table.
CheckedTable tabulate(const AlbedoGrid& grid, int refine, const AlbedoRow& row, unsigned threads = 0);

/// Several albedos from one evaluation (a dielectric's E_R, E_T and their sum): for one alpha, a function writing one
/// value per entry of `stored` at mu into out[0 ..). Returns one measured table per value, each stored as asked (a
/// value tabulated as Stored::log must be > 0).
using AlbedoRows = std::function<std::function<void(double mu, double* out)>(double alpha)>;
/// Tabulates rows(alpha) on the refined grid with `threads` threads (0: the hardware's), one measured table per entry
/// of `stored`, each stored as that entry asks.
std::vector<CheckedTable> tabulate(const AlbedoGrid& grid, int refine, const std::vector<Stored>& stored,
                                   const AlbedoRows& rows, unsigned threads = 0);

/// The missing energy m = 1 - E_avg over alpha (each > 0) by lookup_power_law. 1 - E_avg falls as a power of
/// alpha at small alpha (~alpha^2: E is a function of mu / alpha there), which linear interpolation in sqrt(alpha)
/// misses between the first nodes by a factor 7 (GGX, 32 nodes from 1e-4 to 1, measured against the exact values 10x
/// finer in sqrt(alpha)); in logs it stays within 1.5 % there. Kulla and Conty's lobe, divided by m, needs m to a
/// relative accuracy, which 1 - E_avg as a float cannot keep: floats below 1 are 6e-8 apart (60 % of GGX's m at
/// alpha 1e-4, 9.7e-8), and 1 - m rounds to 1 below m = 3e-8.
double lookup_missing(const std::vector<double>& alphas, const std::vector<double>& missing, double alpha);

/// Below the grid: the worst |lookup - exact| at alpha = alphas.front() times each of `factors` (< 1), over the
/// table's refined cosines at mu >= grazing_mu.
InterpolationError below_grid_error(const CheckedTable& t, const AlbedoRow& row, const std::vector<double>& factors,
                                    unsigned threads = 0);

}  // namespace smithlab::compensation
