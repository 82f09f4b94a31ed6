// smithlab_family_gen OUT.cpp -- generates the GTR family evaluator's two trees (family.hpp) at build time: every
// leaf's polynomial, its estimate and its checks, and the asymptotes' bound, written as C++ (hex floats: exact).
// Deterministic: the same file on any number of threads (the time it took is printed, not written).
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include "smithlab/gtr/family.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/util/parallel.hpp"

namespace {

using smithlab::GtrFamily;
constexpr int D = GtrFamily::degree;
constexpr int F = D + 1;  // the tensor Chebyshev interpolant's degree on each axis (F + 1 points)
constexpr int N = F + 1;
constexpr int max_depth = 24;

// ln t at slope r (r2 = r^2), t = alpha^2 (1 + r^2)/(alpha^2 + r^2) in [alpha^2, 1] (gtr.hpp): while t > 1/2 from
// 1 - t = (1 - alpha^2) r^2 / (alpha^2 + r^2), which keeps the digits t would round away.
double ln_t(double alpha, double r2) {
    const double om = (1.0 - alpha) * (1.0 + alpha), den = alpha * alpha + r2;
    const double t = alpha * alpha * ((1.0 + r2) / den);
    return t < 0.5 ? std::log(t) : std::log1p(-om * (r2 / den));
}

// ln(mu Lambda) at (alpha, mu) for n <= N gammas at once (the knots' route). The reduced integral in
// u = acosh(r/mu), as in lambda_fixed.hpp: Lambda = 2 int_0^inf f(r^2) r^2 H(u) du, H(u) = sinh u (sinh u - gd u) /
// cosh u, gd u = atan(sinh u), with GTR's f = K t^(gamma - 2) w^2 (gtr.hpp). The integrand is even in u and analytic
// in the strip |Im u| < pi/2 (its nearest singularities, f's pole r^2 = -alpha^2 and gd's, are pi/2 off the real
// axis, wherever mu is: lambda_fixed.hpp), so the trapezoid rule converges like exp(-2 pi d / h) (Trefethen and
// Weideman 2014, "The exponentially convergent trapezoidal rule", thm 5.1): h = 1/8 with d = pi/4 leaves ~1e-17 x
// the integrand's growth there (<= 2^(gamma/2)); measured <= 6.3e-10 relative against the adaptive route (tanh-sinh,
// 1e-13) at 300 random (alpha, mu) x 29 gamma, the same with the tail cut 24 or 32 past ln(9/mu). The geometry and
// ln t are shared by the gammas.
void strip(double alpha, double mu, const double* gamma, int n, double* out) {
    constexpr double h = 0.125;
    // past the last slope scale (sqrt(20) < 4.5) by 24: the r^-4 tail leaves ~e^-24 = 4e-11 of Lambda beyond
    const int steps = static_cast<int>((std::max(0.0, std::log(9.0 / mu)) + 24.0) / h) + 1;
    std::array<double, N> acc{};
    const double a2 = alpha * alpha, eh = std::exp(h);
    double E = 1.0;  // e^u, stepped (<= ~500 products: a relative drift below 1e-13)
    for (int k = 1; k <= steps; ++k) {
        E *= eh;
        const double s = 0.5 * (E - 1.0 / E), c = 0.5 * (E + 1.0 / E);
        // sinh u - gd u = s - atan s, its series below s = 0.1 (no cancellation)
        const double s2 = s * s;
        const double smg = s < 0.1 ? s * s2 * (1.0 / 3 - s2 * (1.0 / 5 - s2 * (1.0 / 7 - s2 / 9))) : s - std::atan(s);
        const double r2 = mu * mu * c * c, w = a2 / (r2 + a2), lt = ln_t(alpha, r2);
        const double base = r2 * w * w * (s * smg / c);
        for (int j = 0; j < n; ++j) acc[j] += base * std::exp((gamma[j] - 2.0) * lt);
    }
    for (int j = 0; j < n; ++j) out[j] = std::log(mu * 2.0 * h * smithlab::gtr_K(alpha, gamma[j]) * acc[j]);
}

using Point = std::array<double, 3>;  // (a = ln alpha, gamma, z): z = xi = ln(mu / alpha) in chart 0, ln mu in chart 1
double alpha_of(double a) { return std::min(1.0, std::exp(a)); }
double mu_of(int chart, double a, double z) { return std::exp(GtrFamily::ln_mu_of(chart, a, z)); }

struct Box {
    int chart;
    Point l, h;
    int slot, depth;
};
// A box wholly in the other chart's half (family.hpp: chart 0 holds ln mu < a/2) is no leaf: no point reaches it. The
// margin 1e-9 is far above the rounding of an evaluator's z (~1e-14), so a box near the boundary is always fitted.
bool other_half(const Box& b) { return b.chart == 0 ? b.l[2] + 0.5 * b.l[0] > 1e-9 : b.h[2] - 0.5 * b.l[0] < -1e-9; }

// |dG1| <= rel Lambda * max over the box of Lambda / (1 + Lambda)^2, from ln Lambda at the box's points (their range
// widened by 0.1)
double G1_factor(double ln_lambda_min, double ln_lambda_max) {
    auto q = [](double l) {
        const double e = std::exp(-std::abs(l));
        return e / ((1.0 + e) * (1.0 + e));
    };
    const double lo = ln_lambda_min - 0.1, hi = ln_lambda_max + 0.1;
    return lo <= 0.0 && hi >= 0.0 ? 0.25 : std::max(q(lo), q(hi));
}

struct Fit {
    smithlab::GtrFamilyLeaf leaf{};
    std::array<double, 3> estimate{};  // per axis
    double est = 0.0, g1_factor = 0.0;
    double check = 0.0, G1_check = 0.0;  // the largest |error| of ln(mu Lambda), of G1
    double float_sum = 0.0;              // sum of |float terms|: rounding them moves the value by <= float_sum 2^-24
    bool ok = false;
};

// Chebyshev T_n's monomial coefficients, n <= F
std::array<std::array<double, N>, N> chebyshev_monomials() {
    std::array<std::array<double, N>, N> t{};
    t[0][0] = 1.0;
    t[1][1] = 1.0;
    for (int n = 2; n < N; ++n)
        for (int m = 0; m < N; ++m) t[n][m] = (m > 0 ? 2.0 * t[n - 1][m - 1] : 0.0) - t[n - 2][m];
    return t;
}

// ln(mu Lambda) at the box's Chebyshev points of the first kind, [i][j][k] over (a, gamma, z), and the range of
// ln Lambda there
std::vector<double> values_at_chebyshev_points(const Box& b, double& ll_min, double& ll_max) {
    std::array<std::array<double, N>, 3> x;
    for (int d = 0; d < 3; ++d)
        for (int i = 0; i < N; ++i)
            x[d][i] = 0.5 * (b.l[d] + b.h[d]) + 0.5 * (b.h[d] - b.l[d]) * std::cos(std::numbers::pi * (i + 0.5) / N);
    std::vector<double> v(N * N * N);
    ll_min = INFINITY, ll_max = -INFINITY;
    for (int i = 0; i < N; ++i)
        for (int k = 0; k < N; ++k) {
            std::array<double, N> out;
            strip(alpha_of(x[0][i]), mu_of(b.chart, x[0][i], x[2][k]), x[1].data(), N, out.data());
            for (int j = 0; j < N; ++j) {
                v[(i * N + j) * N + k] = out[j];
                // ln Lambda = ln(mu Lambda) - ln mu
                const double ll = out[j] - GtrFamily::ln_mu_of(b.chart, x[0][i], x[2][k]);
                ll_min = std::min(ll_min, ll), ll_max = std::max(ll_max, ll);
            }
        }
    return v;
}

// values -> Chebyshev coefficients, one axis at a time: c_m = (2 - [m = 0]) / N sum_l v_l T_m(x_l)
void to_chebyshev_coefficients(std::vector<double>& v) {
    for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> c(v.size());
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j)
                for (int k = 0; k < N; ++k) {
                    const std::array<int, 3> at = {i, j, k};
                    const int m = at[axis];
                    double s = 0.0;
                    for (int l = 0; l < N; ++l) {
                        std::array<int, 3> q = at;
                        q[axis] = l;
                        s += v[(q[0] * N + q[1]) * N + q[2]] * std::cos(std::numbers::pi * m * (l + 0.5) / N);
                    }
                    c[(i * N + j) * N + k] = s * (m == 0 ? 1.0 : 2.0) / N;
                }
        v = c;
    }
}

