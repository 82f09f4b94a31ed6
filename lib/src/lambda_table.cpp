#include "smithlab/lambda_table.hpp"

#include <cfloat>
#include <deque>
#include <string>
#include <utility>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab {

namespace {

constexpr double coarse = 0.5;  // the step of the search for the ends, and the first step of the grid, in ln mu
constexpr int max_halvings = 12;
constexpr double floor_Lambda = 1e-290;   // below: "underflowed" (the exact routes' digits are not held there)
constexpr double x_limit = 690.0;         // the ends are searched for within mu in [1e-300, 1e300]
constexpr double underflow_width = 1e-6;  // the bisection for where Lambda crosses floor_Lambda, in ln mu
constexpr double past_scale = 1e-5;       // the large-mu end has mu Lambda below this much of its limit c0 at mu -> 0

std::string num(double v) { return format_printf("%.6g", v); }

// Lambda at mu = e^x from the exact route, checked.
struct Exact {
    const std::function<double(double)>& fn;
    double operator()(double x) const {
        const double mu = std::exp(x), L = fn(mu);
        if (!(L >= 0.0 && L < INFINITY))
            throw input_error("cannot tabulate Lambda: it is " + std::to_string(L) + " at mu = " + std::to_string(mu));
        return L;
    }
    // The same, where the table needs mu: a refusal of the exact route says why the table cannot be built.
    double needed(double x, const char* why) const {
        try {
            return (*this)(x);
        } catch (const input_error& e) {
            const std::string what = e.what();
            if (what.rfind("cannot tabulate", 0) == 0) throw;
            throw input_error(std::string("cannot tabulate Lambda: ") + why +
                              ", and the exact route refuses mu = " + num(std::exp(x)) + ": " + what);
        }
    }
};

// The bound of the small-mu asymptote at knot x0 (lambda_table.hpp): R(mu_0) <= (g_1 - g_0)/(e^coarse - 1),
// relative to c0 - mu_0/2 >= mu_0 Lambda_0 - R(mu_0). Infinite where it cannot hold (Lambda_0 underflowed).
double small_mu_bound(double x0, double L0, double L1) {
    const double mu0 = std::exp(x0), mu1 = std::exp(x0 + coarse);
    const double a0 = mu0 * L0, R = std::max(0.0, (mu1 * L1 + 0.5 * mu1) - (a0 + 0.5 * mu0)) / std::expm1(coarse);
    if (!(L0 >= floor_Lambda) || !(a0 > 2.0 * R)) return INFINITY;
    return R / (a0 - R);
}

// The error of continuing f linearly beyond knot n of a grid of step `coarse` (f = x + ln Lambda at knots n-3..n):
// with the slope converging like e^(-p x), p >= 1, |f'(x_n) - s_inf| <= delta h / (e^h - 1)^2, delta the change of
// the last secant slope; times the length L over which the continuation stays above DBL_MIN. Infinite while the
// secant slopes still diverge (a feature ahead), beyond the noise of the knots.
double large_mu_error(const double* f, double x_n) {
    const double s1 = (f[1] - f[0]) / coarse, s2 = (f[2] - f[1]) / coarse, s3 = (f[3] - f[2]) / coarse;
    const double d3 = std::abs(s3 - s2), d2 = std::abs(s2 - s1);
    if (d3 > d2 && d3 > 1e-11) return INFINITY;
    const double s = std::min(s3, 0.0), ln_L = f[3] - x_n;
    const double length = std::max(0.0, ln_L - std::log(DBL_MIN)) / (1.0 - s) + 1.0;
    return length * d3 * coarse / (std::expm1(coarse) * std::expm1(coarse));
}

// A cubic spline through y on a uniform grid of step h with end second derivatives M_0, M_n from the knots
// (one-sided, 5 points, O(h^3)): its second derivatives solve M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i +
// y_{i+1}) / h^2 (Thomas algorithm: the system is diagonally dominant); on [x_i, x_i + h] in u,
// S = y_i + (dy - h^2 (2 M_i + M_{i+1})/6) u + (h^2 M_i/2) u^2 + (h^2 (M_{i+1} - M_i)/6) u^3.
std::vector<std::array<double, 4>> spline(const std::vector<double>& y) {
    const std::size_t n = y.size() - 1;  // n >= 8
    std::vector<double> M(n + 1);        // h^2 M
    M[0] = (35.0 * y[0] - 104.0 * y[1] + 114.0 * y[2] - 56.0 * y[3] + 11.0 * y[4]) / 12.0;
    M[n] = (35.0 * y[n] - 104.0 * y[n - 1] + 114.0 * y[n - 2] - 56.0 * y[n - 3] + 11.0 * y[n - 4]) / 12.0;
    std::vector<double> cp(n), dp(n);  // the forward sweep over rows 1..n-1, then back substitution
    for (std::size_t i = 1; i < n; ++i) {
        double r = 6.0 * (y[i - 1] - 2.0 * y[i] + y[i + 1]);
        if (i == 1) r -= M[0];
        if (i == n - 1) r -= M[n];
        const double denom = 4.0 - (i == 1 ? 0.0 : cp[i - 1]);
        cp[i] = 1.0 / denom;
        dp[i] = (r - (i == 1 ? 0.0 : dp[i - 1])) / denom;
    }
    M[n - 1] = dp[n - 1];
    for (std::size_t i = n - 1; i-- > 1;) M[i] = dp[i] - cp[i] * M[i + 1];
    std::vector<std::array<double, 4>> coef(n);
    for (std::size_t i = 0; i < n; ++i)
        coef[i] = {y[i], y[i + 1] - y[i] - (2.0 * M[i] + M[i + 1]) / 6.0, M[i] / 2.0, (M[i + 1] - M[i]) / 6.0};
    return coef;
}

}  // namespace

