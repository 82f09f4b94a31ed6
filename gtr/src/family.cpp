// The GTR family table (family.hpp): its grid, its knots from the exact routes, and its per-cell error estimates.
#include "smithlab/gtr/family.hpp"

#include <chrono>
#include <cstddef>
#include <thread>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/gtr.hpp"

namespace smithlab {

namespace {

// The grid. a = ln alpha: 63 uniform knots on [ln 1e-4, 0], step 0.148, as fine as xi's (Lambda's features at mu ~ 1
// and sqrt(gamma) move diagonally in (a, xi)). xi = ln(mu/alpha): uniform on [-9, 19], step 0.14; below,
// R(mu_lo) / (mu_lo Lambda) ~ (mu_lo / alpha)^2 gamma < 1e-6; above, mu >= 1.8e4 alpha, past every GTR's second slope
// scale (1 and sqrt(gamma), gtr.hpp), where Lambda ~ C mu^-2.
constexpr int n_a = 63;
constexpr double xi_lo = -9.0, xi_hi = 19.0, h_xi = 0.14;

std::vector<double> gamma_knots() {  // piecewise uniform, so that strip() steps t^gamma by products
    std::vector<double> g;
    for (int i = 0; i < 16; ++i) g.push_back(0.05 * i);          // 0 .. 0.75
    for (int i = 0; i <= 56; ++i) g.push_back(0.8 + 0.025 * i);  // 0.8 .. 2.2: the regime changes at 1 and 1.5
    for (int i = 1; i <= 18; ++i) g.push_back(2.2 + 0.1 * i);   // 2.3 .. 4
    for (int i = 1; i <= 32; ++i) g.push_back(4.0 + 0.5 * i);   // 4.5 .. 20
    for (double& x : g) x = std::round(x * 1e12) / 1e12;  // 0.1 * 3 is 0.30000000000000004: keep integers exact
    return g;
}

// Lambda at mu for every gamma knot at once (the knots' route). The reduced integral in u = acosh(r/mu), as in
// lambda_fixed.hpp: Lambda = 2 int_0^inf f(r^2) r^2 H(u) du, H(u) = sinh u (sinh u - gd u) / cosh u, gd u =
// atan(sinh u), with GTR's f = K t^(gamma - 2) w^2 (gtr.hpp). The integrand is even in u and analytic in the strip
// |Im u| < pi/2 (its nearest singularities, f's pole r^2 = -alpha^2 and gd's, are pi/2 off the real axis, wherever
// mu is: lambda_fixed.hpp), so the trapezoid rule converges like exp(-2 pi d / h) (Trefethen and Weideman 2014,
// "The exponentially convergent trapezoidal rule", thm 5.1): h = 1/8 with d = pi/4 leaves ~1e-17 x the integrand's
// growth there (<= 2^(gamma/2)); measured <= 3.3e-10 relative against the adaptive route (tanh-sinh, 1e-13) at 300
// random (alpha, mu) x 29 gamma. Every geometric factor and ln t are shared by all gamma; t^(gamma - 2) is stepped
// from knot to knot by products (two exps per run of equal steps), e^u by products too.
void strip(double alpha, double mu, const std::vector<double>& g, const std::vector<double>& K, double* out,
           std::ptrdiff_t stride) {
    const int ng = static_cast<int>(g.size());
    constexpr double h = 0.125;
    // past the last slope scale (sqrt(20) < 4.5) by 32: the r^-4 tail leaves e^-32 of Lambda beyond
    const int n = static_cast<int>((std::max(0.0, std::log(9.0 / mu)) + 32.0) / h) + 1;
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
    const double a2 = alpha * alpha, om = (1.0 - alpha) * (1.0 + alpha), eh = std::exp(h);
    double E = 1.0;  // e^u, stepped (n <= ~500 products: a relative drift below 1e-13)
    for (int k = 1; k <= n; ++k) {
        E *= eh;
        const double s = 0.5 * (E - 1.0 / E), c = 0.5 * (E + 1.0 / E);
        // sinh u - gd u = s - atan s, its series below s = 0.1 (no cancellation)
        const double s2 = s * s;
        const double smg = s < 0.1 ? s * s2 * (1.0 / 3 - s2 * (1.0 / 5 - s2 * (1.0 / 7 - s2 / 9))) : s - std::atan(s);
        const double r2 = mu * mu * c * c, den = r2 + a2, w = a2 / den;
        const double t = a2 * ((1.0 + r2) / den);  // in [alpha^2, 1]; ln t from 1 - t = (1 - alpha^2) r^2 / den near 1
        const double lt = t < 0.5 ? std::log(t) : std::log1p(-om * (r2 / den));
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

// max over v in [c, c+1] of |prod_m (v - x_m)| for the window's 4 knots x_m (sampled: the estimate's constant).
double nodal_max(const double* x, double lo, double hi) {
    double m = 0.0;
    for (int k = 0; k <= 32; ++k) {
        const double v = lo + (hi - lo) * k / 32.0;
        m = std::max(m, std::abs((v - x[0]) * (v - x[1]) * (v - x[2]) * (v - x[3])));
    }
    return m;
}

// |f[x0..x4]|, the fourth divided difference (= f''''/24 at some point of [x0, x4]).
double divided4(const double* x, const double* f) {
    double d[5];
    for (int i = 0; i < 5; ++i) d[i] = f[i];
    for (int k = 1; k <= 4; ++k)
        for (int i = 0; i + k <= 4; ++i) d[i] = (d[i + 1] - d[i]) / (x[i + k] - x[i]);
    return std::abs(d[0]);
}

// fn(i) for i in [0, n), interleaved over every core.
template <class F>
void parallel_for(int n, const F& fn) {
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int th = 0; th < threads; ++th)
        pool.emplace_back([&, th] {
            for (int i = th; i < n; i += threads) fn(i);
        });
    for (std::thread& t : pool) t.join();
}

}  // namespace

double GtrFamily::exact_f(double alpha, double gamma, double xi) {
    const double mu = alpha * std::exp(xi);
    const Gtr n = gtr(alpha, gamma);
    const double L = gtr_has_closed_form(gamma) ? n.Lambda(mu) : Lambda_fixed(n, mu, {Backend::gsl, 1e-11});
    return std::log(mu * L);
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
    for (int s = 0; s + 3 < ng_; ++s) {
        std::array<double, 4> c{};
        for (int k = 0; k < 4; ++k) {
            double den = 1.0;
            for (int m = 0; m < 4; ++m)
                if (m != k) den *= g_[s + k] - g_[s + m];
            c[k] = 1.0 / den;
        }
        g_inv_den_.push_back(c);
    }
    for (int k = 0; k <= 100 * static_cast<int>(gamma_max); ++k) {
        const double gm = k / 100.0;
        int j = 0;
        while (j < ng_ - 2 && g_[j + 1] <= gm) ++j;
        gamma_lut_.push_back(static_cast<std::uint16_t>(j));
    }

    // The knots: one strip of every gamma per (alpha, xi), on every core.
    auto alpha_of = [&](int i) { return i == na_ - 1 ? 1.0 : std::exp(a0_ + h_a * i); };
    f_.assign(static_cast<std::size_t>(na_) * ng_ * nx_, 0.0);
    const int strips = na_ * nx_;
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::thread> pool;
    for (unsigned th = 0; th < threads; ++th)
        pool.emplace_back([&, th] {
            std::vector<double> K(ng_);
            int last_i = -1;
            for (int r = static_cast<int>(th); r < strips; r += static_cast<int>(threads)) {
                const int i = r / nx_, k = r % nx_;
                const double alpha = alpha_of(i), xi = xi_lo_ + h_xi * k, mu = alpha * std::exp(xi);
                if (i != last_i)
                    for (int j = 0; j < ng_; ++j) K[j] = gtr(alpha, g_[j]).K;
                last_i = i;
                double* col = &f_[static_cast<std::size_t>(i) * ng_ * nx_ + k];
                strip(alpha, mu, g_, K, col, nx_);
                for (int j = 0; j < ng_; ++j) {
                    double& v = col[static_cast<std::size_t>(j) * nx_];
                    v = std::log(mu * v);
                }
            }
        });
    for (std::thread& th : pool) th.join();

    // Per-axis fourth divided differences at every 5-knot window, then each cell's estimate.
    auto at = [&](int i, int j, int k) { return f_[(static_cast<std::size_t>(i) * ng_ + j) * nx_ + k]; };
    std::vector<double> ua(na_), ux(nx_);
    for (int i = 0; i < na_; ++i) ua[i] = i;
    for (int k = 0; k < nx_; ++k) ux[k] = k;
    auto index = [](int s, int j, int k, int nj, int nk) { return (static_cast<std::size_t>(s) * nj + j) * nk + k; };
    std::vector<double> Da((na_ - 4) * static_cast<std::size_t>(ng_) * nx_), Dg((ng_ - 4) * static_cast<std::size_t>(na_) * nx_),
        Dx((nx_ - 4) * static_cast<std::size_t>(na_) * ng_);
    parallel_for(na_, [&](int i) {  // each i writes its own entries
        for (int j = 0; j < ng_; ++j)
            for (int k = 0; k < nx_; ++k) {
                double v[5];
                if (i + 4 < na_) {
                    for (int m = 0; m < 5; ++m) v[m] = at(i + m, j, k);
                    Da[index(i, j, k, ng_, nx_)] = divided4(&ua[i], v);
                }
                if (j + 4 < ng_) {
                    for (int m = 0; m < 5; ++m) v[m] = at(i, j + m, k);
                    Dg[index(j, i, k, na_, nx_)] = divided4(&g_[j], v);
                }
                if (k + 4 < nx_) {
                    for (int m = 0; m < 5; ++m) v[m] = at(i, j, k + m);
                    Dx[index(k, i, j, na_, ng_)] = divided4(&ux[k], v);
                }
            }
    });
    auto window = [](int c, int n) { return std::clamp(c - 1, 0, n - 4); };
    // the windows of 5 that hold the cell's 4-knot stencil s..s+3, or overlap it by 4
    auto windows5 = [](int s, int n, int& lo, int& hi) {
        lo = std::max(s - 1, 0);
        hi = std::min(s, n - 5);
    };
    std::vector<double> Pa(na_ - 1), Pg(ng_ - 1), Px(nx_ - 1);
    for (int c = 0; c < na_ - 1; ++c) Pa[c] = nodal_max(&ua[window(c, na_)], c, c + 1);
    for (int c = 0; c < ng_ - 1; ++c) Pg[c] = nodal_max(&g_[window(c, ng_)], g_[c], g_[c + 1]);
    for (int c = 0; c < nx_ - 1; ++c) Px[c] = nodal_max(&ux[window(c, nx_)], c, c + 1);
    const std::size_t cells = static_cast<std::size_t>(na_ - 1) * (ng_ - 1) * (nx_ - 1);
    std::vector<std::uint8_t> ok_cell(cells, 0);
    std::vector<double> worst_a(na_ - 1, 0.0), worst_g1_a(na_ - 1, 0.0);  // per ca, reduced below
    parallel_for(na_ - 1, [&](int ca) {
        for (int cg = 0; cg < ng_ - 1; ++cg)
            for (int cx = 0; cx < nx_ - 1; ++cx) {
                const int sa = window(ca, na_), sg = window(cg, ng_), sx = window(cx, nx_);
                int lo, hi;
                double ea = 0.0, eg = 0.0, ex = 0.0;
                windows5(sa, na_, lo, hi);
                for (int s = lo; s <= hi; ++s)
                    for (int j = sg; j < sg + 4; ++j)
                        for (int k = sx; k < sx + 4; ++k) ea = std::max(ea, Da[index(s, j, k, ng_, nx_)]);
                windows5(sg, ng_, lo, hi);
                for (int s = lo; s <= hi; ++s)
                    for (int i = sa; i < sa + 4; ++i)
                        for (int k = sx; k < sx + 4; ++k) eg = std::max(eg, Dg[index(s, i, k, na_, nx_)]);
                windows5(sx, nx_, lo, hi);
                for (int s = lo; s <= hi; ++s)
                    for (int i = sa; i < sa + 4; ++i)
                        for (int j = sg; j < sg + 4; ++j) ex = std::max(ex, Dx[index(s, i, j, na_, ng_)]);
                // error of 4-point Lagrange: |prod (v - x_m)| |f''''| / 24 = |prod| |f[x0..x4]| (divided difference);
                // tensor product: the Lebesgue constants of the other axes (<= 1.6) and the estimate's own slack: x3
                // (measured against the adaptive route on 3000 random points: error / estimate <= 0.75 x 2 where the
                // estimate is below 1e-5; the estimate misses by 2.3x in unresolved cells near alpha = 0.85, all > 1e-4)
                const double est = 3.0 * (Pa[ca] * ea + Pg[cg] * eg + Px[cx] * ex);
                // |dG1| = |dLambda| / ((1 + Lambda)(1 + Lambda')) <= rel Lambda / (1 + Lambda)^2 = rel h(ln Lambda): h's
                // largest value on the cell, from its 8 corner knots (ln Lambda = f - ln mu), their range widened by 0.1
                double lo_l = INFINITY, hi_l = -INFINITY;
                for (int i = ca; i <= ca + 1; ++i)
                    for (int j = cg; j <= cg + 1; ++j)
                        for (int k = cx; k <= cx + 1; ++k) {
                            const double l = at(i, j, k) - (xi_lo_ + h_xi * k) - (a0_ + h_a * i);
                            lo_l = std::min(lo_l, l - 0.1), hi_l = std::max(hi_l, l + 0.1);
                        }
                auto h = [](double l) { return l > 0 ? std::exp(-l) / ((1.0 + std::exp(-l)) * (1.0 + std::exp(-l)))
                                                     : std::exp(l) / ((1.0 + std::exp(l)) * (1.0 + std::exp(l))); };
                const double hmax = lo_l <= 0.0 && hi_l >= 0.0 ? 0.25 : std::max(h(lo_l), h(hi_l));
                const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + cg) * (nx_ - 1) + cx;
                if (est <= tolerance && est * hmax <= G1_tolerance) {
                    ok_cell[cell] = 1;
                    worst_a[ca] = std::max(worst_a[ca], est);
                    worst_g1_a[ca] = std::max(worst_g1_a[ca], est * hmax);
                }
            }
    });
    ok_.assign((cells + 63) / 64, 0);
    std::size_t n_ok = 0;
    for (std::size_t cell = 0; cell < cells; ++cell)
        if (ok_cell[cell]) ok_[cell >> 6] |= std::uint64_t{1} << (cell & 63), ++n_ok;
    const double worst_ok = *std::max_element(worst_a.begin(), worst_a.end());
    const double worst_ok_g1 = *std::max_element(worst_g1_a.begin(), worst_g1_a.end());
    coverage_ = static_cast<double>(n_ok) / static_cast<double>(cells);

    // The asymptotes' bounds. Below: R(mu_lo) <= (g(mu_1) - g(mu_lo)) / (mu_1/mu_lo - 1), g = mu Lambda + mu/2
    // (lambda_table.hpp), relative to mu Lambda. Above: the secant slope of the last interval against -1.
    double lo_bound = 0.0, hi_bound = 0.0;
    for (int i = 0; i < na_; ++i)
        for (int j = 0; j < ng_; ++j) {
            const double al = alpha_of(i), m0 = al * std::exp(xi_lo_), m1 = al * std::exp(xi_lo_ + h_xi);
            const double g0 = std::exp(at(i, j, 0)) + 0.5 * m0, g1 = std::exp(at(i, j, 1)) + 0.5 * m1;
            lo_bound = std::max(lo_bound, std::max(0.0, g1 - g0) / std::expm1(h_xi) / std::exp(at(i, j, 0)));
            const double s = (at(i, j, nx_ - 1) - at(i, j, nx_ - 2)) / h_xi;
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