// The kept part of the Chebyshev coefficients c in monomials of s = (x - centre) * scale: the constant and linear
// terms as doubles, the rest rounded to float in family.hpp's stored order (gtr_family_plan.term); the sum of the
// floats' magnitudes into float_sum.
void to_monomials(const Box& b, const std::vector<double>& c, smithlab::GtrFamilyLeaf& leaf, double& float_sum) {
    static const auto T = chebyshev_monomials();
    for (int d = 0; d < 3; ++d) leaf.centre[d] = 0.5 * (b.l[d] + b.h[d]), leaf.scale[d] = 2.0 / (b.h[d] - b.l[d]);
    auto monomial = [&](int i, int j, int k) {
        double m = 0.0;
        for (int ci = i; ci <= D; ++ci)
            for (int cj = j; cj <= D - ci; ++cj)
                for (int ck = k; ck <= D - ci - cj; ++ck)
                    m += c[(ci * N + cj) * N + ck] * T[ci][i] * T[cj][j] * T[ck][k];
        return m;
    };
    leaf.c0 = monomial(0, 0, 0);
    leaf.linear[0] = monomial(1, 0, 0), leaf.linear[1] = monomial(0, 1, 0), leaf.linear[2] = monomial(0, 0, 1);
    for (int q = 0; q < smithlab::GtrFamilyLeaf::n_higher; ++q) {
        const auto [i, j, k] = smithlab::gtr_family_plan.term[q];
        leaf.higher[q] = static_cast<float>(monomial(i, j, k));
        float_sum += std::abs(static_cast<double>(leaf.higher[q]));
    }
}

