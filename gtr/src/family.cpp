// The GTR family table (family.hpp): its grid, its knots from the exact routes, and its per-cell error estimates.
#include "smithlab/gtr/family.hpp"

#include <chrono>
#include <cstddef>
#include <thread>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/walk/parallel.hpp"

namespace smithlab {

namespace {

// The grid. a = ln alpha: 93 uniform knots on [ln 1e-4, 0], step 0.1, as fine as xi's (Lambda's features at mu ~ 1
// and sqrt(gamma) move diagonally in (a, xi)). xi = ln(mu/alpha): uniform on [-9, 19], step 0.1; below,
// R(mu_lo) / (mu_lo Lambda) ~ (mu_lo / alpha)^2 gamma < 1e-6; above, mu >= 1.8e4 alpha, past every GTR's second slope
// scale (1 and sqrt(gamma), gtr.hpp), where Lambda ~ C mu^-2.
constexpr int n_a = 93;
constexpr double xi_lo = -9.0, xi_hi = 19.0, h_xi = 0.1;

// Piecewise uniform, so that strip() steps t^gamma by products; the step ~ (gamma + 1/2) / 20, halved at each run's
// start (ln(mu Lambda) goes like ln gamma: a uniform step left every cell of gamma in [4, 9] to the exact route).
std::vector<double> gamma_knots() {
    struct Run {
        double from, step;
        int n;
    };
    std::vector<double> g;
    for (const Run& r : {Run{0.0, 0.025, 20}, Run{0.5, 0.05, 20}, Run{1.5, 0.1, 20}, Run{3.5, 0.2, 20}, Run{7.5, 0.4, 10},
                         Run{11.5, 0.5, 8}, Run{15.5, 1.0, 5}})
        for (int i = 0; i < r.n; ++i) g.push_back(r.from + r.step * i);
    g.push_back(20.0);
    for (double& x : g) x = std::round(x * 1e12) / 1e12;  // 0.1 * 3 is 0.30000000000000004: keep integers exact
    return g;
}

// Lambda at mu for every gamma knot at once (the knots' route). The reduced integral in u = acosh(r/mu), as in
// lambda_fixed.hpp: Lambda = 2 int_0^inf f(r^2) r^2 H(u) du, H(u) = sinh u (sinh u - gd u) / cosh u, gd u =
// atan(sinh u), with GTR's f = K t^(gamma - 2) w^2 (gtr.hpp). The integrand is even in u and analytic in the strip
// |Im u| < pi/2 (its nearest singularities, f's pole r^2 = -alpha^2 and gd's, are pi/2 off the real axis, wherever
// mu is: lambda_fixed.hpp), so the trapezoid rule converges like exp(-2 pi d / h) (Trefethen and Weideman 2014,
// "The exponentially convergent trapezoidal rule", thm 5.1): h = 1/8 with d = pi/4 leaves ~1e-17 x the integrand's
// growth there (<= 2^(gamma/2)); measured <= 6.3e-10 relative against the adaptive route (tanh-sinh, 1e-13) at 300
// random (alpha, mu) x 29 gamma, the same with the tail cut 24 or 32 past ln(9/mu) (h = 1/6: 1.6e-5). Every
// geometric factor and ln t (GtrFamily::ln_t) are shared by all gamma; t^(gamma - 2) is stepped from knot to knot by
// products (two exps per run of equal steps), e^u by products too.
void strip(double alpha, double mu, const std::vector<double>& g, const std::vector<double>& K, double* out,
           std::ptrdiff_t stride) {
    const int ng = static_cast<int>(g.size());
    constexpr double h = 0.125;
    // past the last slope scale (sqrt(20) < 4.5) by 24: the r^-4 tail leaves ~e^-24 = 4e-11 of Lambda beyond
    const int n = static_cast<int>((std::max(0.0, std::log(9.0 / mu)) + 24.0) / h) + 1;
    std::vector<double> acc(ng, 0.0);
    // runs of equal steps in gamma: [start, end) with step d (a knot's t^gamma is its run start's times t^(d k))
    struct Run {
        int start, end;
        double d;
    };
    std::vector<Run> runs;
    for (int j = 0; j < ng;) {
        const double d = j + 1 < ng ? g[j + 1] - g[j] : 0.0;
        int e = j + 1;
        while (e + 1 < ng && std::abs((g[e + 1] - g[e]) - d) < 1e-12) ++e;
        runs.push_back({j, e, d});
        j = e;
    }
    const double a2 = alpha * alpha, eh = std::exp(h);
    double E = 1.0;  // e^u, stepped (n <= ~500 products: a relative drift below 1e-13)
    for (int k = 1; k <= n; ++k) {
        E *= eh;
        const double s = 0.5 * (E - 1.0 / E), c = 0.5 * (E + 1.0 / E);
        // sinh u - gd u = s - atan s, its series below s = 0.1 (no cancellation)
        const double s2 = s * s;
        const double smg = s < 0.1 ? s * s2 * (1.0 / 3 - s2 * (1.0 / 5 - s2 * (1.0 / 7 - s2 / 9))) : s - std::atan(s);
        const double r2 = mu * mu * c * c, den = r2 + a2, w = a2 / den;
        const double lt = GtrFamily::ln_t(alpha, r2);
        const double base = r2 * w * w * (s * smg / c);
        // four knots per product in each run: the chain of products is a quarter as long
        for (const Run& run : runs) {
            double p = base * std::exp((g[run.start] - 2.0) * lt);
            const double f1 = std::exp(run.d * lt), f2 = f1 * f1, f3 = f2 * f1, f4 = f2 * f2;
            int j = run.start;
            for (; j + 3 < run.end; j += 4, p *= f4) {
                acc[j] += p;
                acc[j + 1] += p * f1;
                acc[j + 2] += p * f2;
                acc[j + 3] += p * f3;
            }
            for (; j < run.end; ++j, p *= f1) acc[j] += p;
        }
    }
    for (int j = 0; j < ng; ++j) out[j * stride] = 2.0 * h * K[j] * acc[j];
}

// max over v in [lo, hi] of |prod_m (v - x_m)| for the window's P knots x_m (sampled: the estimate's constant).
double nodal_max(const double* x, int P, double lo, double hi) {
    double m = 0.0;
    for (int k = 0; k <= 32; ++k) {
        const double v = lo + (hi - lo) * k / 32.0;
        double p = 1.0;
        for (int i = 0; i < P; ++i) p *= v - x[i];
        m = std::max(m, std::abs(p));
    }
    return m;
}

// The P-th divided difference f[x0..xP] = sum_m c_m f(x_m), c_m = 1 / prod_{l != m} (x_m - x_l) (= f^(P)/P! at some
// point of [x0, xP]): the weights of every (P+1)-knot window of an axis, P <= 6.
std::vector<std::array<double, 7>> divided_weights(const std::vector<double>& x, int P) {
    std::vector<std::array<double, 7>> w(x.size() - P);
    for (std::size_t s = 0; s < w.size(); ++s)
        for (int m = 0; m <= P; ++m) {
            double den = 1.0;
            for (int l = 0; l <= P; ++l)
                if (l != m) den *= x[s + m] - x[s + l];
            w[s][m] = 1.0 / den;
        }
    return w;
}

// fn(i) for i in [0, n), interleaved over every core.
template <class F>
void parallel_for(int n, const F& fn) {
    const int threads = static_cast<int>(walk::thread_count(0));  // every core
    std::vector<std::thread> pool;
    for (int th = 0; th < threads; ++th)
        pool.emplace_back([&, th] {
            for (int i = th; i < n; i += threads) fn(i);
        });
    for (std::thread& t : pool) t.join();
}

// In place: D[s][u][v] (u < nu, v < nv) becomes the max over the P x P block [u, u + P) x [v, v + P), for every
// u <= nu - P, v <= nv - P (the rest is left as is): a cell's estimate then reads one entry per window, not P^2.
void block_max(std::vector<double>& D, int ns, int nu, int nv, int P) {
    parallel_for(ns, [&](int s) {
        double* d = &D[static_cast<std::size_t>(s) * nu * nv];
        for (int u = 0; u < nu; ++u)
            for (int v = 0; v + P <= nv; ++v) d[u * nv + v] = *std::max_element(d + u * nv + v, d + u * nv + v + P);
        for (int v = 0; v + P <= nv; ++v)
            for (int u = 0; u + P <= nu; ++u) {
                double m = d[u * nv + v];
                for (int l = 1; l < P; ++l) m = std::max(m, d[(u + l) * nv + v]);
                d[u * nv + v] = m;
            }
    });
}

}  // namespace

double GtrFamily::exact_f(double alpha, double gamma, double xi) {
    const double mu = alpha * std::exp(xi);
    // auto: the closed form at integer gamma, else the fixed rule (GSL where its estimate misses 1e-11)
    return std::log(mu * Lambda(gtr(alpha, gamma), mu, {.backend = Backend::gsl, .tolerance = 1e-11}));
}

const GtrFamily& GtrFamily::get() {
    static const GtrFamily table;
    return table;
}

GtrFamily::GtrFamily() {
    const auto t0 = std::chrono::steady_clock::now();
    g_ = gamma_knots();
    na_ = n_a;
    ng_ = static_cast<int>(g_.size());
    nx_ = static_cast<int>(std::lround((xi_hi - xi_lo) / h_xi)) + 1;
    a0_ = std::log(alpha_min);
    const double h_a = -a0_ / (na_ - 1);
    inv_ha_ = 1.0 / h_a;
    xi_lo_ = xi_lo;
    xi_hi_ = xi_lo + h_xi * (nx_ - 1);
    inv_hx_ = 1.0 / h_xi;
    mu_lo_rel_ = std::exp(xi_lo_);
    g_inv_den4_ = divided_weights(g_, 3);  // P-point Lagrange's denominators: the (P-1)-th difference's weights
    g_inv_den6_ = divided_weights(g_, 5);
    for (int k = 0; k <= 100 * static_cast<int>(gamma_max); ++k) {
        const double gm = k / 100.0;
        int j = 0;
        while (j < ng_ - 2 && g_[j + 1] <= gm) ++j;
        gamma_lut_.push_back(static_cast<std::uint16_t>(j));
    }

    // The knots: one strip of every gamma per (alpha, xi), on every core; the known part subtracted.
    auto alpha_of = [&](int i) { return i == na_ - 1 ? 1.0 : std::exp(a0_ + h_a * i); };
    f_.assign(static_cast<std::size_t>(na_) * ng_ * nx_, 0.0);
    std::vector<double> ln_mu_Lambda(f_.size());  // ln(mu Lambda) itself, for the asymptotes' bounds
    parallel_for(na_, [&](int i) {
        const double alpha = alpha_of(i);
        std::vector<double> K(ng_), lnK(ng_);
        for (int j = 0; j < ng_; ++j) K[j] = gtr_K(alpha, g_[j]), lnK[j] = std::log(K[j]);
        for (int k = 0; k < nx_; ++k) {
            const double xi = xi_lo_ + h_xi * k, mu = alpha * std::exp(xi), lt = ln_t(alpha, mu * mu);
            const std::size_t at0 = static_cast<std::size_t>(i) * ng_ * nx_ + k;
            strip(alpha, mu, g_, K, &ln_mu_Lambda[at0], nx_);
            for (int j = 0; j < ng_; ++j) {
                double& v = ln_mu_Lambda[at0 + static_cast<std::size_t>(j) * nx_];
                v = std::log(mu * v);
                f_[at0 + static_cast<std::size_t>(j) * nx_] = v - (lnK[j] + g_[j] * lt);  // known(), its pieces hoisted
            }
        }
    });

    // Per-axis P-th divided differences at every (P+1)-knot window, P = 4 and 6.
    auto index = [](int s, int j, int k, int nj, int nk) { return (static_cast<std::size_t>(s) * nj + j) * nk + k; };
    std::vector<double> ua(na_), ux(nx_);
    for (int i = 0; i < na_; ++i) ua[i] = i;
    for (int k = 0; k < nx_; ++k) ux[k] = k;
    struct Differences {
        std::vector<double> a, g, x;  // [window start][other two axes]
    };
    auto differences = [&](int P) {
        Differences d{std::vector<double>((na_ - P) * static_cast<std::size_t>(ng_) * nx_),
                      std::vector<double>((ng_ - P) * static_cast<std::size_t>(na_) * nx_),
                      std::vector<double>((nx_ - P) * static_cast<std::size_t>(na_) * ng_)};
        const auto wa = divided_weights(ua, P), wg = divided_weights(g_, P), wx = divided_weights(ux, P);
        const std::size_t step_a = static_cast<std::size_t>(ng_) * nx_, step_g = nx_;
        parallel_for(na_, [&](int i) {  // each i writes its own entries
            for (int j = 0; j < ng_; ++j)
                for (int k = 0; k < nx_; ++k) {
                    const double* f0 = &f_[index(i, j, k, ng_, nx_)];
                    double ea = 0.0, eg = 0.0, ex = 0.0;
                    for (int m = 0; m <= P; ++m) {
                        if (i + P < na_) ea += wa[i][m] * f0[m * step_a];
                        if (j + P < ng_) eg += wg[j][m] * f0[m * step_g];
                        if (k + P < nx_) ex += wx[k][m] * f0[m];
                    }
                    if (i + P < na_) d.a[index(i, j, k, ng_, nx_)] = std::abs(ea);
                    if (j + P < ng_) d.g[index(j, i, k, na_, nx_)] = std::abs(eg);
                    if (k + P < nx_) d.x[index(k, i, j, na_, ng_)] = std::abs(ex);
                }
        });
        block_max(d.a, na_ - P, ng_, nx_, P);
        block_max(d.g, ng_ - P, na_, nx_, P);
        block_max(d.x, nx_ - P, na_, ng_, P);
        return d;
    };
    const Differences d4 = differences(4), d6 = differences(6);
    // max |prod (v - x_m)| over each cell of each axis, for its P-knot window (depends on the cell alone)
    struct Nodal {
        std::vector<double> a, g, x;
    };
    auto nodal = [&](int P) {
        Nodal m{std::vector<double>(na_ - 1), std::vector<double>(ng_ - 1), std::vector<double>(nx_ - 1)};
        for (int c = 0; c < na_ - 1; ++c) m.a[c] = nodal_max(&ua[window(c, na_, P)], P, c, c + 1);
        for (int c = 0; c < ng_ - 1; ++c) m.g[c] = nodal_max(&g_[window(c, ng_, P)], P, g_[c], g_[c + 1]);
        for (int c = 0; c < nx_ - 1; ++c) m.x[c] = nodal_max(&ux[window(c, nx_, P)], P, c, c + 1);
        return m;
    };
    const Nodal n4 = nodal(4), n6 = nodal(6);

    // Each cell's estimate per tier: error of P-point Lagrange <= |prod (v - x_m)| |f[x0..xP]| per axis (the windows of
    // P + 1 that hold the cell's P-knot stencil or overlap it by P, across the stencil's lines of the other axes),
    // summed over the axes and tripled (the Lebesgue constants of the other axes, the estimate's own slack).
    auto estimate = [&](const Differences& d, const Nodal& n, int P, int ca, int cg, int cx) {
        const int sa = window(ca, na_, P), sg = window(cg, ng_, P), sx = window(cx, nx_, P);
        double ea = 0.0, eg = 0.0, ex = 0.0;
        for (int s = std::max(sa - 1, 0); s <= std::min(sa, na_ - P - 1); ++s) ea = std::max(ea, d.a[index(s, sg, sx, ng_, nx_)]);
        for (int s = std::max(sg - 1, 0); s <= std::min(sg, ng_ - P - 1); ++s) eg = std::max(eg, d.g[index(s, sa, sx, na_, nx_)]);
        for (int s = std::max(sx - 1, 0); s <= std::min(sx, nx_ - P - 1); ++s) ex = std::max(ex, d.x[index(s, sa, sg, na_, ng_)]);
        return 3.0 * (n.a[ca] * ea + n.g[cg] * eg + n.x[cx] * ex);
    };
    const std::size_t cells = static_cast<std::size_t>(na_ - 1) * (ng_ - 1) * (nx_ - 1);
    std::vector<std::uint8_t> tier_of(cells, 0);
    std::vector<double> worst_a(na_ - 1, 0.0), worst_g1_a(na_ - 1, 0.0);  // per ca, reduced below
    parallel_for(na_ - 1, [&](int ca) {
        for (int cg = 0; cg < ng_ - 1; ++cg)
            for (int cx = 0; cx < nx_ - 1; ++cx) {
                // |dG1| = |dLambda| / ((1 + Lambda)(1 + Lambda')) <= rel Lambda / (1 + Lambda)^2 = rel h(ln Lambda): h's
                // largest value on the cell, from its 8 corner knots (ln Lambda = ln(mu Lambda) - ln mu), their range
                // widened by 0.1
                double lo_l = INFINITY, hi_l = -INFINITY;
                for (int i = ca; i <= ca + 1; ++i)
                    for (int j = cg; j <= cg + 1; ++j)
                        for (int k = cx; k <= cx + 1; ++k) {
                            const double l = ln_mu_Lambda[index(i, j, k, ng_, nx_)] - (xi_lo_ + h_xi * k) - (a0_ + h_a * i);
                            lo_l = std::min(lo_l, l - 0.1), hi_l = std::max(hi_l, l + 0.1);
                        }
                auto h = [](double l) { return l > 0 ? std::exp(-l) / ((1.0 + std::exp(-l)) * (1.0 + std::exp(-l)))
                                                     : std::exp(l) / ((1.0 + std::exp(l)) * (1.0 + std::exp(l))); };
                const double hmax = lo_l <= 0.0 && hi_l >= 0.0 ? 0.25 : std::max(h(lo_l), h(hi_l));
                const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + cg) * (nx_ - 1) + cx;
                for (int P : {4, 6}) {
                    const double est = P == 4 ? estimate(d4, n4, 4, ca, cg, cx) : estimate(d6, n6, 6, ca, cg, cx);
                    if (est <= tolerance && est * hmax <= G1_tolerance) {
                        tier_of[cell] = static_cast<std::uint8_t>(P);
                        worst_a[ca] = std::max(worst_a[ca], est);
                        worst_g1_a[ca] = std::max(worst_g1_a[ca], est * hmax);
                        break;
                    }
                }
            }
    });
    ok4_.assign((cells + 63) / 64, 0);
    ok6_.assign((cells + 63) / 64, 0);
    std::size_t cells4 = 0, cells6 = 0;
    for (std::size_t cell = 0; cell < cells; ++cell) {
        if (tier_of[cell] == 4) ok4_[cell >> 6] |= std::uint64_t{1} << (cell & 63), ++cells4;
        if (tier_of[cell] == 6) ok6_[cell >> 6] |= std::uint64_t{1} << (cell & 63), ++cells6;
    }
    const double worst_ok = *std::max_element(worst_a.begin(), worst_a.end());
    const double worst_ok_g1 = *std::max_element(worst_g1_a.begin(), worst_g1_a.end());
    coverage4_ = static_cast<double>(cells4) / static_cast<double>(cells);
    coverage6_ = static_cast<double>(cells6) / static_cast<double>(cells);

