#include "smithlab/gtr/gtr.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "smithlab/errors.hpp"
#include "smithlab/gtr/closed_forms.hpp"
#include "smithlab/gtr/spline.hpp"

namespace smithlab {

double gtr_K(double alpha, double gamma) {
    constexpr double pi = std::numbers::pi;
    if (alpha == 1.0) return 1.0 / pi;  // uniform D
    const double one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);  // not 1 - alpha*alpha: 5 digits at alpha = 0.999999
    const double log_a = std::log(alpha);
    const double y = 2.0 * (gamma - 1.0) * log_a;  // (gamma - 1) is exact near 1 (Sterbenz)
    // (gamma - 1) / (-expm1(y)) = 1 / (-2 ln alpha * expm1(y)/y), and expm1(y)/y -> 1 as y -> 0.
    const double exprel = (y == 0.0) ? 1.0 : std::expm1(y) / y;
    return one_minus_a2 / (pi * alpha * alpha) / (-2.0 * log_a * exprel);
}

Gtr gtr(double alpha, double gamma) {
    require(alpha >= 1e-50 && alpha <= 1.0, "gtr: alpha", "in [1e-50, 1]", alpha);
    require(gamma >= 0.0 && std::isfinite(gamma), "gtr: gamma", "finite and >= 0", gamma);
    return {alpha, gamma, gtr_K(alpha, gamma)};
}

double Gtr::D(double c) const {
    if (c < 0.0) return 0.0;
    const double t = alpha * alpha / ((1.0 - c) * (1.0 + c) + alpha * alpha * c * c);
    return K * std::pow(t, gamma);
}

double Gtr::slope_density(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    const double w = alpha * alpha / (r2 + alpha * alpha);
    const double t = w * (1.0 + r2);
    return K * std::pow(t, gamma - 2.0) * w * w;
}

double Gtr::Dcos_sf(double r2) const {
    if (alpha == 1.0) return 1.0 / (1.0 + r2);  // uniform D
    if (!(r2 < INFINITY)) return 0.0;
    const double a2 = alpha * alpha, one_minus_a2 = (1.0 - alpha) * (1.0 + alpha), L = -2.0 * std::log(alpha);
    const double Lc = std::log1p(one_minus_a2 / (a2 + r2));
    const double e = 1.0 - gamma;
    return e == 0.0 ? Lc / L : std::exp(e * (L - Lc)) * (std::expm1(e * Lc) / std::expm1(e * L));
}

double Gtr::Dcos_r2(double v) const {
    if (alpha == 1.0) return (1.0 - v) / v;
    const double a2 = alpha * alpha, one_minus_a2 = (1.0 - alpha) * (1.0 + alpha), L = -2.0 * std::log(alpha);
    const double e = 1.0 - gamma;
    // L_c = log1p(v expm1(kL)) / k with k = -e; past kL = 700, where expm1 overflows (gamma = 20 at alpha = 1e-16),
    // as L + log(v + (1 - v) e^{-kL}) / k, which cancels nothing there: v >= 2^-53 > e^{-kL}.
    const double kL = -e * L;
    const double Lc = e == 0.0 ? v * L
                      : kL > 700.0 ? L + std::log(v + (1.0 - v) * std::exp(-kL)) / -e
                                 : -std::log1p(v * std::expm1(kL)) / e;
    return std::max(0.0, one_minus_a2 / std::expm1(Lc) - a2);
}

bool Gtr::has_closed_Lambda() const { return gtr_has_closed_form(gamma); }

double Gtr::Lambda(double mu) const {
    require(has_closed_Lambda(), "gtr: gamma for a closed-form Lambda", "an integer in [0, 31]", gamma);
    return Lambda_gtr_closed(alpha, static_cast<int>(gamma), mu);
}

double Gtr::Lambda_spline(double mu) const {
    return Lambda_of_interpolated_G1(G1_gtr_dimov_spline(alpha, gamma, mu));
}

}  // namespace smithlab