// checks on the box's 3 x 3 x 3 grid (corners, edge and face midpoints, centre: off the fit's points, the corners
// where interpolation errors are largest) against the knots' route, in ln(mu Lambda) and in G1
void check_leaf(const Box& b, Fit& r) {
    const smithlab::GtrFamilyLeaf& leaf = r.leaf;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
            const double a = b.l[0] + 0.5 * i * (b.h[0] - b.l[0]), z = b.l[2] + 0.5 * k * (b.h[2] - b.l[2]);
            const std::array<double, 3> g = {b.l[1], 0.5 * (b.l[1] + b.h[1]), b.h[1]};
            std::array<double, 3> want;
            strip(alpha_of(a), mu_of(b.chart, a, z), g.data(), 3, want.data());
            for (int j = 0; j < 3; ++j) {
                const Point p = {a, g[j], z};
                std::array<double, 3> s;
                for (int d = 0; d < 3; ++d) s[d] = (p[d] - leaf.centre[d]) * leaf.scale[d];  // as GtrFamily::locate
                const double got = GtrFamily::polynomial(leaf, s), ln_mu = GtrFamily::ln_mu_of(b.chart, a, z);
                auto G1 = [&](double f) { return 1.0 / (1.0 + std::exp(f - ln_mu)); };
                r.check = std::max(r.check, std::abs(got - want[j]));
                r.G1_check = std::max(r.G1_check, std::abs(G1(got) - G1(want[j])));
            }
        }
}

Fit fit(const Box& b) {
    double ll_min = 0.0, ll_max = 0.0;
    std::vector<double> v = values_at_chebyshev_points(b, ll_min, ll_max);
    to_chebyshev_coefficients(v);
    Fit r;
    r.g1_factor = G1_factor(ll_min, ll_max);
    // the estimate: the dropped coefficients (total degree > D), each on the axis of its highest degree
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j)
            for (int k = 0; k < N; ++k)
                if (i + j + k > D)
                    r.estimate[i >= j && i >= k ? 0 : j >= k ? 1 : 2] += std::abs(v[(i * N + j) * N + k]);
    r.est = r.estimate[0] + r.estimate[1] + r.estimate[2];
    if (r.est > GtrFamily::tolerance || r.est * r.g1_factor > GtrFamily::G1_tolerance) return r;
    to_monomials(b, v, r.leaf, r.float_sum);
    check_leaf(b, r);
    r.ok = r.check <= 2.0 * GtrFamily::tolerance && r.G1_check <= 2.0 * GtrFamily::G1_tolerance;
    return r;
}

template <class Fn>
void parallel_for(std::size_t n, const Fn& fn) {
    std::atomic<std::size_t> next{0};
    std::vector<std::thread> pool;
    const unsigned threads = smithlab::util::thread_count(0);  // every core
    for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&] {
            for (std::size_t i; (i = next++) < n;) fn(i);
        });
    for (std::thread& t : pool) t.join();
}

