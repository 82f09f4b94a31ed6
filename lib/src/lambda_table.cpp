#include "smithlab/lambda_table.hpp"

#include <gsl/gsl_linalg.h>
#include <gsl/gsl_vector.h>

#include <algorithm>
#include <string>
#include <utility>

#include "smithlab/errors.hpp"

namespace smithlab {

namespace {

// Beyond the range, the grid runs on by this much in ln mu: the natural end condition's error decays by
// 2 - sqrt(3) per knot inward, below 1e-12 after 20 knots of the final step.
constexpr double pad = 2.0;
constexpr double first_step = 0.5;
constexpr int max_halvings = 12;

// Natural cubic spline through y on a uniform grid of step h: its second derivatives M solve
// M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i + y_{i+1}) / h^2, M_0 = M_n = 0; on [x_i, x_i + h] in u,
// S = y_i + (dy - h^2 (2 M_i + M_{i+1})/6) u + (h^2 M_i/2) u^2 + (h^2 (M_{i+1} - M_i)/6) u^3.
std::vector<std::array<double, 4>> natural_spline(const std::vector<double>& y) {
    const std::size_t n = y.size() - 1, m = n - 1;  // m interior knots
    std::vector<double> diag(m, 4.0), off(m - 1, 1.0), rhs(m), M(n + 1, 0.0);
    for (std::size_t i = 1; i < n; ++i) rhs[i - 1] = 6.0 * (y[i - 1] - 2.0 * y[i] + y[i + 1]);  // h^2 M, in units
    gsl_vector_view d = gsl_vector_view_array(diag.data(), m), e = gsl_vector_view_array(off.data(), m - 1),
                    b = gsl_vector_view_array(rhs.data(), m), x = gsl_vector_view_array(M.data() + 1, m);
    gsl_linalg_solve_symm_tridiag(&d.vector, &e.vector, &b.vector, &x.vector);
    std::vector<std::array<double, 4>> c(n);
    for (std::size_t i = 0; i < n; ++i)  // M here is h^2 M
        c[i] = {y[i], y[i + 1] - y[i] - (2.0 * M[i] + M[i + 1]) / 6.0, M[i] / 2.0, (M[i + 1] - M[i]) / 6.0};
    return c;
}

}  // namespace

LambdaTable::LambdaTable(std::function<double(double)> exact, const LambdaTableOptions& opts)
    : exact_(std::move(exact)), mu_min_(opts.mu_min), mu_max_(opts.mu_max) {
    require(mu_min_ > 0.0 && std::isfinite(mu_min_), "table mu_min", "finite and > 0", mu_min_);
    require(mu_max_ > mu_min_ && std::isfinite(mu_max_), "table mu_max", "finite and > mu_min", mu_max_);
    require(opts.tolerance > 0.0, "table tolerance", "> 0", opts.tolerance);
    x0_ = std::log(mu_min_) - pad;
    const double span = std::log(mu_max_) + pad - x0_;
    auto f = [&](double x) {
        const double mu = std::exp(x), L = exact_(mu);
        if (!(L >= 0.0 && L < INFINITY))
            throw input_error("cannot tabulate Lambda: it is " + std::to_string(L) + " at mu = " + std::to_string(mu));
        return std::log(mu * L);  // -inf where Lambda underflows
    };
    std::size_t n = static_cast<std::size_t>(std::ceil(span / first_step));
    double h = span / static_cast<double>(n);
    std::vector<double> y;
    for (std::size_t i = 0; i <= n; ++i) {
        y.push_back(f(x0_ + h * static_cast<double>(i)));
        if (y.back() > -INFINITY) continue;
        // Lambda underflows to 0 from here on (a Beckmann-like tail, exp(-mu^2/alpha^2)): the table ends a pad
        // before the last knot where it is positive, and the exact route answers beyond (with 0, or nearly).
        y.pop_back();
        if (y.size() < static_cast<std::size_t>(2.0 * pad / h) + 8) {
            // Lambda underflows next to mu_min already (Beckmann(1e-50): from mu ~ 1e-48 on): nothing to tabulate, and
            // the exact route answers everywhere (with 0 or nearly).
            mu_min_ = INFINITY;
            mu_max_ = -INFINITY;
            return;
        }
        n = y.size() - 1;
        mu_max_ = std::min(mu_max_, std::exp(x0_ + h * static_cast<double>(n) - pad));
        break;
    }
    for (int halvings = 0;; ++halvings) {
        // Fourth differences away from the padded ends, where the end condition, not f'''', sets the error.
        const auto skip = static_cast<std::size_t>(std::ceil(1.0 / h));
        double d4 = 0.0;
        for (std::size_t i = skip; i + 4 + skip <= n; ++i)
            d4 = std::max(d4, std::abs(y[i] - 4.0 * y[i + 1] + 6.0 * y[i + 2] - 4.0 * y[i + 3] + y[i + 4]));
        error_estimate_ = 5.0 / 384.0 * d4;
        if (error_estimate_ <= opts.tolerance) {
            inv_h_ = 1.0 / h;
            coef_ = natural_spline(y);
            return;
        }
        if (halvings == max_halvings)
            throw input_error("cannot tabulate Lambda to a relative " + std::to_string(opts.tolerance) +
                              ": estimated error " + std::to_string(error_estimate_) + " at step " + std::to_string(h));
        std::vector<double> finer(2 * n + 1);
        for (std::size_t i = 0; i <= n; ++i) finer[2 * i] = y[i];
        for (std::size_t i = 0; i < n; ++i)
            finer[2 * i + 1] = f(x0_ + h * (static_cast<double>(i) + 0.5));
        y = std::move(finer);
        n *= 2;
        h /= 2.0;
    }
}

}  // namespace smithlab