LambdaTable::LambdaTable(const std::function<double(double)>& exact_fn, const LambdaTableOptions& opts) {
    require(opts.mu_min > 0.0 && std::isfinite(opts.mu_min), "table mu_min", "finite and > 0", opts.mu_min);
    require(opts.mu_max > opts.mu_min && std::isfinite(opts.mu_max), "table mu_max", "finite and > mu_min",
            opts.mu_max);
    require(opts.tolerance > 0.0, "table tolerance", "> 0", opts.tolerance);
    const Exact exact{exact_fn};
    const double end_tol = opts.tolerance / 4.0;

    // 1. The ends, on a grid of step `coarse` from mu_min: Lambda at knots x_front + k coarse, up to the first knot
    //    (if any) where it is below floor_Lambda.
    const double xa = std::log(opts.mu_min);
    const auto k_max = static_cast<std::size_t>(std::max(4.0, std::ceil((std::log(opts.mu_max) - xa) / coarse)));
    double x_front = xa;
    std::deque<double> L;
    auto x_at = [&](std::size_t k) { return x_front + coarse * static_cast<double>(k); };
    for (std::size_t k = 0; k <= k_max; ++k) {
        L.push_back(exact.needed(x_at(k), "mu_min .. mu_max"));
        if (L.back() < floor_Lambda && k >= 1) break;
    }
    // Down from mu_min until the small-mu asymptote holds.
    double small_bound = small_mu_bound(x_front, L[0], L[1]);
    while (!(small_bound <= end_tol)) {
        if (x_front - coarse < -x_limit)
            throw input_error("cannot tabulate Lambda: mu Lambda does not settle to a constant down to mu = 1e-300");
        L.push_front(exact.needed(x_front - coarse, "mu Lambda has not yet settled to its limit as mu -> 0"));
        x_front -= coarse;
        small_bound = small_mu_bound(x_front, L[0], L[1]);
    }
    const double c0 = L[0] * std::exp(x_front) + 0.5 * std::exp(x_front);  // to within small_bound
    auto first_underflow = [&] {
        for (std::size_t k = 0; k < L.size(); ++k)
            if (L[k] < floor_Lambda) return k;
        return L.size();
    };
    std::size_t q = first_underflow();
    bool underflow = q < L.size();
    double large_error = 0.0, x_hi = 0.0;
    if (!underflow) {
        // Up from mu_max until the slope of f settles (a power tail), or Lambda drops below floor_Lambda.
        for (;;) {
            const std::size_t n = L.size() - 1;
            double f[4];
            for (int j = 0; j < 4; ++j) f[j] = x_at(n - 3 + j) + std::log(L[n - 3 + j]);
            large_error = large_mu_error(f, x_at(n));
            if (large_error <= end_tol && L[n] * std::exp(x_at(n)) <= past_scale * c0) break;
            if (x_at(n) + coarse > x_limit)
                throw input_error("cannot tabulate Lambda: its slope in ln mu does not settle up to mu = 1e300");
            L.push_back(exact.needed(x_at(n + 1), "the slope of ln(mu Lambda) has not yet settled as mu -> inf"));
            if (L.back() < floor_Lambda) {
                q = n + 1;
                underflow = true;
                break;
            }
        }
        x_hi = x_at(L.size() - 1);
    }
    if (underflow) {
        // Lambda crosses floor_Lambda between knots q-1 and q (q >= 1: the small-mu bound needs Lambda_0 >= floor):
        // the spline ends where it does, to underflow_width.
        double a = x_at(q - 1), b = x_at(q);
        while (b - a > underflow_width) {
            const double m = 0.5 * (a + b);
            (exact(m) >= floor_Lambda ? a : b) = m;
        }
        x_hi = a;
        underflows_ = true;
        large_error = 0.0;
    }
    x_lo_ = x_front;
    x_hi_ = x_hi;
    if (!(x_hi_ > x_lo_ + 8.0 * underflow_width))
        throw input_error(
            "cannot tabulate Lambda: it drops from its small-mu asymptote to below 1e-290 at once, near mu = " +
            num(std::exp(x_lo_)));

    // 2. The spline on [x_lo, x_hi], refined until its estimate meets the tolerance.
    auto f = [&](double x) {
        const double Lx = exact(x);
        if (!(Lx >= floor_Lambda * 0.5))
            throw input_error("cannot tabulate Lambda: it is " + std::to_string(Lx) + " at mu = " +
                              std::to_string(std::exp(x)) + ", inside the table (Lambda must not increase with mu)");
        return x + std::log(Lx);
    };
    const double span = x_hi_ - x_lo_;
    std::size_t n = std::max<std::size_t>(8, static_cast<std::size_t>(std::ceil(span / coarse)));
    double h = span / static_cast<double>(n);
    std::vector<double> y(n + 1);
    for (std::size_t i = 0; i <= n; ++i) y[i] = f(i == n ? x_hi_ : x_lo_ + h * static_cast<double>(i));
    double spline_estimate = 0.0;
    for (int halvings = 0;; ++halvings) {
        double d4 = 0.0;
        for (std::size_t i = 0; i + 4 <= n; ++i)
            d4 = std::max(d4, std::abs(y[i] - 4.0 * y[i + 1] + 6.0 * y[i + 2] - 4.0 * y[i + 3] + y[i + 4]));
        spline_estimate = 5.0 / 384.0 * d4;
        if (spline_estimate <= opts.tolerance) break;
        if (halvings == max_halvings)
            throw input_error("cannot tabulate Lambda to a relative " + num(opts.tolerance) + ": estimated error " +
                              num(spline_estimate) + " at step " + num(h));
        std::vector<double> finer(2 * n + 1);
        for (std::size_t i = 0; i <= n; ++i) finer[2 * i] = y[i];
        for (std::size_t i = 0; i < n; ++i) finer[2 * i + 1] = f(x_lo_ + h * (static_cast<double>(i) + 0.5));
        y = std::move(finer);
        n *= 2;
        h /= 2.0;
    }
    coef_ = spline(y);
    inv_h_ = 1.0 / h;
    g_lo_ = std::exp(y[0]) + 0.5 * std::exp(x_lo_);
    const std::array<double, 4>& c = coef_.back();
    const double end_slope = (c[1] + 2.0 * c[2] + 3.0 * c[3]) / h;  // df/dx at mu_hi
    ln_Lambda_hi_ = y[n] - x_hi_;
    slope_hi_ = std::min(end_slope, 0.0) - 1.0;  // mu Lambda does not increase with mu: f' <= 0
    if (underflows_) {
        // Between mu_hi and the crossing (< underflow_width on): the linear continuation errs by |f''| w^2 / 2.
        large_error = std::abs(2.0 * c[2] + 6.0 * c[3]) / (h * h) * underflow_width * underflow_width / 2.0;
    }
    error_estimate_ = std::max({spline_estimate, small_bound, large_error});
}

}  // namespace smithlab
