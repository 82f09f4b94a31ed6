// smithlab/lambda_table.hpp -- a fast Lambda for one NDF, tabulated once from an exact route.
//
// Lambda(mu) spans 1/mu (mu -> 0: mu Lambda -> E[q+], the mean positive slope) to 1/mu^2 (mu -> inf, for tails
// P22 ~ r^-4 such as every GTR), with its features O(1) wide in ln mu wherever they sit (at mu ~ alpha, and at
// mu ~ 1 where a heavy GTR tail bends). So the table holds
//     f(x) = ln(mu Lambda(mu)),  x = ln mu,
// which is flat at the left end and of slope -1 at the right, as a natural cubic spline on a uniform grid in x,
// refined by halving the step until the interpolation error estimated from the fourth differences,
// (5/384) max |Delta^4 f| (the cubic spline bound (5/384) h^4 max |f''''|, de Boor, "A Practical Guide to Splines",
// ch. V), is below the tolerance. An error in f is the relative error of Lambda. An evaluation costs a log, a
// cubic and an exp. Outside [mu_min, mu_max] the table hands the call to the exact route it was built from; where
// Lambda underflows to 0 inside the range (Beckmann-like tails), the table stops short of it and does the same.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "smithlab/ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

struct LambdaTableOptions {
    double mu_min = 1e-5;
    double mu_max = 1e5;
    double tolerance = 1e-6;  // on the relative error of Lambda, as estimated (measured: 5x below)
    LambdaOptions exact = {};  // the route the knots (and calls outside the range) are computed by
};

class LambdaTable {
public:
    // exact(mu) must be Lambda at any mu (0, inf and mu < 0 included). input_error on bad options, on a Lambda
    // that is negative or not finite at a knot (it names mu), or when no step down to 2^-13 meets the tolerance.
    // Where Lambda underflows to 0 within a few knots of mu_min, the table is empty and exact() answers every call.
    LambdaTable(std::function<double(double)> exact, const LambdaTableOptions& opts);

    double Lambda(double mu) const {
        if (!(mu >= mu_min_ && mu <= mu_max_)) return exact_(mu);
        const double x = std::log(mu);
        const double t = (x - x0_) * inv_h_;
        const auto i = static_cast<std::size_t>(t);
        const double u = t - static_cast<double>(i);
        const std::array<double, 4>& c = coef_[i];
        return std::exp(((c[3] * u + c[2]) * u + c[1]) * u + c[0] - x);
    }
    double G1(double mu) const { return 1.0 / (1.0 + Lambda(std::abs(mu))); }

    double mu_min() const { return mu_min_; }
    double mu_max() const { return mu_max_; }                // below opts.mu_max where Lambda underflows
    double step() const { return 1.0 / inv_h_; }            // in ln mu
    std::size_t knots() const { return coef_.size() + 1; }
    double error_estimate() const { return error_estimate_; }  // relative, of Lambda

private:
    std::function<double(double)> exact_;
    double mu_min_, mu_max_, x0_ = 0.0, inv_h_ = 1.0, error_estimate_ = 0.0;
    std::vector<std::array<double, 4>> coef_;  // per interval, in u = (x - x_i)/h in [0, 1)
};

template <Ndf N>
LambdaTable tabulate_Lambda(const N& ndf, const LambdaTableOptions& opts = {}) {
    return LambdaTable([ndf, e = opts.exact](double mu) { return smithlab::Lambda(ndf, mu, e); }, opts);
}

}  // namespace smithlab
