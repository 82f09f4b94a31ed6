/// @file
/// smithlab/gtr/family.hpp -- Lambda and G1 of every GTR at once: piecewise polynomials over (alpha, gamma, mu),
/// generated at build time (gtr/tools/family_gen.cpp) and compiled in, read-only, shared by every material and thread.
/// No per-material work and no first-use build.
///
/// Domain: alpha in [1e-4, 1], gamma in [0, 20], any mu. The function held is f = ln(mu Lambda) (Lambda: Walter 2007
/// eq. 48, the reduced 1D form of smith.hpp) over (a = ln alpha, gamma, z), in two charts that meet at mu =
/// sqrt(alpha):
///   chart 0, mu < sqrt(alpha): z = xi = ln(mu / alpha) in [xi_lo, -a/2] (the slope scale alpha, where Lambda turns
///            from ~1/mu to its power-law tail, is the plane xi = 0);
///   chart 1, mu >= sqrt(alpha): z = eta = ln mu in [a/2, eta_hi] (GTR's second slope scale, r ~ 1 where t^(gamma - 2)
///            turns, gtr.hpp, is the plane eta = 0).
/// Each feature is axis-aligned in its own chart; in one chart over (a, xi) the second runs diagonally, and resolving
/// it took 2.1x the leaves (14 237 against 6 712 at the same tolerance). Each chart is a k-d tree of boxes: a uniform
/// top grid (`top` boxes per axis), each box split in two at its middle, along one axis, until its polynomial is within
/// the tolerance; a box wholly in the other chart's half is no leaf (its node points at an empty leaf past the last:
/// no point of the domain reaches it, a NaN may, and reads zeros).
/// Each leaf holds the polynomial of total degree `degree` in the box's coordinates s in [-1, 1]^3 (monomials
/// s0^i s1^j s2^k, i + j + k <= degree): the Chebyshev interpolant of degree degree + 1 on each axis (Trefethen 2013,
/// "Approximation Theory and Approximation Practice", ch. 3-4; tensor product of Chebyshev points of the first kind),
/// truncated to total degree `degree`. A leaf's error estimate is the sum of the dropped Chebyshev coefficients
/// (|T_n| <= 1 on the box), each counted on the axis of its highest degree; the box is split along the axis whose share
/// is largest, until the estimate is within `tolerance` (relative, Lambda) and `G1_tolerance` (|dG1| <= rel Lambda /
/// (1 + Lambda)^2, from the leaf's own values), and the polynomial, its terms of degree >= 2 rounded to float
/// (GtrFamilyLeaf), is within twice those on the box's 3 x 3 x 3 grid (corners, edge and face midpoints, centre: off
/// the fit's points; checked against the knots' route, not the fit). A leaf holds on its whole box, across the charts'
/// boundary too.
/// The knots' route (family_gen.cpp): the trapezoid rule in u = acosh(r/mu) on the integrand of lambda_fixed.hpp,
/// every gamma of a box at once (6.3e-10 relative against tanh-sinh).
/// Beyond the charts, the two asymptotes of lambda_table.hpp:
///   xi < xi_lo:   mu Lambda = g_lo - mu/2, g_lo = mu_lo Lambda(mu_lo) + mu_lo/2 (Walter eq. 48 with P(q > 0) = 1/2;
///                 in error by R(mu_lo) - R(mu) in [0, R(mu_lo)], R bounded from two points as in lambda_table.hpp);
///   eta > eta_hi: Lambda ~ C mu^-2 (every GTR has a P22 ~ r^-4 tail: t -> alpha^2 as r -> inf, gtr.hpp), ln(mu Lambda)
///                 continued with slope -1 (its slope's deviation s + 1 at eta_hi, measured, bounds the error: the next
///                 term is relative mu^-2, so the deviation decays like e^(-2 (eta - eta_hi)) and sums to (s + 1)/2).
/// The stated bounds (error_bound(), G1_error_bound()): twice the tolerances (the checks' limit) plus the asymptotes'.
/// An estimate and 27 checks per leaf, not a proof: tested against independent references at two random points of
/// every leaf, and elsewhere (tests/test_family.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>

#include "smithlab/smith.hpp"

