/// @file
/// smithlab/detail/fixed_rule.hpp -- the machinery of the fixed Gauss-Kronrod rule of lambda_fixed.hpp (whose
/// comment derives it): the precomputed nodes and pieces, their sums, and the bisection of the worst piece.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"

namespace smithlab::detail {

double tan_minus_x(double t, double tan_t);  ///< smith.cpp

namespace fixed_rule {

inline constexpr int nodes = 31;            ///< Gauss-Kronrod 15-31
inline constexpr double panel_width = 2.0;  ///< in u
inline constexpr int max_panels = 32;       ///< u up to 64: mu down to ~1e-27 max(r0, 1)
inline constexpr int max_pieces = 64;       ///< the bisection's limits before the adaptive route takes over:
inline constexpr int max_untabled = 4;      ///< pieces, and bisections below the trees' depth (each ~5 us)
/// Each fixed piece comes with its bisections to depth 3, precomputed: a tree in heap order, tree[1] the piece,
/// tree[2i] and tree[2i + 1] the halves of tree[i]. Deeper halves get their nodes computed on the fly (~80 ns a node
/// against ~0 from the table: sinh, cosh, atan).
inline constexpr int tree_size = 16;

/// One piece of the integral on fixed nodes: r_k^2 = mu^2 S[k]; the piece is sum_k W[k] r_k^2 f(r_k^2) (Kronrod) and
/// sum_k V[k] r_k^2 f(r_k^2) (Gauss, V = 0 on the Kronrod-only nodes); W and V include the node's H and the
/// piece's half-width.
struct Piece {
    /// The nodes' r^2 / mu^2, and their Kronrod and Gauss weights.
    /// @{
    std::array<double, nodes> S, W, V;
    /// @}
};

/// A fixed piece with its bisections to depth 3, in heap order (tree[1] the piece).
using Tree = std::array<Piece, tree_size>;

/// The precomputed trees of the fixed pieces: the panels u in [2j, 2j + 2], and the tails beyond each.
struct Tables {
    std::array<Tree, max_panels> panel;         ///< [1]: u in [2j, 2j + 2]
    std::array<Tree, max_panels + 1> tail;      ///< [1]: u >= 2J, in s from atan(1 / sinh(2J)) down to 0
    std::array<double, max_panels + 1> s_edge;  ///< s at u = 2J
};

/// Built once, at the first call (a function-local static: thread-safe, C++11 [stmt.dcl]/4): ~2 ms, 0.8 MB.
const Tables& tables();

/// The Gauss-Kronrod 10-21 nodes on [-1, 1] (all 21), Kronrod weights and Gauss weights (0 on Kronrod-only nodes).
struct Rule {
    /// The nodes, the Kronrod weights and the Gauss weights.
    /// @{
    std::array<double, nodes> x, wk, wg;
    /// @}
};
/// The rule, built once.
const Rule& rule();

/// H for a node given in u, or in s (the tail): the integrand's geometric factor times its Jacobian, and r^2/mu^2.
struct Geometry {
    /// r^2 / mu^2 at the node, and H.
    /// @{
    double S, H;
    /// @}
};
/// The node at u (the panels): S = cosh^2 u, sinh and cosh from one expm1.
inline Geometry at_u(double u) {
    // sinh and cosh from one expm1: sinh u = m (m + 2) / (2 (m + 1)), m = e^u - 1, exact as u -> 0.
    const double m = std::expm1(u), sh = m * (m + 2.0) / (2.0 * (m + 1.0)), ch = sh + 1.0 / (m + 1.0);
    return {ch * ch, sh * detail::tan_minus_x(std::atan(sh), sh) / ch};
}
/// The node at s = pi/2 - t (the tails): S = 1 / sin^2 s.
inline Geometry at_s(double s) {
    // t = pi/2 - s: sec^2 t = 1/sin^2 s, tan t = cos s / sin s; the t-form's sec^2 t carries r^2 = mu^2 sec^2 t.
    const double sn = std::sin(s), tn = std::cos(s) / sn;
    return {1.0 / (sn * sn), tn * detail::tan_minus_x(std::numbers::pi / 2 - s, tn)};
}

/// The result of one piece: Kronrod value, QUADPACK error estimate.
struct PieceResult {
    /// The Kronrod value, and QUADPACK's error estimate.
    /// @{
    double K, E;
    /// @}
};

/// QUADPACK QK21's error estimate from the Kronrod and Gauss sums, resabs = sum w|g| and resasc = sum w|g - K/len|.
inline double quadpack_error(double K, double G, double resabs, double resasc) {
    constexpr double eps = 2.220446049250313e-16;
    double e = std::abs(K - G);
    if (resasc != 0.0 && e != 0.0) e = resasc * std::fmin(1.0, std::pow(200.0 * e / resasc, 1.5));
    return std::fmax(e, 50.0 * eps * resabs);
}

/// A piece from its 21 integrand values g_k = r_k^2 f(r_k^2), the Kronrod and Gauss weights (with H and the
/// half-width) and the half-width h.
inline PieceResult combine(const std::array<double, nodes>& g, const std::array<double, nodes>& W,
                           const std::array<double, nodes>& V, double h) {
    double K = 0.0, G = 0.0, resabs = 0.0;
    for (int k = 0; k < nodes; ++k) {
        K += W[k] * g[k];
        G += V[k] * g[k];
        resabs += W[k] * std::abs(g[k]);
    }
    // QUADPACK's resasc: integral of |F - mean F| by the Kronrod rule, F = W g / wk the integrand itself.
    const Rule& R = rule();
    const double mean = K / (2.0 * h);
    double resasc = 0.0;
    for (int k = 0; k < nodes; ++k) resasc += std::abs(W[k] * g[k] - R.wk[k] * h * mean);
    return {K, quadpack_error(K, G, resabs, resasc)};
}

/// A piece of `ndf`'s integral at mu^2 = mu2 on the piece's precomputed nodes, of half-width h: its g_k = r_k^2
/// P22(r_k^2) combined.
template <Ndf N>
PieceResult eval_piece(const N& ndf, double mu2, const Piece& p, double h) {
    std::array<double, nodes> g;
    for (int k = 0; k < nodes; ++k) {
        const double r2 = mu2 * p.S[k];
        const double f = slope_density(ndf, r2);
        g[k] = f == 0.0 ? 0.0 : f * r2;
    }
    return combine(g, p.W, p.V, h);
}

/// A piece [a, b] of u (in_s false) or of s (in_s true), nodes computed here (the bisection).
template <Ndf N>
PieceResult eval_interval(const N& ndf, double mu2, double a, double b, bool in_s) {
    const Rule& R = rule();
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    std::array<double, nodes> g, W, V;
    for (int k = 0; k < nodes; ++k) {
        const double x = c + h * R.x[k];
        const Geometry geo = in_s ? at_s(x) : at_u(x);
        const double r2 = mu2 * geo.S;
        const double f = r2 < INFINITY ? slope_density(ndf, r2) : 0.0;
        g[k] = f == 0.0 ? 0.0 : f * r2;
        W[k] = R.wk[k] * h * geo.H;
        V[k] = R.wg[k] * h * geo.H;
    }
    return combine(g, W, V, h);
}

/// A piece the rule holds: [a, b] in u (in s for the tail), its Kronrod value and error estimate, and its nodes.
struct OpenPiece {
    double a;          ///< the lower end, in u (in s where in_s)
    double b;          ///< the upper end
    double K;          ///< the Kronrod value
    double E;          ///< QUADPACK's error estimate
    bool in_s;         ///< a piece of the tail
    const Tree* tree;  ///< the piece is (*tree)[node] while node < tree_size
    int node;          ///< its place in the tree (tree_size below the tree's depth)
};

/// The pieces the rule holds, and the sums of their values and of their estimates.
struct OpenPieces {
    std::array<OpenPiece, max_pieces> piece;  ///< the first n are held
    int n = 0;                                ///< how many are held
    double K = 0.0;                           ///< the sum of their values
    double E = 0.0;                           ///< the sum of their estimates
};

/// The first pieces, on the tables' nodes: J panels of u and the tail.
template <Ndf N>
void start_pieces(const N& ndf, const Tables& T, double mu2, int J, OpenPieces& p) {
    const double h_u = 0.5 * panel_width;
    for (int j = 0; j < J; ++j) {
        const PieceResult r = eval_piece(ndf, mu2, T.panel[j][1], h_u);
        p.piece[p.n++] = {j * panel_width, (j + 1) * panel_width, r.K, r.E, false, &T.panel[j], 1};
        p.K += r.K;
        p.E += r.E;
    }
    const PieceResult r = eval_piece(ndf, mu2, T.tail[J][1], 0.5 * T.s_edge[J]);
    p.piece[p.n++] = {0.0, T.s_edge[J], r.K, r.E, true, &T.tail[J], 1};
    p.K += r.K;
    p.E += r.E;
}

/// Halves the piece of the largest estimate and re-sums; false, with nothing halved, where the adaptive route is
/// to answer instead. untabled counts the bisections below the trees' depth.
template <Ndf N>
bool bisect_worst(const N& ndf, double mu2, OpenPieces& p, int& untabled) {
    int worst = 0;
    for (int i = 1; i < p.n; ++i)
        if (p.piece[i].E > p.piece[worst].E) worst = i;
    const OpenPiece q = p.piece[worst];
    const double m = 0.5 * (q.a + q.b);
    // Below the tree's depth, node stays at tree_size (a piece bisected 60 times would overflow 2^node).
    const bool tabled = q.node < tree_size / 2;
    // A piece that needs halving below the tree's depth has a feature narrower than 1/16 of it: an end point
    // singularity (Blinn n -> 0: s^n), a lobe far narrower than its panel (Beckmann at mu/alpha >~ 20). Bisection
    // converges there only linearly; the adaptive route's double-exponential rule does better.
    // At the tail's end point s = 0 such a feature is the power tail itself (s^(k - 4) for f ~ r^-k): no depth
    // of bisection gains more than a constant factor there, so the adaptive route answers at once.
    if (!tabled && (++untabled > max_untabled || (q.in_s && q.a == 0.0))) return false;
    const int child = tabled ? 2 * q.node : tree_size;
    const double h = 0.5 * (m - q.a);
    const PieceResult left =
        tabled ? eval_piece(ndf, mu2, (*q.tree)[child], h) : eval_interval(ndf, mu2, q.a, m, q.in_s);
    const PieceResult right =
        tabled ? eval_piece(ndf, mu2, (*q.tree)[child + 1], h) : eval_interval(ndf, mu2, m, q.b, q.in_s);
    p.piece[worst] = {q.a, m, left.K, left.E, q.in_s, q.tree, child};
    p.piece[p.n++] = {m, q.b, right.K, right.E, q.in_s, q.tree, tabled ? child + 1 : tree_size};
    // Re-summed, not updated, so that round-off does not accumulate over the bisections.
    p.K = 0.0;
    p.E = 0.0;
    for (int i = 0; i < p.n; ++i) p.K += p.piece[i].K, p.E += p.piece[i].E;
    return true;
}

}  // namespace fixed_rule

}  // namespace smithlab::detail
