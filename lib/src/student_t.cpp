#include "smithlab/student_t.hpp"

#include <boost/math/special_functions/gamma.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "smithlab/errors.hpp"

namespace smithlab {

namespace {
constexpr double pi = std::numbers::pi;
// Boost's special functions in double itself (its default promotes to long double).
constexpr boost::math::policies::policy<boost::math::policies::promote_double<false>> double_policy;
}  // namespace

StudentT student(double alpha, double gamma) {
    require(alpha >= 1e-50 && alpha <= 1e50, "student: alpha", "in [1e-50, 1e50]", alpha);
    require(gamma >= student_min_gamma && gamma <= student_max_gamma, "student: gamma", "in [1.6, 1e6]", gamma);
    const double g = gamma - 1.0, A = gamma - 1.5;  // both exact for gamma in [1.5, 2^52]
    const double P = boost::math::tgamma_delta_ratio(gamma - 0.5, 0.5, double_policy) * std::sqrt(g) /
                     (4.0 * A * std::sqrt(pi));
    return {alpha, gamma, P};
}

double StudentT::D(double c) const {
    if (!(c > 0.0)) return 0.0;
    const double s2 = (1.0 - c) * (1.0 + c), ga2 = (gamma - 1.0) * alpha * alpha, lc = std::log(c);
    // L = ln(1 + q), q = tan^2 / ((gamma - 1) alpha^2) = s2 / (ga2 c^2). Below c = 1e-100 (where c^2 c^2 would
    // underflow) q > 1e94 and ln(1 + q) = ln q to double.
    const double L = c > 1e-100 ? std::log1p(s2 / (ga2 * c * c)) : std::log(s2) - std::log(ga2) - 2.0 * lc;
    // P22 / cos^4 as one exponential: (1 + q)^-gamma c^-4, finite at every c > 0 (it grows like c^(2 gamma - 4)).
    return std::exp(-gamma * L - 4.0 * lc) / (pi * alpha * alpha);
}

double StudentT::slope_density(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    return std::exp(-gamma * std::log1p(r2 / ((gamma - 1.0) * alpha * alpha))) / (pi * alpha * alpha);
}

double StudentT::Dcos_sf(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    const double g = gamma - 1.0;
    return std::exp(-g * std::log1p(r2 / (g * alpha * alpha)));
}

double StudentT::Dcos_r2(double v) const {
    const double g = gamma - 1.0, ga2 = g * alpha * alpha, y = -std::log(v) / g;
    return y < 700.0 ? ga2 * std::expm1(y) : std::exp(std::log(ga2) + y);  // (overflows to inf only when r^2 does)
}

double StudentT::ggx_alpha() const { return gamma == 2.0 ? alpha : std::numeric_limits<double>::quiet_NaN(); }

// ---------------------------------------------------------------------------------------------------------------
// Lambda.
//
// The paper's eq. 13-15, with z = mu / alpha (its "z"; eq. 14 S1 = ((gamma - 1) + z^2)^(3/2 - gamma) / z):
//     Lambda = Gamma(gamma - 1/2) / (sqrt(pi) Gamma(gamma))
//              [(gamma - 1)^gamma S1 / (2 gamma - 3) + sqrt(gamma - 1) S2] - 1/2,
// S2 = integral_0^z (1 + u^2/(gamma - 1))^(1/2 - gamma) du its hypergeometric part (eq. 15, which the paper then fits,
// eq. 22-23). The slope marginal P2 is a Student's t: q = (alpha / sqrt 2) T, T with n = 2 gamma - 2 degrees of
// freedom, so Lambda = E[(q - mu)+] / mu (Walter 2007 eq. 48) is the t's stop-loss over s = sqrt(2) z,
//     Lambda = (n + s^2) f_n(s) / ((n - 1) s) - S_n(s)            (f_n its density, S_n its survival),
// which is eq. 13 again (the bracket minus 1/2 is -S_n), and Beckmann's Lambda as n -> inf.
// As written, eq. 13 cancels: all digits as mu -> inf (Lambda -> 0 against 1/2), a factor ~2 z^2 at large gamma
// (as Beckmann's e^{-a^2}/(a sqrt pi) - erfc(a) does). Here it is evaluated in two forms that do not, with
// g = gamma - 1, A = gamma - 3/2 and w = z^2 / g:
//  (Y) Expanding eq. 13's integrals in powers of -1/w (the bracket's series, term by term) gives
//          Lambda = P (1 + w)^(1 - A) / (w z) Phi(1/w),   Phi(y) = 2F1(3/2, 1; gamma; -y),
//      P = Gamma(gamma - 1/2) sqrt(g) / (4 A sqrt(pi) Gamma(gamma)) (student(), once per NDF), after the Pfaff
//      transformation (DLMF 15.8.1) that makes it converge for every w > 0. Phi(y) = g integral_0^1 (1 - u)^(g-1)
//      (1 + y u)^(-3/2) du (DLMF 15.6.1) is completely monotone in y; Gauss's continued fraction for it (DLMF 15.7(i),
//      F(a, b + 1; c + 1; z) / F(a, b; c; z) at b = 0) has positive partial numerators,
//          Phi = 1 / (1 + k1 y / (1 + k2 y / (1 + ...))),
//          k_{2m+1} = (3/2 + m)(g + m) / ((g + 2m)(g + 2m + 1)),   k_{2m} = m (g - 3/2 + m) / ((g + 2m - 1)(g + 2m)),
//      so that every step adds and multiplies positive numbers, and its convergents bracket Phi. It is evaluated by
//      the three-term (Wallis) recurrences, without a division on the recurrence's path. Steps: ~10 at z = 10, ~20
//      at z = 4, ~60 at z = 2, ~100-700 at z = 0.7 (more as gamma, and with it y = g / z^2, grows).
//  (X) For z <= 0.7, the same function continued to w = 0 (DLMF 15.8.4, c - a - b = 1/2):
//          Lambda = 2 g P (1 + w)^-A / z H(x) - 1/2,   H(x) = 2F1(A, 1; 1/2; x),   x = w / (1 + w),
//      a series of positive terms (x^n z^2n / (1/2)_n-like: ~15-35 terms); the -1/2 is the paper's, and costs
//      a factor (Lambda + 1/2) / Lambda <= 6.8 (Lambda >= Beckmann's 0.0858 at z = 0.7: Lambda decreases with gamma).
// Both take mu / alpha and w as double-double (z + z_lo, w + w_lo) from the exact inputs: rounded once, their error
// would be multiplied by Lambda's sensitivity to mu, ~2 gamma - 2 at large z.
// ---------------------------------------------------------------------------------------------------------------

namespace {

// Phi(y) = 2F1(3/2, 1; g + 1; -y), y > 0, by the continued fraction above: with d_j = k_j y, the convergents
// A_j / B_j of 1 + d1 / (1 + d2 / (1 + ...)) follow A_j = A_{j-1} + d_j A_{j-2} (and B alike), all positive; they are
// rescaled when they grow, and the even and odd convergents bracket the value, so stopping when two consecutive ones
// agree to 1e-16 leaves at most that.
double Phi_continued_fraction(double g, double y) {
    double A0 = 1.0, A1 = 1.0, B0 = 0.0, B1 = 1.0;  // A_{j-2}, A_{j-1}, B_{j-2}, B_{j-1}; j = 1
    for (int j = 1; j < 20000; j += 2) {
        const double m = static_cast<double>(j / 2);
        const double d_odd = (1.5 + m) * (g + m) / ((g + 2.0 * m) * (g + 2.0 * m + 1.0)) * y;
        const double d_even = (m + 1.0) * (g - 0.5 + m) / ((g + 2.0 * m + 1.0) * (g + 2.0 * m + 2.0)) * y;
        const double A2 = A1 + d_odd * A0, B2 = B1 + d_odd * B0;  // j (odd)
        const double A3 = A2 + d_even * A1, B3 = B2 + d_even * B1;  // j + 1 (even)
        if (std::abs(A3 * B2 - A2 * B3) <= 1e-16 * A3 * B2) return B3 / A3;
        A0 = A2, A1 = A3, B0 = B2, B1 = B3;
        if (A1 > 1e150) {  // A and B grow by up to ~y per step: rescale (exactly, by a power of 2)
            A0 = std::ldexp(A0, -500), A1 = std::ldexp(A1, -500), B0 = std::ldexp(B0, -500), B1 = std::ldexp(B1, -500);
        }
    }
    return B1 / A1;
}

// 1 / (1/2 + n), so that H's series divides by nothing.
constexpr std::array<double, 96> inv_half_plus = [] {
    std::array<double, 96> a{};
    for (std::size_t n = 0; n < a.size(); ++n) a[n] = 1.0 / (0.5 + static_cast<double>(n));
    return a;
}();

// H(x) = 2F1(A, 1; 1/2; x) = sum_n (A)_n / (1/2)_n x^n: positive terms whose ratio r_n = (A + n) x / (1/2 + n) tends to
// x (from above for A > 1/2, from below for A < 1/2); the tail after a term is at most term r / (1 - r),
// r = max(r_n, x). Here x <= 0.49 / (g + 0.49) <= 0.48 (z <= 0.7, g >= 0.55).
double H_series(double A, double x) {
    double term = 1.0, sum = 1.0;
    for (std::size_t n = 0; n < inv_half_plus.size(); ++n) {
        const double r = (A + static_cast<double>(n)) * inv_half_plus[n] * x;
        term *= r;
        sum += term;
        const double rmax = std::max(r, x);
        if (term * rmax < 5e-17 * (1.0 - rmax) * sum) break;
    }
    return sum;
}

}  // namespace

double StudentT::Lambda(double mu) const {
    const double g = gamma - 1.0, A = gamma - 1.5;
    const double z = mu / alpha;
    if (!(z > 0.0)) return z == 0.0 ? INFINITY : std::numeric_limits<double>::quiet_NaN();  // mu / alpha underflows
    if (z == INFINITY) return 0.0;
    const double z_lo = std::fma(-z, alpha, mu) / alpha;  // mu / alpha = z + z_lo
    if (z > 1e100) {
        // w > 1e194 and Phi(1/w) = 1 - 3/(2 gamma w) + ... = 1: Lambda = P g^A z^-(2A + 1), without forming z^2
        // (which overflows past 1.3e154).
        return P * std::pow(std::sqrt(g) / z, 2.0 * A) / z * (1.0 - (2.0 * A + 1.0) * (z_lo / z));
    }
    const double z2 = z * z, z2_lo = std::fma(z, z, -z2) + 2.0 * z * z_lo;
    const double w = z2 / g, w_lo = (std::fma(-w, g, z2) + z2_lo) / g;
    const double s = 1.0 + w, s_b = s - 1.0, s_lo = ((1.0 - (s - s_b)) + (w - s_b)) + w_lo;  // 1 + w = s + s_lo
    if (z <= 0.7) {
        const double tA_z = std::pow(s, -A) * (1.0 - A * (s_lo / s)) / z * (1.0 - z_lo / z);  // (1 + w)^-A / z
        return 2.0 * g * P * tA_z * H_series(A, w / s) - 0.5;
    }
    const double y = 1.0 / w * (1.0 - w_lo / w);
    const double lead = std::pow(s, 1.0 - A) * (1.0 + (1.0 - A) * (s_lo / s)) / (w * z) *
                        (1.0 - w_lo / w - z_lo / z);  // (1 + w)^(1 - A) / (w z)
    return P * lead * Phi_continued_fraction(g, y);
}

}  // namespace smithlab