namespace smithlab {

/// The generated data (family_gen.cpp writes it; one definition, in the build tree's family_patches.cpp).
inline constexpr int gtr_family_degree = 6;  ///< each leaf's polynomial: total degree
/// One leaf: its box, and its polynomial in the box's coordinates s = (x - centre) * scale in [-1, 1]^3. The constant
/// and linear terms are doubles (they carry ln(mu Lambda), up to ~300, and its slopes, up to ~40); the rest are floats
/// (their magnitudes sum to <= 2.97 on every leaf, so rounding them moves the value by <= 1.8e-7: the generator prints
/// the figure, and its checks are of these rounded values). Half the bytes of doubles: ~7 cache lines a leaf, not 12.
struct GtrFamilyLeaf {
    /// The number of terms of degree >= 2.
    static constexpr int n_higher = (gtr_family_degree + 1) * (gtr_family_degree + 2) * (gtr_family_degree + 3) / 6 - 4;
    /// The box: s = (x - centre) * scale.
    /// @{
    double centre[3], scale[3];
    /// @}
    /// @{
    double c0, linear[3];  ///< the terms in 1, s0, s1, s2
    /// @}
    float higher[n_higher];  ///< c_ijk s0^i s1^j s2^k for 2 <= i + j + k <= degree, in gtr_family_plan's order
};
/// The stored order of a leaf's terms of degree >= 2 (GtrFamilyLeaf::higher): row (i, j) holds c_ijk for k from
/// k0 = max(0, 2 - i - j) to degree - i - j. Rows are taken by length, longest first, in (i, j) order; two of one
/// length are a pair, stored interleaved (a_k0, b_k0, a_k0+1, b_k0+1, ...); every pair first, then each length's
/// odd row. term[q] = (i, j, k) of stored term q: the generator writes the terms in this order; the evaluator
/// (GtrFamily::polynomial) runs the pairs two rows at a time.
struct GtrFamilyPlan {
    /// The polynomials' total degree.
    static constexpr int degree = gtr_family_degree;
    static constexpr int n_rows = (degree + 1) * (degree + 2) / 2;  ///< the (i, j) with i + j <= degree
    /// Each row's (i, j), first power k0 of s2, and number of terms.
    /// @{
    std::array<int, n_rows> i{}, j{}, k0{}, length{};  ///< per row, in (i, j) order
    /// @}
    /// Pair p's two rows and where its terms start; the odd rows and where theirs start.
    /// @{
    std::array<int, n_rows> pair_a{}, pair_b{}, pair_at{}, single{}, single_at{};  ///< rows; where their terms start
    /// @}
    /// The number of pairs, of odd rows, and of terms placed.
    /// @{
    int n_pairs = 0, n_singles = 0, n_terms = 0;
    /// @}
    /// term[q] = (i, j, k) of stored term q.
    std::array<std::array<int, 3>, GtrFamilyLeaf::n_higher> term{};
};
/// The plan of the stored order, as above: rows by length, longest first, paired in (i, j) order, then the odd rows.
constexpr GtrFamilyPlan make_gtr_family_plan() {
    constexpr int degree = gtr_family_degree, n_rows = GtrFamilyPlan::n_rows;
    GtrFamilyPlan p;
    int row = 0;
    for (int i = 0; i <= degree; ++i)
        for (int j = 0; j <= degree - i; ++j, ++row) {
            p.i[row] = i, p.j[row] = j, p.k0[row] = std::max(0, 2 - i - j);
            p.length[row] = degree - i - j - p.k0[row] + 1;
        }
    int at = 0;
    std::array<int, n_rows> odd{};
    int n_odd = 0;
    for (int length = degree + 1; length >= 1; --length) {
        int waiting = -1;
        for (int r = 0; r < n_rows; ++r) {
            if (p.length[r] != length) continue;
            if (waiting < 0) {
                waiting = r;
                continue;
            }
            p.pair_a[p.n_pairs] = waiting, p.pair_b[p.n_pairs] = r, p.pair_at[p.n_pairs++] = at;
            for (int t = 0; t < length; ++t) {
                p.term[at++] = {p.i[waiting], p.j[waiting], p.k0[waiting] + t};
                p.term[at++] = {p.i[r], p.j[r], p.k0[r] + t};
            }
            waiting = -1;
        }
        if (waiting >= 0) odd[n_odd++] = waiting;
    }
    for (int o = 0; o < n_odd; ++o) {
        const int r = odd[o];
        p.single[p.n_singles] = r, p.single_at[p.n_singles++] = at;
        for (int t = 0; t < p.length[r]; ++t) p.term[at++] = {p.i[r], p.j[r], p.k0[r] + t};
    }
    p.n_terms = at;
    return p;
}
/// The stored order, computed at compile time.
inline constexpr GtrFamilyPlan gtr_family_plan = make_gtr_family_plan();
static_assert(gtr_family_plan.n_terms == GtrFamilyLeaf::n_higher);  // every row placed once, in pairs or alone

/// A node of a chart's k-d tree: an inner node splits its box in two along one axis; a leaf's node points at its leaf.
struct GtrFamilyNode {
    double split;       ///< an inner node: its children hold x[axis] < split and >= split
    std::int32_t next;  ///< >= 0: the first of its two children; < 0: the leaf ~next
    /// The axis of the split: 0 ln alpha, 1 gamma, 2 z.
    std::int32_t axis;
};
/// The generated tree: nodes, leaves and the measured bounds (family_gen.cpp writes it).
struct GtrFamilyData {
    const GtrFamilyNode* nodes;   ///< each chart's top boxes first (chart 0's, chart 1's; row-major over a, gamma, z),
    std::size_t n_nodes;          ///< then children in pairs
    const GtrFamilyLeaf* leaves;  ///< n_leaves + 1: the last, empty, for the boxes that are no leaf
    /// The number of leaves, the empty one past the last not counted.
    std::size_t n_leaves;
    double asymptote_bound;  ///< relative Lambda, beyond the charts
    int max_depth;           ///< splits below a top box
};
/// The tree, compiled in (the build tree's family_patches.cpp).
extern const GtrFamilyData gtr_family_data;

/// Lambda and G1 of every GTR at once from the generated tree (the file comment); one instance, shared.
class GtrFamily {
public:
    /// The domain: alpha in [alpha_min, 1], gamma in [0, gamma_max].
    /// @{
    static constexpr double alpha_min = 1e-4;
    static constexpr double gamma_max = 20.0;
    /// @}
    /// The charts' ends: chart 0 from xi = xi_lo, chart 1 up to eta = eta_hi, the asymptotes beyond.
    /// Below xi_lo, R(mu_lo) / (mu_lo Lambda) ~ (mu_lo / alpha)^2 gamma < 1e-6; above eta_hi, mu >= 1.8e4, past every
    /// GTR's second slope scale (1 and sqrt(gamma), gtr.hpp), where Lambda ~ C mu^-2
    /// @{
    static constexpr double xi_lo = -9.0, eta_hi = 9.8;
    /// @}
    /// Each leaf's polynomial: total degree.
    static constexpr int degree = gtr_family_degree;
    static constexpr double a_lo = -9.2103403719762;       ///< just below ln 1e-4
    static constexpr std::array<int, 3> top = {8, 8, 14};  ///< each chart's
    /// Each chart's box in (ln alpha, gamma, z): from lo to hi.
    /// @{
    static constexpr std::array<std::array<double, 3>, 2> lo = {{{a_lo, 0.0, xi_lo}, {a_lo, 0.0, 0.5 * a_lo}}};
    static constexpr std::array<std::array<double, 3>, 2> hi = {
        {{0.0, gamma_max, -0.5 * a_lo}, {0.0, gamma_max, eta_hi}}};
    /// @}
    /// The top boxes of each chart.
    static constexpr std::size_t top_cells = static_cast<std::size_t>(top[0]) * top[1] * top[2];
    /// 1 / the width of chart c's top boxes along axis d (x -> top box: (x - lo) * inv_step)
    static constexpr double inv_step(int c, int d) { return top[d] / (hi[c][d] - lo[c][d]); }
    /// The domain (the checked calls' rules): alpha in [1e-4, 1], gamma in [0, 20]; NaN is outside.
    /// @{
    static constexpr bool alpha_in_domain(double alpha) { return alpha >= alpha_min && alpha <= 1.0; }
    static constexpr bool gamma_in_domain(double gamma) { return gamma >= 0.0 && gamma <= gamma_max; }
    /// @}
    /// A leaf's estimate is at most `tolerance` relative in Lambda and `G1_tolerance` in G1; its checks at most twice.
    /// @{
    static constexpr double tolerance = 4e-6;
    static constexpr double G1_tolerance = 4e-7;
    /// @}

