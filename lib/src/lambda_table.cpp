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

// Lambda at the knots x_front + k coarse of the search for the ends.
struct EndKnots {
    double x_front;
    std::deque<double> L;

    double x(std::size_t k) const { return x_front + coarse * static_cast<double>(k); }
    // The first knot where Lambda is below floor_Lambda, or L.size().
    std::size_t first_underflow() const {
        for (std::size_t k = 0; k < L.size(); ++k)
            if (L[k] < floor_Lambda) return k;
        return L.size();
    }
};

// The knots from mu_min up to mu_max, or to the first (if any) where Lambda is below floor_Lambda.
EndKnots knots_from_mu_min(const Exact& exact, const LambdaTableOptions& opts) {
    const double xa = std::log(opts.mu_min);
    const auto k_max = static_cast<std::size_t>(std::max(4.0, std::ceil((std::log(opts.mu_max) - xa) / coarse)));
    EndKnots e{xa, {}};
    for (std::size_t k = 0; k <= k_max; ++k) {
        e.L.push_back(exact.needed(e.x(k), "mu_min .. mu_max"));
        if (e.L.back() < floor_Lambda && k >= 1) break;
    }
    return e;
}

// Down from mu_min until the small-mu asymptote holds to end_tol; its bound.
double extend_down(EndKnots& e, const Exact& exact, double end_tol) {
    double bound = small_mu_bound(e.x_front, e.L[0], e.L[1]);
    while (!(bound <= end_tol)) {
        if (e.x_front - coarse < -x_limit)
            throw input_error("cannot tabulate Lambda: mu Lambda does not settle to a constant down to mu = 1e-300");
        e.L.push_front(exact.needed(e.x_front - coarse, "mu Lambda has not yet settled to its limit as mu -> 0"));
        e.x_front -= coarse;
        bound = small_mu_bound(e.x_front, e.L[0], e.L[1]);
    }
    return bound;
}

// Up from the last knot until the slope of f = x + ln Lambda settles (a power tail) with mu Lambda below past_scale
// c0, returning the error of continuing f linearly; or until Lambda drops below floor_Lambda (at the last knot).
double extend_up(EndKnots& e, const Exact& exact, double end_tol, double c0) {
    for (;;) {
        const std::size_t n = e.L.size() - 1;
        double f[4];
        for (int j = 0; j < 4; ++j) f[j] = e.x(n - 3 + j) + std::log(e.L[n - 3 + j]);
        const double error = large_mu_error(f, e.x(n));
        if (error <= end_tol && e.L[n] * std::exp(e.x(n)) <= past_scale * c0) return error;
        if (e.x(n) + coarse > x_limit)
            throw input_error("cannot tabulate Lambda: its slope in ln mu does not settle up to mu = 1e300");
        e.L.push_back(exact.needed(e.x(n + 1), "the slope of ln(mu Lambda) has not yet settled as mu -> inf"));
        if (e.L.back() < floor_Lambda) return 0.0;
    }
}

// The ends of the table in ln mu and the bounds of the asymptotes beyond them.
struct Ends {
    double x_lo = 0.0, x_hi = 0.0;
    double small_bound = 0.0, large_error = 0.0;
    bool underflows = false;  // x_hi is where Lambda crosses floor_Lambda
};

Ends table_ends(const Exact& exact, const LambdaTableOptions& opts) {
    const double end_tol = opts.tolerance / 4.0;
    EndKnots e = knots_from_mu_min(exact, opts);
    Ends out;
    out.small_bound = extend_down(e, exact, end_tol);
    const double c0 = e.L[0] * std::exp(e.x_front) + 0.5 * std::exp(e.x_front);  // to within small_bound
    std::size_t q = e.first_underflow();
    out.underflows = q < e.L.size();
    if (!out.underflows) {
        out.large_error = extend_up(e, exact, end_tol, c0);
        q = e.first_underflow();
        out.underflows = q < e.L.size();
        out.x_hi = e.x(e.L.size() - 1);
    }
    if (out.underflows) {
        // Lambda crosses floor_Lambda between knots q-1 and q (q >= 1: the small-mu bound needs Lambda_0 >= floor):
        // the spline ends where it does, to underflow_width.
        double a = e.x(q - 1), b = e.x(q);
        while (b - a > underflow_width) {
            const double m = 0.5 * (a + b);
            (exact(m) >= floor_Lambda ? a : b) = m;
        }
        out.x_hi = a;
        out.large_error = 0.0;
    }
    out.x_lo = e.x_front;
    if (!(out.x_hi > out.x_lo + 8.0 * underflow_width))
        throw input_error(
            "cannot tabulate Lambda: it drops from its small-mu asymptote to below 1e-290 at once, near mu = " +
            num(std::exp(out.x_lo)));
    return out;
}

