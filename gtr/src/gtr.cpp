#include "smithlab/gtr/gtr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/spline.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

Gtr gtr(double alpha, double gamma) {
    require(alpha >= 1e-50 && alpha <= 1.0, "gtr: alpha", "in [1e-50, 1]", alpha);
    require(gamma >= 0.0 && gamma <= gtr_max_gamma, "gtr: gamma", "in [0, 1e6]", gamma);
    return {alpha, gamma, gtr_K(alpha, gamma)};
}

namespace {
// t^e for t = alpha^2 / (sin^2 + alpha^2 cos^2) = alpha^2 (1 + r^2) / (r^2 + alpha^2) in [alpha^2, 1], given
// x = 1 - t = (1 - alpha^2) u with u = sin^2 / (sin^2 + alpha^2 cos^2) = r^2 / (r^2 + alpha^2), and t itself: while
// x < 1/2 as exp(e log1p(-x)), because t rounds 1 - x and t^e would lose e * 1e-16 of its digits (all of them at
// gamma = 1e16, where t^gamma ~ exp(-gamma r^2 / alpha^2) is a Beckmann lobe of width alpha / sqrt(gamma));
// beyond, where t is the small number and carries its own digits, as pow(t, e).
double t_pow(double one_minus_a2, double u, double t, double e) {
    const double x = one_minus_a2 * u;
    return x < 0.5 ? std::exp(e * std::log1p(-x)) : std::pow(t, e);
}
}  // namespace

double Gtr::D(double c) const {
    if (c < 0.0) return 0.0;
    const double a2 = alpha * alpha, s2 = (1.0 - c) * (1.0 + c), den = s2 + a2 * c * c;
    return K * t_pow((1.0 - alpha) * (1.0 + alpha), s2 / den, a2 / den, gamma);
}

double Gtr::slope_density(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    const double a2 = alpha * alpha, den = r2 + a2;
    const double w = a2 / den;  // underflows to 0 in the far tail (alpha = 1e-15, r^2 = 1e300): then P22 = 0
    if (w == 0.0) return 0.0;
    // t formed as alpha^2 ((1 + r^2) / (r^2 + alpha^2)), not w (1 + r^2), which is 0 * inf = NaN in that tail.
    return K * (t_pow((1.0 - alpha) * (1.0 + alpha), r2 / den, a2 * ((1.0 + r2) / den), gamma - 2.0) * w) * w;
}

double Gtr::Dcos_sf(double r2) const {
    if (alpha == 1.0) return 1.0 / (1.0 + r2);  // uniform D
    if (!(r2 < INFINITY)) return 0.0;
    const double a2 = alpha * alpha, one_minus_a2 = (1.0 - alpha) * (1.0 + alpha), L = -2.0 * std::log(alpha);
    const double Lc = std::log1p(one_minus_a2 / (a2 + r2));
    // L - L_c = -ln t (t = alpha^2 (1 + r^2)/(r^2 + alpha^2), gtr.cpp's t_pow): by log1p near the pole, where the
    // difference of two numbers near L would cost gamma * 1e-16 in S (1e-10 at gamma = 1e6).
    const double x = one_minus_a2 * (r2 / (a2 + r2));
    const double d = x < 0.5 ? -std::log1p(-x) : L - Lc;
    const double e = 1.0 - gamma;
    return e == 0.0 ? Lc / L : std::exp(e * d) * (std::expm1(e * Lc) / std::expm1(e * L));
}

double Gtr::Dcos_r2(double v) const {
    if (alpha == 1.0) return (1.0 - v) / v;
    const double a2 = alpha * alpha, one_minus_a2 = (1.0 - alpha) * (1.0 + alpha), L = -2.0 * std::log(alpha);
    const double e = 1.0 - gamma, k = -e;
    // d = L - L_c = -ln t, the quantile from the pole side: -log(v + (1 - v) e^{-kL}) / k (d = (1 - v) L at k = 0),
    // with log1p where the argument is near 1. Then r^2 = alpha^2 (1 - t) / (t - alpha^2), t = e^{-d}: exact while
    // t > alpha (the core; at gamma = 1e6 the lobe is alpha / 1000 wide, and the form below would cancel 6 digits).
    const double kL = k * L;
    double d;
    if (k == 0.0) d = (1.0 - v) * L;
    else {
        const double m = -std::expm1(-kL);  // 1 - e^{-kL}: in (0, 1) for k > 0, negative for k < 0 (|kL| <= 230)
        const double y = (1.0 - v) * m;
        d = std::abs(y) < 0.5 ? -std::log1p(-y) / k : -std::log(v + (1.0 - v) * std::exp(-kL)) / k;
    }
    if (d < 0.5 * L) {
        const double one_minus_t =
            -std::expm1(-d);  // t - alpha^2 = (1 - alpha^2) - (1 - t): no cancellation at d < L/2
        return std::max(0.0, a2 * one_minus_t / (one_minus_a2 - one_minus_t));
    }
    // The tail: L_c = log1p(v expm1(kL)) / k; past kL = 700, where expm1 overflows (gamma = 20 at alpha = 1e-16),
    // as L + log(v + (1 - v) e^{-kL}) / k, which cancels nothing there: v >= 2^-53 > e^{-kL}.
    const double Lc = e == 0.0 ? v * L
        : kL > 700.0           ? L + std::log(v + (1.0 - v) * std::exp(-kL)) / -e
                               : -std::log1p(v * std::expm1(kL)) / e;
    return std::max(0.0, one_minus_a2 / std::expm1(Lc) - a2);
}

double Gtr::ggx_alpha() const { return gamma == 2.0 ? alpha : std::numeric_limits<double>::quiet_NaN(); }

void Gtr::no_closed_Lambda() const {
    require(false, "gtr: gamma for a closed-form Lambda", "an integer in [0, 31]", gamma);
    throw input_error("gtr: no closed-form Lambda");  // not reached: require(false, ...) throws
}

double Lambda_from_cos_slow(const Gtr& ndf, double c) {
    if (std::isnan(c)) return c;  // as the forms in c: NaN in, NaN out (the mu route would throw input_error)
    if (c > 1.0) c = 1.0;
    return smithlab::Lambda(ndf, c / std::sqrt((1.0 - c) * (1.0 + c)));
}

double Gtr::Lambda_spline(double mu) const { return Lambda_of_interpolated_G1(G1_gtr_dimov_spline(alpha, gamma, mu)); }

}  // namespace smithlab
