// smithlab/gtr/family.hpp -- Lambda and G1 of every GTR at once: one table over (alpha, gamma, mu), built once at
// first use (a function-local static), read-only afterwards and shared by every material and thread (issue 14).
//
// Domain: alpha in [1e-4, 1], gamma in [0, 20], any mu. The table holds
//     g = ln(mu Lambda) - ln K - gamma ln t(mu)
// (Lambda: Walter 2007 eq. 48, the reduced 1D form of smith.hpp; K the normalization of gtr.hpp, whose gamma -> 1
// transition is 1/ln(1/alpha^2) wide; t(mu) = alpha^2 (1 + mu^2)/(alpha^2 + mu^2) the GTR t at slope mu, gamma ln t the
// Laplace leading term of P22's t^gamma, which carries Lambda's gamma-proportional fall: both known in closed form,
// subtracted at the knots and added back here) on a tensor grid in
//     a = ln alpha  (93 uniform knots, step 0.1),   gamma  (104 knots, piecewise uniform, the step ~ (gamma + 1/2) / 20:
//     ln(mu Lambda) goes like ln gamma),   xi = ln(mu / alpha)  (281 uniform knots, step 0.1, on [xi_lo, xi_hi]).
// Two tiers on the same knots: 4-point Lagrange on each axis (64 knots) where its error estimate passes, else 6-point
// (216 knots) where its estimate passes (windows shifted inward at the edges), else the exact route.
// Its knots are computed at first use by strips (family.cpp): every gamma at once at one (alpha, mu), by the
// trapezoid rule in u = acosh(r/mu) (the integrand of lambda_fixed.hpp). The exact route, where the table does not
// resolve, is the closed form at integer gamma (closed_forms.hpp), else the fixed-rule 1D
// quadrature (lambda_fixed.hpp, relative 1e-11). Outside [xi_lo, xi_hi] the two asymptotes of lambda_table.hpp:
//   xi < xi_lo: mu Lambda = g_lo - mu/2, g_lo = mu_lo Lambda(mu_lo) + mu_lo/2 (Walter eq. 48 with P(q > 0) = 1/2;
//               in error by R(mu_lo) - R(mu) in [0, R(mu_lo)], R bounded from two knots as in lambda_table.hpp);
//   xi > xi_hi: Lambda ~ C mu^-2 (every GTR has a P22 ~ r^-4 tail: t -> alpha^2 as r -> inf, gtr.hpp), ln(mu Lambda)
//               continued with slope -1.
// Error: each cell's interpolation error, per tier, is estimated at build from the fourth (sixth) divided differences
// along each axis (error of P-point Lagrange <= max|prod (x - x_m)| max|f[x0..xP]|), summed over the axes and
// tripled (measured: error / estimate <= 0.32 for both tiers). A tier whose estimate exceeds `tolerance` (relative,
// Lambda) or `G1_tolerance` (absolute, G1) is not used in that cell.
// The stated bounds (error_bound(), G1_error_bound()) thus hold everywhere; tested against independent references in
// tests/test_family.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "smithlab/gtr/gtr.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

class GtrFamily {
public:
    static constexpr double alpha_min = 1e-4;
    static constexpr double gamma_max = 20.0;
    // An interpolated cell's estimate is at most `tolerance` relative in Lambda and `G1_tolerance` in G1
    // (|dG1| <= rel Lambda / (1 + Lambda)^2: where Lambda is far from 1, G1 takes a larger relative error of Lambda).
    static constexpr double tolerance = 8e-6;
    static constexpr double G1_tolerance = 8e-7;

    // The one table, built at first use (thread-safe: C++11 static initialization).
    static const GtrFamily& get();