// The asymptotes' bound, on a grid of (alpha, gamma). Below xi_lo: R(mu_lo) <= (g(mu_1) - g(mu_lo)) / (mu_1/mu_lo -
// 1), g = mu Lambda + mu/2 (lambda_table.hpp), relative to mu Lambda. Above eta_hi: the secant slope of ln(mu Lambda)
// over the last 0.1 in ln mu against -1.
double asymptote_bound() {
    constexpr int na = 93, ng = 80;
    constexpr double hx = 0.1;
    std::vector<double> worst(na, 0.0);
    parallel_for(na, [&](std::size_t i) {
        const double a = GtrFamily::a_lo * (1.0 - static_cast<double>(i) / (na - 1)), alpha = alpha_of(a);
        for (int j0 = 0; j0 < ng; j0 += N) {
            std::array<double, N> g, f0, f1, f2, f3;
            const int n = std::min(N, ng - j0);
            for (int j = 0; j < n; ++j) g[j] = GtrFamily::gamma_max * (j0 + j) / (ng - 1);
            const double m0 = mu_of(0, a, GtrFamily::xi_lo), m1 = mu_of(0, a, GtrFamily::xi_lo + hx);
            strip(alpha, m0, g.data(), n, f0.data());
            strip(alpha, m1, g.data(), n, f1.data());
            strip(alpha, mu_of(1, a, GtrFamily::eta_hi - hx), g.data(), n, f2.data());
            strip(alpha, mu_of(1, a, GtrFamily::eta_hi), g.data(), n, f3.data());
            for (int j = 0; j < n; ++j) {
                const double g0 = std::exp(f0[j]) + 0.5 * m0, g1 = std::exp(f1[j]) + 0.5 * m1;
                worst[i] = std::max(worst[i], std::max(0.0, g1 - g0) / std::expm1(hx) / std::exp(f0[j]));
                worst[i] = std::max(worst[i], std::abs((f3[j] - f2[j]) / hx + 1.0));
            }
        }
    });
    return *std::max_element(worst.begin(), worst.end());
}

// The top boxes of both charts, GtrFamily::top per axis, each in its slot of the trees' first nodes
std::vector<Box> top_boxes() {
    const auto& top = GtrFamily::top;
    std::vector<Box> boxes;
    for (int c = 0; c < 2; ++c)
        for (int i = 0; i < top[0]; ++i)
            for (int j = 0; j < top[1]; ++j)
                for (int k = 0; k < top[2]; ++k)
                    boxes.push_back(
                        {c,
                         {GtrFamily::edge(c, 0, i), GtrFamily::edge(c, 1, j), GtrFamily::edge(c, 2, k)},
                         {GtrFamily::edge(c, 0, i + 1), GtrFamily::edge(c, 1, j + 1), GtrFamily::edge(c, 2, k + 1)},
                         static_cast<int>(c * GtrFamily::top_cells) + (i * top[1] + j) * top[2] + k,
                         0});
    return boxes;
}

// The two trees as they grow: their nodes (family.hpp), the leaves' data, and the largest estimates and checks
struct Trees {
    std::vector<smithlab::GtrFamilyNode> nodes = std::vector<smithlab::GtrFamilyNode>(2 * GtrFamily::top_cells);
    std::vector<int> no_leaf;  // the slots of boxes in the other chart's half
    std::vector<smithlab::GtrFamilyLeaf> leaf_data;
    std::size_t leaves = 0;
    double est_max = 0.0, g1_est_max = 0.0, check_max = 0.0, g1_check_max = 0.0, float_sum_max = 0.0;
    int depth_max = 0;

    void keep_leaf(const Box& b, const Fit& f) {
        nodes[b.slot] = {0.0, ~static_cast<std::int32_t>(leaves++), 0};
        leaf_data.push_back(f.leaf);
        est_max = std::max(est_max, f.est), g1_est_max = std::max(g1_est_max, f.est * f.g1_factor);
        check_max = std::max(check_max, f.check), g1_check_max = std::max(g1_check_max, f.G1_check);
        float_sum_max = std::max(float_sum_max, f.float_sum);
        depth_max = std::max(depth_max, b.depth);
    }
    // b halved along the axis of its largest estimate: a split node, the halves into next
    void halve(const Box& b, const Fit& f, std::vector<Box>& next) {
        const int axis = static_cast<int>(std::max_element(f.estimate.begin(), f.estimate.end()) - f.estimate.begin());
        const auto first = static_cast<std::int32_t>(nodes.size());
        const double split = 0.5 * (b.l[axis] + b.h[axis]);
        nodes[b.slot] = {split, first, axis};
        nodes.push_back({}), nodes.push_back({});
        Box lo = b, hi = b;
        lo.h[axis] = hi.l[axis] = split;
        lo.slot = first, hi.slot = first + 1, lo.depth = hi.depth = b.depth + 1;
        next.push_back(lo), next.push_back(hi);
    }
    // One level of the trees: every pending box fitted (in parallel), then kept as a leaf or split, in order;
    // pending becomes the halves. False, with a message, where a box at max_depth has no fit.
    bool grow(std::vector<Box>& pending) {
        std::vector<Fit> fits(pending.size());
        std::vector<char> no(pending.size());
        for (std::size_t i = 0; i < pending.size(); ++i) no[i] = other_half(pending[i]);
        parallel_for(pending.size(), [&](std::size_t i) {
            if (!no[i]) fits[i] = fit(pending[i]);
        });
        std::vector<Box> next;
        for (std::size_t i = 0; i < pending.size(); ++i) {
            const Box& b = pending[i];
            const Fit& f = fits[i];
            if (no[i]) {
                no_leaf.push_back(b.slot);
            } else if (f.ok) {
                keep_leaf(b, f);
            } else if (b.depth == max_depth) {
                std::fprintf(stderr,
                             "smithlab_family_gen: no fit within the tolerance at depth %d, chart %d box a "
                             "[%g, %g] gamma [%g, %g] z [%g, %g] (estimate %g)\n",
                             max_depth, b.chart, b.l[0], b.h[0], b.l[1], b.h[1], b.l[2], b.h[2], f.est);
                return false;
            } else {
                halve(b, f, next);
            }
        }
        pending.swap(next);
        return true;
    }
};

