// smithlab/gtr/family.hpp -- Lambda and G1 of every GTR at once: one table over (alpha, gamma, mu), built once at
// first use (a function-local static), read-only afterwards and shared by every material and thread (issue 14).
//
// Domain: alpha in [1e-4, 1], gamma in [0, 20], any mu. The table holds f = ln(mu Lambda) (Lambda: Walter 2007
// eq. 48, the reduced 1D form of smith.hpp) on a tensor grid in
//     a = ln alpha  (63 uniform knots),   gamma  (123 knots, piecewise uniform, densest on [0.8, 2.2] where Lambda
//     changes regime),   xi = ln(mu / alpha)  (201 uniform knots on [xi_lo, xi_hi]),
// and interpolates it with the 4-point Lagrange rule on each axis (64 knots; windows shifted inward at the edges).
// Its knots are computed at first use by strips (family.cpp): every gamma at once at one (alpha, mu), by the
// trapezoid rule in u = acosh(r/mu) (the integrand of lambda_fixed.hpp). The exact route, where the table does not
// resolve, is the closed form at integer gamma (closed_forms.hpp), else the fixed-rule 1D
// quadrature (lambda_fixed.hpp, relative 1e-11). Outside [xi_lo, xi_hi] the two asymptotes of lambda_table.hpp:
//   xi < xi_lo: mu Lambda = g_lo - mu/2, g_lo = mu_lo Lambda(mu_lo) + mu_lo/2 (Walter eq. 48 with P(q > 0) = 1/2;
//               in error by R(mu_lo) - R(mu) in [0, R(mu_lo)], R bounded from two knots as in lambda_table.hpp);
//   xi > xi_hi: Lambda ~ C mu^-2 (every GTR has a P22 ~ r^-4 tail: t -> alpha^2 as r -> inf, gtr.hpp), f continued
//               with slope -1.
// Error: each cell's interpolation error is estimated at build from the fourth divided differences along each
// axis (error of 4-point Lagrange <= max|prod (x - x_m)| / 24 max|f''''|), summed over the axes and tripled. A cell
// whose estimate exceeds `tolerance` (relative, Lambda) or `G1_tolerance` (absolute, G1) is not interpolated: there
// the evaluator calls the exact route (microseconds).
// The stated bounds (error_bound(), G1_error_bound()) thus hold everywhere; tested against independent references in
// tests/test_family.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

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
    // Lambda_gtr_family for the checked call). No allocation, exception or virtual call on the interpolated path.
    double Lambda_up(double alpha, double gamma, double mu) const {
        const double a = std::log(alpha), xi = std::log(mu / alpha);
        // a: uniform knots a0 + i h_a
        const double ta = (a - a0_) * inv_ha_;
        const int ca = std::clamp(static_cast<int>(ta), 0, na_ - 2);
        const int sa = std::clamp(ca - 1, 0, na_ - 4);
        std::array<double, 4> wa = uniform_weights(ta - sa);
        // gamma: non-uniform knots, a lookup table on a 0.01 grid finds the cell
        const int cg = gamma_cell(gamma);
        const int sg = std::clamp(cg - 1, 0, ng_ - 4);
        std::array<double, 4> wg = gamma_weights(sg, gamma);
        // xi: uniform, clamped to the tabulated range
        const double xc = std::clamp(xi, xi_lo_, xi_hi_);
        const double tx = (xc - xi_lo_) * inv_hx_;
        const int cx = std::clamp(static_cast<int>(tx), 0, nx_ - 2);
        const int sx = std::clamp(cx - 1, 0, nx_ - 4);
        std::array<double, 4> wx = uniform_weights(tx - sx);
        double f;
        const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + cg) * (nx_ - 1) + cx;
        if ((ok_[cell >> 6] >> (cell & 63)) & 1u) {
            f = 0.0;
            for (int i = 0; i < 4; ++i) {
                double fi = 0.0;
                for (int j = 0; j < 4; ++j) {
                    const double* p = &f_[(static_cast<std::size_t>(sa + i) * ng_ + (sg + j)) * nx_ + sx];
                    fi += wg[j] * (((wx[0] * p[0] + wx[1] * p[1]) + wx[2] * p[2]) + wx[3] * p[3]);
                }
                f += wa[i] * fi;
            }
        } else {
            f = exact_f(alpha, gamma, xc);  // a cell the table does not resolve to `tolerance`
        }
        if (xi < xi_lo_) return (std::exp(f) + 0.5 * alpha * mu_lo_rel_) / mu - 0.5;  // mu = 0: +inf
        if (xi > xi_hi_) return std::exp(f - (xi - xi_hi_)) / mu;                     // mu = inf: 0
        return std::exp(f) / mu;
    }
    double G1_up(double alpha, double gamma, double mu) const { return 1.0 / (1.0 + Lambda_up(alpha, gamma, mu)); }
    // Whether Lambda_up interpolates at this point (else it takes the exact route).
    bool interpolated(double alpha, double gamma, double mu) const {
        const int ca = std::clamp(static_cast<int>((std::log(alpha) - a0_) * inv_ha_), 0, na_ - 2);
        const double xc = std::clamp(std::log(mu / alpha), xi_lo_, xi_hi_);
        const int cx = std::clamp(static_cast<int>((xc - xi_lo_) * inv_hx_), 0, nx_ - 2);
        const std::size_t cell = (static_cast<std::size_t>(ca) * (ng_ - 1) + gamma_cell(gamma)) * (nx_ - 1) + cx;
        return (ok_[cell >> 6] >> (cell & 63)) & 1u;
    }

    // The stated bound on the relative error of Lambda, anywhere in the domain (the worst cell estimate, the
    // asymptotes' bounds, and the exact route's 1e-10 where a cell is not interpolated).
    double error_bound() const { return error_bound_; }
    double G1_error_bound() const { return G1_error_bound_; }  // the same on |dG1|
    double coverage() const { return coverage_; }          // fraction of cells interpolated
    double build_seconds() const { return build_seconds_; }
    std::size_t knots() const { return f_.size(); }

    // ln(mu Lambda) by the exact route at xi = ln(mu / alpha) (the knots' route).
    static double exact_f(double alpha, double gamma, double xi);