    // Lambda at finite mu > 0 for alpha in [1e-4, 1], gamma in [0, 20]: nothing is checked here (see
    // Lambda_gtr_family for the checked call). No allocation, exception or virtual call on the interpolated paths.
    double Lambda_up(double alpha, double gamma, double mu) const {
        const double a = std::log(alpha), xi = std::log(mu / alpha);
        const double xc = std::clamp(xi, xi_lo_, xi_hi_);
        const double ta = (a - a0_) * inv_ha_, tx = (xc - xi_lo_) * inv_hx_;
        const int ca = std::clamp(static_cast<int>(ta), 0, na_ - 2), cg = gamma_cell(gamma),
                  cx = std::clamp(static_cast<int>(tx), 0, nx_ - 2);
        const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + cg) * (nx_ - 1) + cx;
        double f;
        if (bit(ok4_, cell))
            f = interpolate<4>(ta, ca, gamma, cg, tx, cx) + known(alpha, gamma, alpha * std::exp(xc));
        else if (bit(ok6_, cell))
            f = interpolate<6>(ta, ca, gamma, cg, tx, cx) + known(alpha, gamma, alpha * std::exp(xc));
        else
            f = exact_f(alpha, gamma, xc);  // a cell neither tier resolves to `tolerance`
        if (xi < xi_lo_) return (std::exp(f) + 0.5 * alpha * mu_lo_rel_) / mu - 0.5;  // mu = 0: +inf
        if (xi > xi_hi_) return std::exp(f - (xi - xi_hi_)) / mu;                     // mu = inf: 0
        return std::exp(f) / mu;
    }
    double G1_up(double alpha, double gamma, double mu) const { return 1.0 / (1.0 + Lambda_up(alpha, gamma, mu)); }
    // Which route Lambda_up takes at this point: 4 or 6 (the interpolation tier), 0 (the exact route).
    int tier(double alpha, double gamma, double mu) const {
        const int ca = std::clamp(static_cast<int>((std::log(alpha) - a0_) * inv_ha_), 0, na_ - 2);
        const double xc = std::clamp(std::log(mu / alpha), xi_lo_, xi_hi_);
        const int cx = std::clamp(static_cast<int>((xc - xi_lo_) * inv_hx_), 0, nx_ - 2);
        const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + gamma_cell(gamma)) * (nx_ - 1) + cx;
        return bit(ok4_, cell) ? 4 : bit(ok6_, cell) ? 6 : 0;
    }

    // The stated bound on the relative error of Lambda, anywhere in the domain (the worst cell estimate, the
    // asymptotes' bounds, and the exact route's 1e-10 where a cell is not interpolated).
    double error_bound() const { return error_bound_; }
    double G1_error_bound() const { return G1_error_bound_; }  // the same on |dG1|
    // The fraction of cells that take tier 4, 6, or 0 (the exact route).
    double coverage(int tier) const {
        return tier == 4 ? coverage4_ : tier == 6 ? coverage6_ : 1.0 - coverage4_ - coverage6_;
    }
    double build_seconds() const { return build_seconds_; }
    std::size_t knots() const { return f_.size(); }

    // ln(mu Lambda) by the exact route at xi = ln(mu / alpha) (the knots' route).
    static double exact_f(double alpha, double gamma, double xi);
    // ln K + gamma ln t(mu), the part of ln(mu Lambda) the table does not hold (K: gtr_K).
    static double known(double alpha, double gamma, double mu) {
        return std::log(gtr_K(alpha, gamma)) + gamma * ln_t(alpha, mu * mu);
    }
    // ln t at slope r (r2 = r^2), t = alpha^2 (1 + r^2)/(alpha^2 + r^2) in [alpha^2, 1]: while t > 1/2 from
    // 1 - t = (1 - alpha^2) r^2 / (alpha^2 + r^2), which keeps the digits t would round away.
    static double ln_t(double alpha, double r2) {
        const double om = (1.0 - alpha) * (1.0 + alpha), den = alpha * alpha + r2;
        const double t = alpha * alpha * ((1.0 + r2) / den);
        return t < 0.5 ? std::log(t) : std::log1p(-om * (r2 / den));
    }