    /// The evaluator, built at the first call (thread-safe) and shared.
    static const GtrFamily& get();

    /// The chart of (a = ln alpha, eta = ln mu): 0 below mu = sqrt(alpha), else 1 (NaN: 1); chart c's third coordinate
    /// z of (a, eta), and ln mu back from z (the generator's and the tests' one definition).
    /// @{
    static constexpr int chart_of(double a, double eta) { return eta < 0.5 * a ? 0 : 1; }
    static constexpr double z_of(int c, double a, double eta) { return c == 0 ? eta - a : eta; }
    static constexpr double ln_mu_of(int c, double a, double z) { return c == 0 ? a + z : z; }
    /// @}
    /// Lambda at finite mu > 0 for alpha in [1e-4, 1], gamma in [0, 20]: nothing is checked here (see
    /// Lambda_gtr_family for the checked call; a NaN gives some value, never a read out of bounds). No allocation,
    /// exception or virtual call.
    double Lambda_up(double alpha, double gamma, double mu) const {
        const double a = std::log(alpha), eta = std::log(mu);
        if (chart_of(a, eta) == 0) {  // locate clamps xi to xi_lo; mu = 0: +inf
            const double xi = z_of(0, a, eta), f = value(0, {a, gamma, xi});
            return xi < xi_lo ? (std::exp(f) + 0.5 * alpha * mu_lo_rel_) / mu - 0.5 : std::exp(f) / mu;
        }
        const double f = value(1, {a, gamma, eta});  // locate clamps eta to eta_hi; mu = inf: 0
        return std::exp(eta > eta_hi ? f - (eta - eta_hi) : f) / mu;
    }
    /// G1 = 1 / (1 + Lambda_up), on the same terms.
    double G1_up(double alpha, double gamma, double mu) const { return 1.0 / (1.0 + Lambda_up(alpha, gamma, mu)); }

