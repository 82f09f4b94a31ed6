#include "smithlab/student_t.hpp"

#include <algorithm>
#include <array>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "smithlab/errors.hpp"

namespace smithlab {

namespace {
using std::numbers::pi;
// (1 + q)^-e for q >= 0: by log1p near q = 0, where 1 + q would drop q's digits; beyond, by pow, whose error is a few
// ulp of 1 + q times e where exp(-e log1p(q)) would add e ln(q) ulp (5e-14 at q = 1e100, e = 2).
double inv_pow1p(double q, double e) { return q < 0.5 ? std::exp(-e * std::log1p(q)) : std::pow(1.0 + q, -e); }
}  // namespace

StudentT student(double alpha, double gamma) {
    require(alpha >= 1e-50 && alpha <= 1e50, "student: alpha", "in [1e-50, 1e50]", alpha);
    require(gamma >= student_min_gamma && gamma <= student_max_gamma, "student: gamma", "in [1.65, 1e6]", gamma);
    // P = Gamma(gamma - 1/2) / Gamma(gamma) sqrt(g) / (4 A sqrt(pi)), once per NDF in long double (to 0.5 ulp in
    // double: its error is multiplied by up to 6.9 near z = 0.7, Lambda below).
    const long double g = gamma - 1.0L, A = gamma - 1.5L;  // both exact
    const long double P = boost::math::tgamma_delta_ratio(gamma - 0.5L, 0.5L) * std::sqrt(g) /
        (4.0L * A * std::sqrt(std::numbers::pi_v<long double>));
    return {alpha, gamma, static_cast<double>(P)};
}

double StudentT::D(double c) const {
    if (!(c > 0.0)) return 0.0;
    const double s2 = (1.0 - c) * (1.0 + c), ga2 = (gamma - 1.0) * alpha * alpha;
    // P22 / cos^4 with q = tan^2 / ((gamma - 1) alpha^2) = s2 / (ga2 c^2), while c^4 and (1 + q)^-gamma stay in range
    // (the divisions in this order cannot underflow where D does not: pi alpha^2 c^2 >= 3e-220) ...
    if (c > 1e-60) {
        const double c2 = c * c, p = inv_pow1p(s2 / (ga2 * c2), gamma);
        if (p > 1e-280) return p / (pi * alpha * alpha * c2) / c2;
    }
    // ... else as one exponential, (1 + q)^-gamma c^-4 = exp(-gamma ln(1 + q) - 4 ln c), finite at every c > 0 (it
    // grows like c^(2 gamma - 4) for gamma < 2); past q = 1e94, ln(1 + q) = ln q to double.
    const double lc = std::log(c), q_big = c > 1e-100 ? s2 / (ga2 * c * c) : INFINITY;
    const double L = q_big < 1e94 ? std::log1p(q_big) : std::log(s2) - std::log(ga2) - 2.0 * lc;
    return std::exp(-gamma * L - 4.0 * lc) / (pi * alpha * alpha);
}

double StudentT::slope_density(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    const double q = r2 / ((gamma - 1.0) * alpha * alpha), p = inv_pow1p(q, gamma), pa2 = pi * alpha * alpha;
    // Where (1 + q)^-gamma nears its underflow, 1 / (pi alpha^2) (up to 3e99) may still lift P22 into range: one
    // exponential then (a q that overflows leaves P22 below 1e-400 for every accepted alpha and gamma: 0).
    return p > 1e-280 ? p / pa2 : std::exp(-gamma * std::log1p(q) - std::log(pa2));
}

double StudentT::Dcos_sf(double r2) const {
    if (!(r2 < INFINITY)) return 0.0;
    const double g = gamma - 1.0;
    return inv_pow1p(r2 / (g * alpha * alpha), g);
}

double StudentT::Dcos_r2(double v) const {
    // r^2 = g alpha^2 (v^(-1/g) - 1): expm1 near v = 1, pow beyond (exact at g = 1: GGX's (1 - v) / v), and through
    // logs where v^(-1/g) alone would overflow but r^2 need not (alpha < 1).
    const double g = gamma - 1.0, ga2 = g * alpha * alpha, y = -std::log(v) / g;
    if (y < 0.5) return ga2 * std::expm1(y);
    const double p = std::pow(v, -1.0 / g);
    return p < INFINITY ? ga2 * (p - 1.0) : std::exp(std::log(ga2) + y);
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
//  (Y) Expanding eq. 13's integrals in powers of -1/w, term by term, sums to 2F1(A, g; gamma; -1/w) times powers of w,
//      and Euler's transformation (DLMF 15.8.1) turns it into
//          Lambda = P (1 + w)^(1 - A) / (w z) Phi(1/w),   Phi(y) = 2F1(3/2, 1; gamma; -y),
//      P = Gamma(gamma - 1/2) sqrt(g) / (4 A sqrt(pi) Gamma(gamma)) (student(), once per NDF), with no cancellation
//      left; the series converges only for w > 1, the continued fraction below for every w.
//      Phi(y) = g integral_0^1 (1 - u)^(g-1) (1 + y u)^(-3/2) du (DLMF 15.6.1) is completely monotone in y; Gauss's
//      continued fraction for it (DLMF 15.7(i), F(a, b + 1; c + 1; z) / F(a, b; c; z) at b = 0) has positive partial
//      numerators,
//          Phi = 1 / (1 + k1 y / (1 + k2 y / (1 + ...))),
//          k_{2m+1} = (3/2 + m)(g + m) / ((g + 2m)(g + 2m + 1)),   k_{2m} = m (g - 3/2 + m) / ((g + 2m - 1)(g + 2m)),
//      so that every step adds and multiplies positive numbers, and its convergents bracket Phi. It is evaluated by
//      the three-term (Wallis) recurrences, without a division on the recurrence's path. Steps: ~10 at z = 10, ~20
//      at z = 4, ~60 at z = 2, ~100-700 at z = 0.7 (more as gamma, and with it y = g / z^2, grows).
//  (X) For z <= 0.7, the same function about w = 0: Phi(y) = x F(A, 1; gamma; 1 - x), x = w / (1 + w) (Pfaff,
//      DLMF 15.8.1), and F's connection formula from 1 - x to x (DLMF 15.8.4, c - a - b = 1/2) gives
//          Lambda = 2 g P (1 + w)^-A / z H(x) - 1/2,   H(x) = 2F1(A, 1; 1/2; x),
//      a series of positive terms (at large gamma ~ sum_n z^2n / (1/2)_n: ~15-35 terms); the -1/2 is the paper's, and
//      costs a factor (Lambda + 1/2) / Lambda <= 6.9 (Lambda >= Beckmann's 0.0857 at z = 0.7; Lambda decreases with
//      gamma, tests/test_student_t.cpp).
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
        const double A2 = A1 + d_odd * A0, B2 = B1 + d_odd * B0;    // j (odd)
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

// H(x) = 2F1(A, 1; 1/2; x) = sum_n (A)_n / (1/2)_n x^n at x + x_lo, to first order in x_lo (H' = sum_n n term_n / x):
// positive terms whose ratio r_n = (A + n) x / (1/2 + n) tends to x (from above for A > 1/2, from below for
// A < 1/2); the tail after a term is at most term r / (1 - r), r = max(r_n, x). Here x <= 0.49 / (g + 0.49) <= 0.48
// (z <= 0.7, g >= 0.65).
double H_series(double A, double x, double x_lo) {
    double term = 1.0, sum = 1.0, dsum = 0.0;  // dsum = x H'(x)
    for (std::size_t n = 0; n < inv_half_plus.size(); ++n) {
        const double r = (A + static_cast<double>(n)) * inv_half_plus[n] * x;
        term *= r;
        sum += term;
        dsum += static_cast<double>(n + 1) * term;
        const double rmax = std::max(r, x);
        if (term * rmax < 5e-17 * (1.0 - rmax) * sum) break;
    }
    return x > 0.0 ? sum + dsum * (x_lo / x) : sum;  // x = 0: z^2 underflowed
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
        const double x = w / s, x_lo = (std::fma(-x, s, w) + w_lo - x * s_lo) / s;            // w / (1 + w)
        return 2.0 * g * P * tA_z * H_series(A, x, x_lo) - 0.5;
    }
    const double y = 1.0 / w * (1.0 - w_lo / w);
    const double lead = std::pow(s, 1.0 - A) * (1.0 + (1.0 - A) * (s_lo / s)) / (w * z) *
        (1.0 - w_lo / w - z_lo / z);  // (1 + w)^(1 - A) / (w z)
    return P * lead * Phi_continued_fraction(g, y);
}

}  // namespace smithlab