private:
    GtrFamily();
    static bool bit(const std::vector<std::uint64_t>& b, std::size_t i) { return (b[i >> 6] >> (i & 63)) & 1u; }
    // prod_{m != k} (v - x_m) for k < P, from prefix and suffix products (d_m = v - x_m)
    template <int P>
    static std::array<double, P> products_but_one(const std::array<double, P>& d) {
        std::array<double, P> w;
        double pre = 1.0;
        for (int k = 0; k < P; ++k) w[k] = pre, pre *= d[k];
        double suf = 1.0;
        for (int k = P - 1; k >= 0; --k) w[k] *= suf, suf *= d[k];
        return w;
    }
    // P-point Lagrange weights on uniform nodes 0 .. P-1 at v: prod_{m != k} (v - m) / prod_{m != k} (k - m)
    template <int P>
    static std::array<double, P> uniform_weights(double v) {
        static constexpr std::array<double, 6> c4 = {-1.0 / 6, 1.0 / 2, -1.0 / 2, 1.0 / 6}, c6 = {
            -1.0 / 120, 1.0 / 24, -1.0 / 12, 1.0 / 12, -1.0 / 24, 1.0 / 120};
        std::array<double, P> d;
        for (int m = 0; m < P; ++m) d[m] = v - m;
        std::array<double, P> w = products_but_one<P>(d);
        for (int k = 0; k < P; ++k) w[k] *= (P == 4 ? c4 : c6)[k];
        return w;
    }
    // The first knot of cell c's P-knot stencil on an axis of n knots (shifted inward at the edges): the evaluator's and
    // the build's estimates' (family.cpp) one rule.
    static int window(int c, int n, int P) { return std::clamp(c - (P / 2 - 1), 0, n - P); }
    int gamma_cell(double gamma) const {
        int j = gamma_lut_[static_cast<std::size_t>(gamma * 100.0)];
        while (j < ng_ - 2 && gamma >= g_[j + 1]) ++j;
        return j;
    }
    template <int P>
    std::array<double, P> gamma_weights(int s, double gamma) const {
        const double* inv_den = P == 4 ? &g_inv_den4_[s][0] : &g_inv_den6_[s][0];
        std::array<double, P> d;
        for (int m = 0; m < P; ++m) d[m] = gamma - g_[s + m];
        std::array<double, P> w = products_but_one<P>(d);
        for (int k = 0; k < P; ++k) w[k] *= inv_den[k];
        return w;
    }
    // The stored g at (ta, gamma, tx) (ta, tx: positions in knot steps) by P-point Lagrange on each axis.
    template <int P>
    double interpolate(double ta, int ca, double gamma, int cg, double tx, int cx) const {
        const int sa = window(ca, na_, P), sg = window(cg, ng_, P), sx = window(cx, nx_, P);
        const std::array<double, P> wa = uniform_weights<P>(ta - sa), wg = gamma_weights<P>(sg, gamma),
                                    wx = uniform_weights<P>(tx - sx);
        double f = 0.0;
        for (int i = 0; i < P; ++i) {
            double fi = 0.0;
            for (int j = 0; j < P; ++j) {
                const double* p = &f_[(static_cast<std::size_t>(sa + i) * ng_ + (sg + j)) * nx_ + sx];
                double row = 0.0;
                for (int k = 0; k < P; ++k) row += wx[k] * p[k];
                fi += wg[j] * row;
            }
            f += wa[i] * fi;
        }
        return f;
    }

    int na_ = 0, ng_ = 0, nx_ = 0;
    double a0_ = 0.0, inv_ha_ = 1.0, xi_lo_ = 0.0, xi_hi_ = 0.0, inv_hx_ = 1.0, mu_lo_rel_ = 0.0;
    std::vector<double> g_;                            // gamma knots
    // 1 / prod_{m != k} (g_k - g_m) per window start, 4- and 6-knot windows (the divided-difference weights)
    std::vector<std::array<double, 7>> g_inv_den4_, g_inv_den6_;
    std::vector<std::uint16_t> gamma_lut_;             // cell of gamma = k / 100
    std::vector<double> f_;                            // g = ln(mu Lambda) - known() at [a][gamma][xi]
    std::vector<std::uint64_t> ok4_, ok6_;             // one bit per cell: that tier is within the tolerances
    double error_bound_ = 0.0, G1_error_bound_ = 0.0, coverage4_ = 0.0, coverage6_ = 0.0, build_seconds_ = 0.0;
};

// Checked calls: input_error naming alpha (not in [1e-4, 1], NaN) or gamma (not in [0, 20], NaN); mu as everywhere
// (smith.hpp): NaN refused, 0 gives Lambda = inf, inf gives 0, mu < 0 follows the downward convention; G1 takes |mu|.
double Lambda_gtr_family(double alpha, double gamma, double mu, Downward downward = Downward::smith);
double G1_gtr_family(double alpha, double gamma, double mu);
void require_gtr_family_domain(double alpha, double gamma);

}  // namespace smithlab
