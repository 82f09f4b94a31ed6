// tests/closed_forms_plain.hpp -- the closed forms, GGX's Lambda and Dimov's spline evaluated straightforwardly (the
// formulas as the papers print them: hypot, log, the incomplete beta function where the integer-gamma forms
// integrate), a second route beside the library's rewritten ones: test_gtr checks that Dimov's spline and the
// generated integer-gamma forms give their values, and bench_closed_forms times both on the same inputs. Not part
// of the library.
#pragma once

#include <algorithm>
#include <array>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/special_functions/log1p.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <smithlab/gtr/gtr.hpp>

namespace smithlab_plain {

inline double Ggx_Lambda(double alpha, double mu) {
    return alpha / (mu + std::hypot(mu, alpha)) * (alpha / (2.0 * mu));
}

namespace detail {

inline double lambda0(double mu) { return 1.0 / (2.0 * mu * (mu + std::hypot(mu, 1.0))); }

inline double lambda1(double alpha, double mu) {
    const double A = std::hypot(mu, alpha), B = std::hypot(mu, 1.0);
    const double one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);
    // h = (1 - alpha^2) / (-2 ln alpha) -> 1 as alpha -> 1 (uniform D, where gamma = 1 meets gamma = 0).
    const double h = alpha == 1.0 ? 1.0 : one_minus_a2 / (-2.0 * std::log(alpha));
    const double x = one_minus_a2 / ((A + B) * (mu + A));  // (mu + B)/(mu + A) - 1
    // log1pmx(x) = log1p(x) - x ~ -x^2/2: no cancellation, and log1pmx(x)/x -> 0 as x -> 0.
    const double lx = x == 0.0 ? 0.0 : boost::math::log1pmx(x) / x;
    return h / ((A + B) * (mu + A)) * (A / mu - lx);
}

inline double lambda2(double alpha, double mu) { return alpha * alpha / (mu + std::hypot(mu, alpha)) / (2.0 * mu); }

inline double lambda3(double alpha, double mu) {
    const double a2 = alpha * alpha, A = std::hypot(mu, alpha);
    const double w = a2 / (mu + A);
    return w * w / (1.0 + a2) * ((mu + A) / A + (1.0 + 3.0 * a2) / (4.0 * mu * A));
}

inline double lambda4(double alpha, double mu) {
    const double a2 = alpha * alpha, a4 = a2 * a2, A = std::hypot(mu, alpha);
    const double s = mu + A, v = a2 / A, p = mu / s;
    const double c = a4 + a2 + 1.0;
    const double tail =
        (3.0 * A + mu + 2.0 * a2 * (3.0 * A + 5.0 * mu) + a4 * (15.0 * A + 37.0 * mu)) / (mu * s * s * s);
    const double bracket = 48.0 * mu * p * p + 12.0 * p * p / mu * (1.0 + a2 * (5.0 * A + 7.0 * mu) / s) + tail;
    return v * v * v / (16.0 * c) * bracket;
}

// The brackets b_k = A^(2k+1) I_k, k = 0..n <= 29, of Lambda_gtr_integer_sum, from the integral's definition by a
// route of their own (the library's brackets() integrates a polynomial and an angular form by Gauss-Legendre):
//   I_k = integral_mu^inf (q - mu) (q^2 + alpha^2)^-(k+3/2) dq
//       = A^-(2k+1) / (2k+1) - mu alpha^-(2k+2) integral_{mu/A}^1 (1 - s^2)^k ds        (q = alpha tan phi, s = sin
//       phi)
// and the last integral is the incomplete beta function: with x = alpha^2 / A^2 (DLMF 8.17.7, 15.2.1),
//   b_k = 1/(2k+1) - (mu/A) F / (2k+2),  F = 2F1(k+1, 1/2; k+2; x) = (k+1) B_x(k+1, 1/2) / x^(k+1).
// F by its power series where x < 1/2 (terms falling by x or faster), else by Boost's incomplete beta. Where
// mu >> alpha the two terms cancel by a factor 2k + 2 at most: two digits, against the library's every-term-positive
// form.
inline std::array<double, 30> brackets(int n, double alpha, double mu, double A) {
    std::array<double, 30> b{};
    const double ratio = alpha / A, x = ratio * ratio;
    for (int k = 0; k <= n; ++k) {
        double F = 0.0;
        if (x < 0.5) {
            double term = 1.0;  // (1/2)_j / j! x^j
            for (int j = 0; term > 1e-18; ++j) {
                F += (k + 1.0) / (k + 1.0 + j) * term;
                term *= (j + 0.5) / (j + 1.0) * x;
            }
        } else {
            F = (k + 1.0) * boost::math::beta(k + 1.0, 0.5, x) / std::pow(x, k + 1);
        }
        b[k] = 1.0 / (2 * k + 1) - mu / A * F / (2.0 * k + 2.0);
    }
    return b;
}

}  // namespace detail

using namespace detail;

