#include "smithlab/detail/fixed_rule.hpp"

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <memory>

namespace smithlab::detail::fixed_rule {

namespace {

// Boost.Math stores the non-negative half of the nodes (x = 0 first) and their weights. The n-point Gauss nodes,
// n = (nodes - 1) / 2, are the entries of odd index when n is even (x = 0 is then a Kronrod node), of even index when
// n is odd (Boost's gauss_kronrod::integrate_non_adaptive_m1_1 reads them so).
Rule make_rule() {
    constexpr int half = (nodes - 1) / 2;
    using GK = boost::math::quadrature::gauss_kronrod<double, nodes>;
    using G = boost::math::quadrature::gauss<double, half>;
    const auto& x = GK::abscissa();
    const auto& wk = GK::weights();
    const auto& wg = G::weights();
    const int gauss_parity = half % 2 == 0 ? 1 : 0;
    Rule r{};
    r.x[half] = 0.0;
    r.wk[half] = wk[0];
    r.wg[half] = gauss_parity == 0 ? wg[0] : 0.0;
    for (int i = 1; i <= half; ++i) {
        const double gauss = i % 2 == gauss_parity ? wg[i / 2] : 0.0;
        for (int side : {-1, 1}) {
            const int k = half + side * i;
            r.x[k] = side * x[i];
            r.wk[k] = wk[i];
            r.wg[k] = gauss;
        }
    }
    return r;
}

// A piece on [a, b] of u (or of s) with the geometry at its nodes.
Piece make_piece(const Rule& R, double a, double b, bool in_s) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    Piece p{};
    for (int k = 0; k < nodes; ++k) {
        const double x = c + h * R.x[k];
        const Geometry g = in_s ? at_s(x) : at_u(x);
        p.S[k] = g.S;
        p.W[k] = R.wk[k] * h * g.H;
        p.V[k] = R.wg[k] * h * g.H;
    }
    return p;
}

// The tree of a piece [a, b]: tree[1] = [a, b], tree[2i], tree[2i + 1] the halves of tree[i].
void make_tree(const Rule& R, Tree& tree, double a, double b, bool in_s) {
    std::array<double, tree_size> lo{}, hi{};
    lo[1] = a;
    hi[1] = b;
    for (int i = 1; i < tree_size; ++i) {
        if (i > 1) {
            const int parent = i / 2;
            const double m = 0.5 * (lo[parent] + hi[parent]);
            lo[i] = i % 2 == 0 ? lo[parent] : m;
            hi[i] = i % 2 == 0 ? m : hi[parent];
        }
        tree[i] = make_piece(R, lo[i], hi[i], in_s);
    }
}

// On the heap (0.8 MB: not a temporary on a thread's stack), built once.
std::unique_ptr<const Tables> make_tables() {
    const Rule& R = rule();
    auto t = std::make_unique<Tables>();
    for (int j = 0; j < max_panels; ++j) make_tree(R, t->panel[j], j * panel_width, (j + 1) * panel_width, false);
    for (int j = 0; j <= max_panels; ++j) {
        // s = pi/2 - gd(u) = atan(1 / sinh u), without the cancellation of pi/2 - atan(sinh u).
        t->s_edge[j] = j == 0 ? std::numbers::pi / 2 : std::atan(1.0 / std::sinh(j * panel_width));
        make_tree(R, t->tail[j], 0.0, t->s_edge[j], true);
    }
    return t;
}

}  // namespace

const Rule& rule() {
    static const Rule r = make_rule();
    return r;
}

const Tables& tables() {
    static const std::unique_ptr<const Tables> t = make_tables();
    return *t;
}

}  // namespace smithlab::detail::fixed_rule
