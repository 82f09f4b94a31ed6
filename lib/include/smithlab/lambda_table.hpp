/// @file
/// smithlab/lambda_table.hpp -- a fast Lambda for one NDF at every mu, tabulated once from an exact route.
///
/// With x = ln mu, the table holds f(x) = ln(mu Lambda(mu)) (docs/math.md, "The tabulated Lambda") in three
/// pieces; none calls the exact route, allocates or throws after construction (read-only: any number of threads):
///   mu < mu_lo: the two-term asymptote. From Lambda = (1/mu) int_mu^inf (q - mu) P2(q) dq (Walter 2007 eq. 48) and
///     P(q > 0) = 1/2, mu Lambda = c0 - mu/2 + R(mu) exactly, with c0 = E[q+] (the mean positive slope) and
///     R(mu) = int_0^mu (mu - q) P2(q) dq >= 0. The table answers (g_lo - mu/2)/mu with g_lo = mu_lo Lambda(mu_lo) +
///     mu_lo/2 = c0 + R(mu_lo), in error by R(mu_lo) - R(mu), in [0, R(mu_lo)]. R(mu)/mu does not decrease for any
///     P2 >= 0, so R(mu_lo) <= (g(e^h mu_lo) - g(mu_lo)) / (e^h - 1), g = mu Lambda + mu/2: a bound from two knots
///     h = 0.5 apart, with no assumption on the law. mu_lo is the first knot, stepping down from mu_min, where it
///     bounds the relative error by tolerance/4.
///   [mu_lo, mu_hi]: a cubic spline of f on a uniform grid in x, its end second derivatives from the knots (one-sided,
///     O(h^3)), refined by halving the step until (5/384) max |Delta^4 f| (the spline bound (5/384) h^4 max |f''''|,
///     de Boor, "A Practical Guide to Splines", ch. V) is below the tolerance. An evaluation: a log, a cubic, an exp.
///   mu > mu_hi: f continued linearly with the spline's end slope s (Lambda ~ C mu^(s-1)): exact for a power tail
///     P22 ~ r^-(2+2k), Lambda ~ C mu^-2k (every GTR and GGX: k = 1; Blinn-Phong: k = 1 + n/2). mu_hi is the first
///     knot, stepping up from mu_max, where mu Lambda is below 1e-5 of its limit c0 (past the slope scale: a flat f at
///     mu_max, GGX alpha = 1e50, is no tail) and the secant slopes of f have settled: if the slope converges at least
///     like 1/mu (GTR, GGX, Blinn: 1/mu^2), the continuation's error is then below tolerance/4 wherever
///     Lambda >= DBL_MIN. A second slope scale beyond mu_max that leaves no trace in the slope there is not seen
///     (GTR's, at 1 and sqrt(gamma), are within the default). Where Lambda drops below 1e-290 first (a tail like
///     Beckmann's exp(-mu^2/alpha^2)), mu_hi is that point (to 1e-6 in ln mu), and beyond it the table answers a value
///     in [0, 1e-290] that reaches 0 (the truth is < 1e-290 there: Lambda decreases).
/// mu = 0 gives +inf, mu = +inf gives 0, and NaN or mu < 0 give NaN: the table is Lambda for mu >= 0 (G1 takes |mu|;
/// downward directions are the caller's convention, smith.hpp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "smithlab/ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

/// How a LambdaTable is built: the range its spline must cover, its tolerance, and the exact route of its knots.
struct LambdaTableOptions {
    /// @{
    double mu_min = 1e-5;  ///< the spline covers at least [mu_min, mu_max], less where Lambda drops below 1e-290
    double mu_max = 1e5;
    /// @}
    double tolerance = 1e-6;   ///< on the relative error of Lambda, as estimated (measured: ~5x below)
    LambdaOptions exact = {};  ///< the route the knots are computed by
};

/// Lambda of one NDF at every mu >= 0, tabulated once from an exact route in three pieces (the file comment).
class LambdaTable {
public:
    /// exact(mu) is Lambda at mu > 0; it is called only here. input_error on bad options, on a Lambda that is negative,
    /// NaN or inf at a knot (it names mu), where exact() refuses a mu the table needs (before its asymptotes hold),
    /// and when no step down to 2^-13 meets the tolerance.
    LambdaTable(const std::function<double(double)>& exact, const LambdaTableOptions& opts);

    /// Lambda(mu) for mu >= 0: the asymptote below mu_lo, the spline on [mu_lo, mu_hi], the power tail beyond; NaN for
    /// mu < 0 or NaN.
    double Lambda(double mu) const {
        const double x = std::log(mu);
        if (x >= x_lo_ && x <= x_hi_) {
            const double t = (x - x_lo_) * inv_h_;
            const std::size_t i = std::min(static_cast<std::size_t>(t), coef_.size() - 1);
            const double u = t - static_cast<double>(i);
            const std::array<double, 4>& c = coef_[i];
            return std::exp(((c[3] * u + c[2]) * u + c[1]) * u + c[0] - x);
        }
        if (x < x_lo_) return Lambda_grazing({g_lo_, 0.0}, mu);                   // mu = 0: +inf
        if (x > x_hi_) return std::exp(ln_Lambda_hi_ + slope_hi_ * (x - x_hi_));  // mu = +inf: 0
        return x;                                                                 // NaN, mu < 0
    }
    /// G1 = 1 / (1 + Lambda(|mu|)) (Walter 2007 eq. 44: G1 takes |mu|).
    double G1(double mu) const { return 1.0 / (1.0 + Lambda(std::abs(mu))); }

    /// @{
    double mu_min() const { return std::exp(x_lo_); }  ///< the spline's range, [mu_lo, mu_hi]
    double mu_max() const { return std::exp(x_hi_); }
    /// @}
    double step() const { return 1.0 / inv_h_; }  ///< in ln mu
    /// The number of knots of the spline.
    std::size_t knots() const { return coef_.size() + 1; }
    bool underflows() const { return underflows_; }            ///< beyond mu_max(), Lambda < 1e-290
    double error_estimate() const { return error_estimate_; }  ///< relative, of Lambda, the worst of the three pieces

private:
    double x_lo_ = 0.0, x_hi_ = 0.0, inv_h_ = 1.0;
    double g_lo_ = 0.0;                            ///< c0 + R(mu_lo)
    double ln_Lambda_hi_ = 0.0, slope_hi_ = -1.0;  ///< ln Lambda at mu_hi, and its slope in ln mu beyond
    bool underflows_ = false;
    double error_estimate_ = 0.0;
    std::vector<std::array<double, 4>> coef_;  ///< per interval, in u = (x - x_i)/h in [0, 1]
};

/// The table of `ndf`'s Lambda, its knots by smithlab::Lambda with opts.exact (the NDF's own quadrature backend where
/// it names one).
template <Ndf N>
LambdaTable tabulate_Lambda(const N& ndf, const LambdaTableOptions& opts = {}) {
    LambdaOptions e = opts.exact;
    // An NDF whose slope density is only piecewise smooth (a tabulated D: tabulated.hpp) names the quadrature its
    // integrals need: Boost's tanh-sinh, made for analytic integrands, crawls and misses on its kinks.
    if constexpr (requires { ndf.quadrature_backend(); })
        if (const std::optional<Backend> b = ndf.quadrature_backend()) e.backend = *b;
    return LambdaTable([&ndf, e](double mu) { return smithlab::Lambda(ndf, mu, e); }, opts);
}

}  // namespace smithlab