// The knots y_i = x_i + ln Lambda(x_i) of the spline on [x_lo, x_hi], n intervals of step h, and its error estimate.
struct SplineKnots {
    std::vector<double> y;
    std::size_t n;
    double h;
    double estimate = 0.0;
};

// From ceil(span / coarse) intervals (at least 8), halved until the estimate 5/384 max |4th difference| meets the
// tolerance.
SplineKnots refined_knots(const Exact& exact, double x_lo, double x_hi, double tolerance) {
    auto f = [&](double x) {
        const double Lx = exact(x);
        if (!(Lx >= floor_Lambda * 0.5))
            throw input_error("cannot tabulate Lambda: it is " + std::to_string(Lx) + " at mu = " +
                              std::to_string(std::exp(x)) + ", inside the table (Lambda must not increase with mu)");
        return x + std::log(Lx);
    };
    const double span = x_hi - x_lo;
    const std::size_t n0 = std::max<std::size_t>(8, static_cast<std::size_t>(std::ceil(span / coarse)));
    SplineKnots k{std::vector<double>(n0 + 1), n0, span / static_cast<double>(n0)};
    for (std::size_t i = 0; i <= k.n; ++i) k.y[i] = f(i == k.n ? x_hi : x_lo + k.h * static_cast<double>(i));
    for (int halvings = 0;; ++halvings) {
        double d4 = 0.0;
        for (std::size_t i = 0; i + 4 <= k.n; ++i)
            d4 = std::max(d4, std::abs(k.y[i] - 4.0 * k.y[i + 1] + 6.0 * k.y[i + 2] - 4.0 * k.y[i + 3] + k.y[i + 4]));
        k.estimate = 5.0 / 384.0 * d4;
        if (k.estimate <= tolerance) return k;
        if (halvings == max_halvings)
            throw input_error("cannot tabulate Lambda to a relative " + num(tolerance) + ": estimated error " +
                              num(k.estimate) + " at step " + num(k.h));
        std::vector<double> finer(2 * k.n + 1);
        for (std::size_t i = 0; i <= k.n; ++i) finer[2 * i] = k.y[i];
        for (std::size_t i = 0; i < k.n; ++i) finer[2 * i + 1] = f(x_lo + k.h * (static_cast<double>(i) + 0.5));
        k.y = std::move(finer);
        k.n *= 2;
        k.h /= 2.0;
    }
}

}  // namespace

LambdaTable::LambdaTable(const std::function<double(double)>& exact_fn, const LambdaTableOptions& opts) {
    require(opts.mu_min > 0.0 && std::isfinite(opts.mu_min), "table mu_min", "finite and > 0", opts.mu_min);
    require(opts.mu_max > opts.mu_min && std::isfinite(opts.mu_max), "table mu_max", "finite and > mu_min",
            opts.mu_max);
    require(opts.tolerance > 0.0, "table tolerance", "> 0", opts.tolerance);
    const Exact exact{exact_fn};

    // 1. The ends, on a grid of step `coarse` from mu_min.
    const Ends ends = table_ends(exact, opts);
    x_lo_ = ends.x_lo;
    x_hi_ = ends.x_hi;
    underflows_ = ends.underflows;

    // 2. The spline on [x_lo, x_hi], refined until its estimate meets the tolerance.
    const SplineKnots k = refined_knots(exact, x_lo_, x_hi_, opts.tolerance);
    coef_ = spline(k.y);
    inv_h_ = 1.0 / k.h;
    g_lo_ = std::exp(k.y[0]) + 0.5 * std::exp(x_lo_);
    const std::array<double, 4>& c = coef_.back();
    const double end_slope = (c[1] + 2.0 * c[2] + 3.0 * c[3]) / k.h;  // df/dx at mu_hi
    ln_Lambda_hi_ = k.y[k.n] - x_hi_;
    slope_hi_ = std::min(end_slope, 0.0) - 1.0;  // mu Lambda does not increase with mu: f' <= 0
    double large_error = ends.large_error;
    if (underflows_) {
        // Between mu_hi and the crossing (< underflow_width on): the linear continuation errs by |f''| w^2 / 2.
        large_error = std::abs(2.0 * c[2] + 6.0 * c[3]) / (k.h * k.h) * underflow_width * underflow_width / 2.0;
    }
    error_estimate_ = std::max({k.estimate, ends.small_bound, large_error});
}

}  // namespace smithlab