inline double Lambda_gtr_integer_sum(double alpha, int gamma, double mu) {
    if (gamma < 2 || gamma > 31) return std::numeric_limits<double>::quiet_NaN();
    const int n = gamma - 2;
    const double one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);
    const double A = std::hypot(mu, alpha);
    const double ratio = alpha / A;
    const std::array<double, 30> b = brackets(n, alpha, mu, A);
    // alpha^(2(n-k)+3) (alpha/A)^(2k+1) reaches 1e-2900 at alpha = 1e-50, gamma = 31 while K / mu is 1e146 and Lambda
    // 1e-251: each power is carried as a mantissa (frexp: in [0.5, 1), so fa^63 >= 1e-19) and a binary exponent, the
    // terms summed relative to the largest exponent, and the exponent put back last (ldexp rounds once, gradually).
    int ea = 0, er = 0;
    const double fa = std::frexp(alpha, &ea), fr = std::frexp(ratio, &er);
    std::array<double, 30> mant{};
    std::array<int, 30> ex{};
    int emax = std::numeric_limits<int>::min();
    double cb = std::numbers::pi / 2;  // C(n, k) B(1/2, k + 3/2), starting from B(1/2, 3/2) = pi/2
    for (int k = 0; k <= n; ++k) {
        const int pa = 2 * (n - k) + 3, pr = 2 * k + 1;
        mant[k] = cb * std::pow(one_minus_a2, k) * std::pow(fa, pa) * std::pow(fr, pr) * b[k];
        ex[k] = ea * pa + er * pr;
        if (mant[k] > 0.0) emax = std::max(emax, ex[k]);
        cb *= (n - k) / (k + 1.0) * (k + 1.5) / (k + 2.0);  // C(n,k+1)/C(n,k) and B(1/2,k+5/2)/B(1/2,k+3/2)
    }
    if (emax == std::numeric_limits<int>::min()) return 0.0;
    double sum = 0.0;
    for (int k = 0; k <= n; ++k)
        if (mant[k] > 0.0) sum += std::ldexp(mant[k], std::max(ex[k] - emax, -2000));
    return std::ldexp(smithlab::gtr_K(alpha, gamma) / mu * sum, emax);
}

inline double Lambda_gtr_closed(double alpha, int gamma, double mu) {
    // Far from the scales alpha and 1, Lambda is its asymptote to every digit: mu^2 Lambda = C (1 + O((1 + alpha^2)
    // / mu^2)) above mu = 1e100 (every GTR tail is r^-4), and mu Lambda = E[q+] - mu/2 + O(mu / alpha) below 1e-100;
    // the forms below would overflow their intermediate products there (mu^3 at mu = 1e103, 1/mu at 1e-309).
    constexpr double big = 1e100, small = 1e-100;
    if (mu > big) {
        const double r = big / mu;
        return Lambda_gtr_closed(alpha, gamma, big) * r * r;
    }
    if (mu < small) return Lambda_gtr_closed(alpha, gamma, small) * (small / mu);
    switch (gamma) {
        case 0:
            return lambda0(mu);
        case 1:
            return lambda1(alpha, mu);
        case 2:
            return lambda2(alpha, mu);
        case 3:
            return lambda3(alpha, mu);
        case 4:
            return lambda4(alpha, mu);
        default:
            return Lambda_gtr_integer_sum(alpha, gamma, mu);
    }
}

inline double G1_gtr_dimov_spline(double alpha, double gamma, double mu) {
    // Beyond mu in [1e-100, 1e100] the knots' Lambda is its asymptote (closed_forms.cpp), C/mu^2 or E[q+]/mu: the
    // spline's Lambda at the end of the range is carried out the same way, so that no 1 - G1 of a G1 within 1e-300
    // of 0 or 1 turns into NaN (mu = 1e307).
    constexpr double big = 1e100, small = 1e-100;
    if (mu > big || mu < small) {
        const double edge = mu > big ? big : small, g = G1_gtr_dimov_spline(alpha, gamma, edge);
        if (!(g > 0.0 && g < 1.0)) return g;
        const double scale = mu > big ? (big / mu) * (big / mu) : small / mu;
        return 1.0 / (1.0 + (1.0 - g) / g * scale);
    }
    std::array<double, 5> y;
    for (int k = 0; k < 5; ++k) y[k] = 1.0 / (1.0 + Lambda_gtr_closed(alpha, k, mu));
    // Natural cubic spline on unit-spaced knots: M0 = M4 = 0 and, for the second derivatives M1..M3,
    //   M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i + y_{i+1}).
    // The 3x3 system has the fixed inverse (1/56) [[15,-4,1],[-4,16,-4],[1,-4,15]].
    const double d1 = 6.0 * (y[0] - 2.0 * y[1] + y[2]);
    const double d2 = 6.0 * (y[1] - 2.0 * y[2] + y[3]);
    const double d3 = 6.0 * (y[2] - 2.0 * y[3] + y[4]);
    const std::array<double, 5> M = {0.0, (15.0 * d1 - 4.0 * d2 + d3) / 56.0, (-4.0 * d1 + 16.0 * d2 - 4.0 * d3) / 56.0,
                                     (d1 - 4.0 * d2 + 15.0 * d3) / 56.0, 0.0};
    const double g = std::min(gamma, 4.0);
    const int i = std::min(static_cast<int>(g), 3);
    const double b = g - i, a = 1.0 - b;  // distances to the right and left knots
    return M[i] * a * a * a / 6.0 + M[i + 1] * b * b * b / 6.0 + (y[i] - M[i] / 6.0) * a +
        (y[i + 1] - M[i + 1] / 6.0) * b;
}

}  // namespace smithlab_plain