// The trees as C++ (hex floats: exact) into out_path, by way of out_path.tmp; false, with a message, on failure
bool write_trees(const Trees& t, double asymptotes, const std::string& out_path) {
    const std::string tmp = out_path + ".tmp";
    std::FILE* out = std::fopen(tmp.c_str(), "w");
    if (!out) {
        std::fprintf(stderr, "smithlab_family_gen: cannot write %s\n", tmp.c_str());
        return false;
    }
    std::fprintf(out,
                 "// Generated by smithlab_family_gen (gtr/tools/family_gen.cpp) at build time: do not edit.\n"
                 "#include \"smithlab/gtr/family.hpp\"\n\nnamespace smithlab {\nnamespace {\n"
                 "const GtrFamilyNode nodes[] = {\n");
    for (std::size_t i = 0; i < t.nodes.size(); ++i)
        std::fprintf(out, "{%a,%d,%d},%s", t.nodes[i].split, t.nodes[i].next, t.nodes[i].axis, i % 4 == 3 ? "\n" : "");
    std::fprintf(out, "};\nconst GtrFamilyLeaf leaves[] = {\n");
    for (const smithlab::GtrFamilyLeaf& l : t.leaf_data) {
        std::fprintf(out, "{{%a,%a,%a},{%a,%a,%a},%a,{%a,%a,%a},{", l.centre[0], l.centre[1], l.centre[2], l.scale[0],
                     l.scale[1], l.scale[2], l.c0, l.linear[0], l.linear[1], l.linear[2]);
        for (float c : l.higher) std::fprintf(out, "%af,", static_cast<double>(c));
        std::fprintf(out, "}},\n");
    }
    std::fprintf(out,
                 "{},\n};\n}  // namespace\n\n"
                 "const GtrFamilyData gtr_family_data = {nodes, %zu, leaves, %zu, %a, %d};\n\n"
                 "}  // namespace smithlab\n",
                 t.nodes.size(), t.leaves, asymptotes, t.depth_max);
    if (std::fclose(out) != 0 || std::rename(tmp.c_str(), out_path.c_str()) != 0) {
        std::fprintf(stderr, "smithlab_family_gen: cannot write %s\n", out_path.c_str());
        return false;
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: smithlab_family_gen OUT.cpp\n");
        return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    Trees t;
    std::vector<Box> pending = top_boxes();
    while (!pending.empty())
        if (!t.grow(pending)) return 1;
    for (int slot : t.no_leaf) t.nodes[slot] = {0.0, ~static_cast<std::int32_t>(t.leaves), 0};  // the empty leaf
    const double asymptotes = asymptote_bound();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!write_trees(t, asymptotes, argv[1])) return 1;
    const double bytes = static_cast<double>(t.leaf_data.size() * sizeof(smithlab::GtrFamilyLeaf) +
                                             t.nodes.size() * sizeof(smithlab::GtrFamilyNode));
    std::printf(
        "smithlab_family_gen: %zu leaves and %zu nodes (%.1f MB), depth <= %d, estimates <= %.3g / %.3g (G1), "
        "checks <= %.3g / %.3g, float terms' |sum| <= %.3g (rounding <= %.2g), asymptotes %.3g, %.1f s\n",
        t.leaves, t.nodes.size(), bytes / 1e6, t.depth_max, t.est_max, t.g1_est_max, t.check_max, t.g1_check_max,
        t.float_sum_max, std::ldexp(t.float_sum_max, -24), asymptotes, seconds);
    return 0;
}