    /// ln(mu Lambda) at x = (ln alpha, gamma, z) in chart c, inside the chart's box (clamped to it).
    double value(int c, const std::array<double, 3>& x) const {
        const Located l = locate(c, x);
        return polynomial(*l.leaf, l.s);
    }
    /// The leaf holding x in chart c (x clamped to the chart's box), and x in its coordinates s in [-1, 1]^3.
    struct Located {
        /// The leaf, and x in its coordinates.
        /// @{
        const GtrFamilyLeaf* leaf;
        std::array<double, 3> s;
        /// @}
    };
    /// The leaf holding x in chart c, as above: the top box by x's cell, then down the tree.
    Located locate(int c, std::array<double, 3> x) const {
        std::size_t cell = 0;
        for (int d = 0; d < 3; ++d) {
            x[d] = x[d] >= lo[c][d] ? std::min(x[d], hi[c][d]) : lo[c][d];  // NaN to lo: never a read out of bounds
            cell = cell * top[d] + std::min(static_cast<int>((x[d] - lo[c][d]) * inv_step_[c][d]), top[d] - 1);
        }
        const GtrFamilyNode* node = &data_.nodes[c * top_cells + cell];
        while (node->next >= 0) node = &data_.nodes[node->next + (x[node->axis] >= node->split)];
        const GtrFamilyLeaf& leaf = data_.leaves[~node->next];
        return {&leaf,
                {(x[0] - leaf.centre[0]) * leaf.scale[0], (x[1] - leaf.centre[1]) * leaf.scale[1],
                 (x[2] - leaf.centre[2]) * leaf.scale[2]}};
    }

    /// Chart c's top grid's i-th edge on axis d (the generator's boxes are these, halved; the evaluator's top cell is
    /// the one x falls in by its own rounding, which may be the neighbour's at an edge: both polynomials hold there).
    static constexpr double edge(int c, int d, int i) {
        return i == top[d] ? hi[c][d] : lo[c][d] + (hi[c][d] - lo[c][d]) * i / top[d];
    }