    // The asymptotes' bounds. Below: R(mu_lo) <= (g(mu_1) - g(mu_lo)) / (mu_1/mu_lo - 1), g = mu Lambda + mu/2
    // (lambda_table.hpp), relative to mu Lambda. Above: the secant slope of the last interval against -1.
    auto lml = [&](int i, int j, int k) { return ln_mu_Lambda[index(i, j, k, ng_, nx_)]; };
    double lo_bound = 0.0, hi_bound = 0.0;
    for (int i = 0; i < na_; ++i)
        for (int j = 0; j < ng_; ++j) {
            const double al = alpha_of(i), m0 = al * std::exp(xi_lo_), m1 = al * std::exp(xi_lo_ + h_xi);
            const double g0 = std::exp(lml(i, j, 0)) + 0.5 * m0, g1 = std::exp(lml(i, j, 1)) + 0.5 * m1;
            lo_bound = std::max(lo_bound, std::max(0.0, g1 - g0) / std::expm1(h_xi) / std::exp(lml(i, j, 0)));
            const double s = (lml(i, j, nx_ - 1) - lml(i, j, nx_ - 2)) / h_xi;
            hi_bound = std::max(hi_bound, std::abs(s + 1.0));
        }
    const double asymptotes = std::max(lo_bound, hi_bound);
    error_bound_ = std::max(worst_ok, 1e-10) + asymptotes;
    G1_error_bound_ = std::max(worst_ok_g1, 1e-10) + asymptotes / 4;
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void require_gtr_family_domain(double alpha, double gamma) {
    require(alpha >= GtrFamily::alpha_min && alpha <= 1.0, "family: alpha", "in [1e-4, 1]", alpha);
    require(gamma >= 0.0 && gamma <= GtrFamily::gamma_max, "family: gamma", "in [0, 20]", gamma);
}

double Lambda_gtr_family(double alpha, double gamma, double mu, Downward downward) {
    require_gtr_family_domain(alpha, gamma);
    const GtrFamily& t = GtrFamily::get();
    return Lambda_at(mu, downward, [&](double m) { return t.Lambda_up(alpha, gamma, m); });
}

double G1_gtr_family(double alpha, double gamma, double mu) {
    require_gtr_family_domain(alpha, gamma);
    const GtrFamily& t = GtrFamily::get();
    return 1.0 / (1.0 + Lambda_of_abs(mu, [&](double m) { return t.Lambda_up(alpha, gamma, m); }));
}

}  // namespace smithlab
