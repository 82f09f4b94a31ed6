#include "smithlab/ndfs.hpp"

#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <numbers>

#include "smithlab/errors.hpp"

namespace smithlab {

namespace {
using std::numbers::pi;

// alpha^2 and alpha^4 must neither underflow nor overflow in D and the closed forms.
void require_alpha(const char* what, double x) { require(x >= 1e-50 && x <= 1e50, what, "in [1e-50, 1e50]", x); }
}  // namespace

Ggx ggx(double alpha) {
    require_alpha("ggx: alpha", alpha);
    return {alpha};
}

Beckmann beckmann(double alpha) {
    require_alpha("beckmann: alpha", alpha);
    return {alpha};
}

BlinnPhong blinn(double n) {
    require(n >= 0.0 && std::isfinite(n), "blinn: n", "finite and >= 0", n);
    return {n};
}

double Beckmann::D(double c) const {
    if (c <= 0.0) return 0.0;
    const double c2 = c * c;
    const double e = std::exp(-(1.0 - c) * (1.0 + c) / (c2 * alpha * alpha));
    return e == 0.0 ? 0.0 : e / (pi * alpha * alpha * c2 * c2);
}

double Beckmann::slope_density(double r2) const { return std::exp(-r2 / (alpha * alpha)) / (pi * alpha * alpha); }

namespace {
// Boost's erfc in double itself: its default promotes to long double, 5x slower (the walk calls Lambda per bounce).
constexpr boost::math::policies::policy<boost::math::policies::promote_double<false>> double_erfc;
}  // namespace

double Beckmann::Lambda(double mu) const {
    // a = mu/alpha carried as a + a_lo (one rounding error removed): Lambda's relative sensitivity to a is ~2 a^2,
    // which would cost 3 digits near the underflow of exp(-a^2) if a were rounded once.
    const double a = mu / alpha;
    // Past a = 27.3, e^{-a^2} < 1e-324: Lambda underflows to 0 (and a^2 would overflow to inf * 0 = NaN at 1.3e154).
    if (a > 28.0) return 0.0;
    const double a_lo = std::fma(-a, alpha, mu) / alpha;
    const double a2 = a * a;
    const double a2_lo = std::fma(a, a, -a2) + 2.0 * a * a_lo;
    const double gauss = std::exp(-a2) * (1.0 - a2_lo) / std::sqrt(pi);  // e^{-a^2} / sqrt(pi), a^2 to ~1 ulp
    double ierfc;
    if (a < 6.0) {
        // Cancellation here is at most a factor 2 a^2 < 72. erfc is corrected to first order for a_lo.
        const double erfc_a = boost::math::erfc(a, double_erfc) - 2.0 * a_lo * gauss;
        ierfc = gauss - (a + a_lo) * erfc_a;
    } else {
        ierfc = gauss * detail::ierfc_scaled_asymptotic(a);
    }
    return ierfc / (2.0 * a);
}

namespace {
// sum_{k>=k0} (-1)^{k-k0} (2k-1)!! x^k, x = 1 / (2 a^2), (-1)!! = 1, stopped at its smallest term or at 1e-17.
double asymptotic_sum(double a, int k0) {
    const double x = 1.0 / (2.0 * a * a);
    double term = k0 == 0 ? 1.0 : x, sum = term;
    for (int k = k0 + 1; k < 60; ++k) {
        const double next = -term * (2 * k - 1) * x;
        if (std::abs(next) >= std::abs(term)) break;
        term = next;
        sum += term;
        if (std::abs(term) < 1e-17 * sum) break;
    }
    return sum;
}
}  // namespace

// A&S 7.1.23: sqrt(pi) a e^{a^2} erfc(a) ~ sum_{k>=0} (-1)^k (2k-1)!! / (2a^2)^k; integrated once (ierfc' = -erfc):
// sqrt(pi) e^{a^2} ierfc(a) ~ sum_{k>=1} (-1)^{k+1} (2k-1)!! / (2a^2)^k.
double detail::erfc_scaled_asymptotic(double a) { return asymptotic_sum(a, 0) / a; }
double detail::ierfc_scaled_asymptotic(double a) { return asymptotic_sum(a, 1); }

double BlinnPhong::D(double c) const {
    if (c < 0.0) return 0.0;
    return (n + 2.0) / (2.0 * pi) * std::pow(c, n);
}

double BlinnPhong::slope_density(double r2) const {
    // cos^2 = 1/(1 + r^2); log1p keeps the digits of a tiny r^2.
    return (n + 2.0) / (2.0 * pi) * std::exp(-0.5 * (n + 4.0) * std::log1p(r2));
}

}  // namespace smithlab