    /// sum over i + j + k <= degree of c_ijk s0^i s1^j s2^k. The terms of degree >= 2 by rows (i, j): each row a
    /// polynomial in s2 (Horner), times s0^i s1^j s2^k0. Two rows of one length run in one two-lane vector (GCC >= 9
    /// and Clang vector extensions, which this header needs; SSE2 on x86-64), their floats widened four at a time:
    /// straight-line code, unrolled by index sequences over gtr_family_plan (~19 ns alone, against 26.7 for one row at
    /// a time with scalar widening).
    static double polynomial(const GtrFamilyLeaf& leaf, const std::array<double, 3>& s) {
        return polynomial(leaf, s, std::make_index_sequence<gtr_family_plan.n_pairs>{},
                          std::make_index_sequence<gtr_family_plan.n_singles>{});
    }

private:
    typedef double v2d __attribute__((vector_size(16)));
    typedef double v4d __attribute__((vector_size(32)));
    typedef float v2f __attribute__((vector_size(8)));
    typedef float v4f __attribute__((vector_size(16)));
    /// a pair's row polynomials at s2 (Horner), from its 2 * length interleaved floats
    template <int length>
    static v2d horner_pair(const float* c, v2d s2) {
        double w[2 * length];
        for (int t = 0; t + 1 < length; t += 2) {
            v4f f;
            std::memcpy(&f, c + 2 * t, sizeof f);
            const v4d d = __builtin_convertvector(f, v4d);
            std::memcpy(w + 2 * t, &d, sizeof d);
        }
        if constexpr (length % 2 == 1) {
            v2f f;
            std::memcpy(&f, c + 2 * (length - 1), sizeof f);
            const v2d d = __builtin_convertvector(f, v2d);
            std::memcpy(w + 2 * (length - 1), &d, sizeof d);
        }
        v2d h;
        std::memcpy(&h, w + 2 * (length - 1), sizeof h);
        for (int t = length - 2; t >= 0; --t) {
            v2d x;
            std::memcpy(&x, w + 2 * t, sizeof x);
            h = h * s2 + x;
        }
        return h;
    }
    template <int length>
    static double horner(const float* c, double s2) {
        double h = c[length - 1];
        for (int t = length - 2; t >= 0; --t) h = h * s2 + static_cast<double>(c[t]);
        return h;
    }
    /// Out of line: inlined into value(), the whole call measured 72 ns against 62 (bench_family, family/random).
    template <std::size_t... P, std::size_t... S>
    [[gnu::noinline]] static double polynomial(const GtrFamilyLeaf& leaf, const std::array<double, 3>& s,
                                               std::index_sequence<P...>, std::index_sequence<S...>) {
        constexpr const GtrFamilyPlan& t = gtr_family_plan;
        double p0[degree + 1], p1[degree + 1], p2[degree + 1];
        p0[0] = p1[0] = p2[0] = 1.0;
        for (int e = 1; e <= degree; ++e) p0[e] = p0[e - 1] * s[0], p1[e] = p1[e - 1] * s[1], p2[e] = p2[e - 1] * s[2];
        auto factor = [&](int r) { return p0[t.i[r]] * p1[t.j[r]] * p2[t.k0[r]]; };
        const v2d s2 = {s[2], s[2]};
        v2d pairs = {0.0, 0.0};
        ((pairs += horner_pair<t.length[t.pair_a[P]]>(leaf.higher + t.pair_at[P], s2) *
              v2d{factor(t.pair_a[P]), factor(t.pair_b[P])}),
         ...);
        double singles = 0.0;
        ((singles += horner<t.length[t.single[S]]>(leaf.higher + t.single_at[S], s[2]) * factor(t.single[S])), ...);
        return (leaf.c0 + leaf.linear[0] * s[0]) + (leaf.linear[1] * s[1] + leaf.linear[2] * s[2]) +
            ((pairs[0] + pairs[1]) + singles);
    }

public:
    /// The stated bound on the relative error of Lambda, anywhere in the domain, and on |dG1|.
    double error_bound() const { return error_bound_; }
    /// e^xi_lo: mu / alpha where the lower asymptote begins (Lambda_up)
    double mu_lo_rel() const { return mu_lo_rel_; }
    /// The stated bound on |dG1| (error_bound()).
    double G1_error_bound() const { return G1_error_bound_; }
    /// The tree it reads.
    const GtrFamilyData& data() const { return data_; }
    /// The bytes of its nodes and leaves.
    std::size_t bytes() const { return data_.n_nodes * sizeof(GtrFamilyNode) + data_.n_leaves * sizeof(GtrFamilyLeaf); }

private:
    GtrFamily();
    const GtrFamilyData& data_;
    std::array<std::array<double, 3>, 2> inv_step_;
    double mu_lo_rel_, error_bound_, G1_error_bound_;
};

/// Checked calls: input_error naming alpha (not in [1e-4, 1], NaN) or gamma (not in [0, 20], NaN); mu as everywhere
/// (smith.hpp): NaN refused, 0 gives Lambda = inf, inf gives 0, mu < 0 follows the downward convention; G1 takes |mu|.
/// @{
double Lambda_gtr_family(double alpha, double gamma, double mu, Downward downward = Downward::smith);
double G1_gtr_family(double alpha, double gamma, double mu);
/// @}
/// The domain check of the checked calls: input_error naming alpha or gamma outside it.
void require_gtr_family_domain(double alpha, double gamma);

}  // namespace smithlab
