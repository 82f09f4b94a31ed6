/// @file
/// smithlab/quadrature.hpp -- one call, two backends, relative stopping rule.
///
/// Boost.Math: tanh-sinh on [a, b] and exp-sinh on [a, inf) (double-exponential, bounded cost).
/// GSL: QAG (21-point Gauss-Kronrod, globally adaptive) and QAGIU for [a, inf).
/// Both stop on a *relative* error. An absolute rule silently returns three correct digits when the integral is
/// 1e-78; the relative rule keeps Lambda's digits down to its underflow (docs/accuracy-and-limits.md).
/// Threads: any number may integrate at once (Boost's node tables are per thread). GSL reports a missed tolerance
/// through its process-wide error handler, whose default aborts: smithlab switches it off (gsl_set_error_handler_off)
/// once, at its first GSL integration, and never touches it again. A program that installs its own GSL handler
/// after that receives those reports (GSL_EROUND is routine at 1e-12); one that restores GSL's default aborts on them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <type_traits>

#include "smithlab/named.hpp"

namespace smithlab {

/// The quadrature library of the integrals: Boost.Math's double-exponential rules, or GSL's adaptive Gauss-Kronrod
/// (QAG, QAGIU).
enum class Backend { boost, gsl };
/// The backends by name (`--backend NAME`).
inline constexpr std::array<Named<Backend>, 2> backend_names = {{
    {Backend::boost, "boost", "Boost.Math tanh-sinh / exp-sinh"},
    {Backend::gsl, "gsl", "GSL QAG / QAGIU"},
}};

Backend parse_backend(std::string_view name);  ///< "boost" | "gsl", throws input_error otherwise
/// The backend's name, as backend_names spells it.
std::string_view to_string(Backend b);

/// How an integral is computed: the library, and the relative tolerance asked of it.
struct QuadratureOptions {
    /// The library (Boost by default).
    Backend backend = Backend::boost;
    double tolerance = 1e-12;  ///< relative
};

/// A non-owning reference to a callable double(double): no allocation, one indirect call per node.
class FunctionRef {
public:
    /// Refers to `f`, which must outlive the reference (no copy is made).
    template <class F>
    requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef>)
        FunctionRef(const F& f)  // NOLINT(google-explicit-constructor): implicit by design
        : obj_(&f), call_([](const void* o, double x) { return (*static_cast<const F*>(o))(x); }) {}
    /// f(x).
    double operator()(double x) const { return call_(obj_, x); }

private:
    const void* obj_;
    double (*call_)(const void*, double);
};

/// integral_a^b f(x) dx, a < b finite, or b = +inf.
double integrate(FunctionRef f, double a, double b, const QuadratureOptions& opts = {});

/// integral_0^{pi/2} g(t, tan t, sec^2 t) dt, for the substitutions x = a tan t and x = a sec t that map [0, inf) or
/// [a, inf) onto it: a feature of the integrand at x ~ scale then sits at pi/2 - t ~ a/scale, as wide as its
/// distance from the end point. Split at pi/4; the upper half is integrated in s = pi/2 - t, with tan t = cos s / sin s
/// and sec^2 t = 1/sin^2 s, so that both keep every digit as t -> pi/2. `s_breaks` (ignored outside (0, pi/4)) split
/// the upper half where a feature sits, s = a/scale for the scales the caller knows: end points are where the
/// double-exponential rules crowd their nodes, so a feature on one is resolved however close to s = 0 it is. Without
/// them, a feature far below s ~ 1e-5 can fall between the nodes of two successive levels alike and pass the
/// convergence test: Boost's tanh-sinh put Beckmann's Lambda at mu = 2e-12 alpha 59 % low (tests/test_quadrature.cpp).
template <class G>
double integrate_quarter_turn(const G& g, const QuadratureOptions& opts = {}, std::array<double, 2> s_breaks = {}) {
    constexpr double pi = std::numbers::pi;
    auto lower = [&](double t) {
        const double c = std::cos(t);
        return g(t, std::tan(t), 1.0 / (c * c));
    };
    auto upper = [&](double s) {
        const double sn = std::sin(s);
        return g(pi / 2 - s, std::cos(s) / sn, 1.0 / (sn * sn));
    };
    std::sort(s_breaks.begin(), s_breaks.end());
    double total = integrate(lower, 0.0, pi / 4, opts), from = 0.0;
    for (double b : s_breaks)
        if (b > from && b < pi / 4) total += integrate(upper, from, b, opts), from = b;
    return total + integrate(upper, from, pi / 4, opts);
}

/// integral_0^inf h(x) dx in x = x0 e^y and x = x0 e^-y, y in [0, inf): a feature at any scale is O(1) wide in y,
/// and a kink of h at x0 falls on the split.
template <class H>
double integrate_log_axis(const H& h, const QuadratureOptions& opts = {}, double x0 = 1.0) {
    auto up = [&](double y) {
        const double x = x0 * std::exp(y);
        return x < INFINITY ? h(x) * x : 0.0;
    };
    auto down = [&](double y) {
        const double x = x0 * std::exp(-y);
        return x > 0.0 ? h(x) * x : 0.0;
    };
    return integrate(up, 0.0, INFINITY, opts) + integrate(down, 0.0, INFINITY, opts);
}

/// integral_0^inf h(x) dx with two break points x0 <= x1 (features or kinks at both): [0, x0] and [x1, inf) as in
/// integrate_log_axis, [x0, x1] in y = ln x. A feature 50 e-folds from a single split (a slope law of width 1e-20 and
/// a kink at 1) is then still O(1) wide in its piece.
template <class H>
double integrate_log_axis(const H& h, const QuadratureOptions& opts, double x0, double x1) {
    if (!(x1 > x0 * 1.0000001)) return integrate_log_axis(h, opts, x0);
    auto up = [&](double y) {
        const double x = x1 * std::exp(y);
        return x < INFINITY ? h(x) * x : 0.0;
    };
    auto down = [&](double y) {
        const double x = x0 * std::exp(-y);
        return x > 0.0 ? h(x) * x : 0.0;
    };
    auto mid = [&](double y) {
        const double x = std::exp(y);
        return h(x) * x;
    };
    return integrate(down, 0.0, INFINITY, opts) + integrate(mid, std::log(x0), std::log(x1), opts) +
        integrate(up, 0.0, INFINITY, opts);
}

}  // namespace smithlab