private:
    GtrFamily();
    static std::array<double, 4> uniform_weights(double v) {  // Lagrange on nodes 0, 1, 2, 3, v in [0, 3]
        const double v1 = v - 1.0, v2 = v - 2.0, v3 = v - 3.0;
        return {-(v1 * v2 * v3) * (1.0 / 6.0), v * v2 * v3 * 0.5, -(v * v1 * v3) * 0.5, v * v1 * v2 * (1.0 / 6.0)};
    }
    int gamma_cell(double gamma) const {
        int j = gamma_lut_[static_cast<std::size_t>(gamma * 100.0)];
        while (j < ng_ - 2 && gamma >= g_[j + 1]) ++j;
        return j;
    }
    std::array<double, 4> gamma_weights(int s, double gamma) const {
        const double d0 = gamma - g_[s], d1 = gamma - g_[s + 1], d2 = gamma - g_[s + 2], d3 = gamma - g_[s + 3];
        const std::array<double, 4>& c = g_inv_den_[s];
        return {d1 * d2 * d3 * c[0], d0 * d2 * d3 * c[1], d0 * d1 * d3 * c[2], d0 * d1 * d2 * c[3]};
    }

    int na_ = 0, ng_ = 0, nx_ = 0;
    double a0_ = 0.0, inv_ha_ = 1.0, xi_lo_ = 0.0, xi_hi_ = 0.0, inv_hx_ = 1.0, mu_lo_rel_ = 0.0;
    std::vector<double> g_;                            // gamma knots
    std::vector<std::array<double, 4>> g_inv_den_;     // 1 / prod_{m != k} (g_k - g_m), per window start
    std::vector<std::uint16_t> gamma_lut_;             // cell of gamma = k / 100
    std::vector<double> f_;                            // ln(mu Lambda) at [a][gamma][xi]
    std::vector<std::uint64_t> ok_;                    // one bit per cell: interpolated
    double error_bound_ = 0.0, G1_error_bound_ = 0.0, coverage_ = 0.0, build_seconds_ = 0.0;
};

// Checked calls: input_error naming alpha (not in [1e-4, 1], NaN) or gamma (not in [0, 20], NaN); mu as everywhere
// (smith.hpp): NaN refused, 0 gives Lambda = inf, inf gives 0, mu < 0 follows the downward convention; G1 takes |mu|.
double Lambda_gtr_family(double alpha, double gamma, double mu, Downward downward = Downward::smith);
double G1_gtr_family(double alpha, double gamma, double mu);
void require_gtr_family_domain(double alpha, double gamma);

}  // namespace smithlab
