/// @file
/// smithlab/gtr/closed_forms.hpp -- Smith Lambda of GTR in closed form for gamma = 0, 1, 2, 3, 4 (Dimov 2015, sec. 3)
/// and for every larger integer gamma (generated; Dimov stopped at 4 because gamma = 10 was "quite large"),
/// rewritten so that every term is positive: each keeps full relative accuracy in double for all alpha in
/// [1e-50, 1] and mu > 0. Dimov's printed forms, evaluated literally, lose up to all 16 digits (gamma = 3,
/// alpha = 1e-4, mu >= 10: the difference mu - sqrt(mu^2 + alpha^2)).
///
/// The forms for gamma = 0..4 are inline here (a renderer calls them per sample): each is a ratio num / den of positive
/// terms, so that Lambda = num / den and G1 = 1 / (1 + Lambda) = den / (den + num) cost one division each, built from
/// sqrt, log and log1p only (no hypot, no log1pmx). Each is given twice, in mu = cot(theta) and in
/// c = cos(theta) (what a renderer holds; s2 = sin^2 = (1 - c)(1 + c)), the second obtained from the first by
/// mu = c / s, A = Ac / s, B = 1 / s with Ac = sqrt(c^2 + alpha^2 s2) (B s = sqrt(c^2 + s2) = 1) and cleared of s.
#pragma once

#include <cmath>

namespace smithlab {

/// Closed forms exist for every integer gamma in [0, gtr_max_closed_gamma].
inline constexpr int gtr_max_closed_gamma = 31;  ///< Ghat_k is integrated exactly for k <= 29
/// An integer in [0, 31]: there the truncating cast is floor (no libm call on baseline x86-64); NaN is false.
inline bool gtr_has_closed_form(double gamma) {
    return gamma >= 0.0 && gamma <= gtr_max_closed_gamma && gamma == static_cast<double>(static_cast<int>(gamma));
}

namespace gtr_closed {

/// Lambda = num / den with num >= 0, den > 0 (finite, neither overflowing on the stated domain).
struct Ratio {
    /// The numerator and the denominator.
    /// @{
    double num, den;
    /// @}
    /// num / den.
    double Lambda() const { return num / den; }
    double G1() const { return den / (den + num); }  ///< 1 / (1 + num / den)
};

/// The domain of the mu forms below: alpha in [1e-50, 1], mu in [mu_small, mu_big]; Lambda_gtr_closed continues them
/// beyond by their asymptotes. There mu^2 lies in [1e-200, 1e100], and every product below stays within double
/// (the extremes: den of gamma = 4 is 16 c mu s^3 <= 4e202 at mu = 1e50, >= 1.6e-249 at mu = 1e-100, alpha = 1e-50).
/// @{
inline constexpr double mu_big = 1e50, mu_small = 1e-100;
/// @}

/// sqrt(mu^2 + x2) for mu in [1e-100, 1e50], x2 = alpha^2 in [1e-100, 1]: mu^2 neither overflows nor underflows
/// harmfully (below 1e-100 it is negligible next to x2), and the root of a sum of two positive rounded products is
/// within 1.25 ulp, as hypot's is, at a fraction of its cost (hypot guards ranges this domain does not reach).
inline double root_sum_squares(double mu, double x2) { return std::sqrt(mu * mu + x2); }

// ---- in mu = cot(theta); A = sqrt(mu^2 + alpha^2), B = sqrt(mu^2 + 1), s = mu + A, a2 = alpha^2 ----

/// gamma = 0, Dimov 2015 sec. 3.1: Lambda = (B - mu) / (2 mu) = 1 / (2 mu (mu + B))   (rationalized: B^2 - mu^2 = 1).
inline Ratio ratio0(double mu, double B) { return {1.0, 2.0 * mu * (mu + B)}; }

/// gamma = 1, Dimov 2015 sec. 3.2, printed as Lambda = (A - B + mu asinh(mu) - mu log(mu + A)) / (mu ln alpha^2).
/// With asinh(mu) = log(mu + B) and x = (mu + B)/(mu + A) - 1 = (B - A)/(mu + A) = (1 - alpha^2)/((A + B)(mu + A)),
/// so that B - A = x (mu + A):
///     Lambda = (A x + mu (x - log1p(x))) / (-2 mu ln alpha),
/// two non-negative terms (x >= log1p(x)). The subtraction x - log1p(x) loses relative digits only where x is small,
/// and there it is <= x^2/2 next to A x >= mu x: an absolute error of a few ulp(x) is a few ulp of the numerator. (This
/// replaces boost's log1pmx.) log1p itself by Kahan's trick (Goldberg 1991, "What every computer scientist should
/// know about floating-point arithmetic", Theorem 4): with u = fl(1 + x) and d = u - 1,
/// log1p(x) = x log(u) / d to a few ulp (d is exact below 2^53; above, log is well-conditioned), so that, with x / d
/// put into the ratio,
///     Lambda = x (A d + mu (d - log(u))) / (d (-2 mu ln alpha))      (d = 0, x < 2^-53: x A / (-2 mu ln alpha)),
/// where d - log(u) >= 0 has an absolute error of ~ulp(d) next to A d >= mu d: glibc's log is several times faster than
/// its log1p. 1 - alpha^2 as (1 - alpha)(1 + alpha): 5 digits better at alpha = 0.999999.
/// alpha = 1 is the uniform D (0/0 here; the limit is gamma = 0's form).
/// The common part of the mu and c forms: x, the scale A (or Ac) and mu (or c).
inline Ratio ratio1_of_x(double alpha, double x, double A, double mu) {
    const double u = 1.0 + x, d = u - 1.0, den = -2.0 * mu * std::log(alpha);
    if (d == 0.0) return {x * A, den};
    return {x * (A * d + mu * (d - std::log(u))), d * den};
}
/// gamma = 1 in mu (Dimov 2015 sec. 3.2, in the form derived above ratio1_of_x); alpha = 1, the uniform D, by gamma =
/// 0's form.
inline Ratio ratio1(double alpha, double mu, double A, double B) {
    if (alpha == 1.0) return ratio0(mu, B);
    return ratio1_of_x(alpha, (1.0 - alpha) * (1.0 + alpha) / ((A + B) * (mu + A)), A, mu);
}

/// gamma = 2 (GGX), Dimov 2015 sec. 3.3 = Heitz 2014 eq. 72: Lambda = (A - mu) / (2 mu) = alpha^2 / (2 mu (mu + A)).
inline Ratio ratio2(double a2, double mu, double A) { return {a2, 2.0 * mu * (mu + A)}; }

/// gamma = 3, Dimov 2015 sec. 3.4, printed as (3 a^4 + 2 mu (mu - A) + a^2 (1 + 2 mu (mu - A))) / (4 (1 + a^2) mu A).
/// With mu - A = -a2 / s and s^2 = 2 mu s + a2, the numerator is a2^2 (4 mu s + 1 + 3 a2) / s^2, so with w = a2 / s
///     Lambda = w^2 (4 mu s + 1 + 3 a2) / (4 (1 + a2) mu A),
/// every term positive. w w (...) is ordered so that it underflows only where Lambda does (w < 1e-154 needs mu > 1e50).
inline Ratio ratio3(double a2, double mu, double A) {
    const double s = mu + A, w = a2 / s;
    return {w * (w * (4.0 * mu * s + 1.0 + 3.0 * a2)), 4.0 * (1.0 + a2) * mu * A};
}

/// gamma = 4, Dimov 2015 sec. 3.5, printed as a sum over 16 (a^4 + a^2 + 1) mu A^3 with differences mu - A. With
/// mu - A = -a2 / s again, every difference cleared (the form as first derived,
///     Lambda = v^3/(16 k) [48 mu p^2 + 12 p^2/mu (1 + a2 (5A + 7mu)/s) + N / (mu s^3)],  v = a2/A, p = mu/s,
/// N = 3A + mu + 2 a2 (3A + 5mu) + a2^2 (15A + 37mu), k = a2^2 + a2 + 1), put over one denominator:
///     Lambda = v^3 P / (16 k mu s^3),   P = 48 mu^4 s + 12 mu^2 (s + a2 (5A + 7mu)) + N,
/// every term positive. v (v (v P)) underflows only where Lambda does (v^2 < 1e-308 needs mu > 1e50).
inline Ratio ratio4(double a2, double mu, double A) {
    const double s = mu + A, v = a2 / A, mu2 = mu * mu;
    const double N = 3.0 * A + mu + 2.0 * a2 * (3.0 * A + 5.0 * mu) + a2 * a2 * (15.0 * A + 37.0 * mu);
    const double P = 48.0 * mu2 * mu2 * s + 12.0 * mu2 * (s + a2 * (5.0 * A + 7.0 * mu)) + N;
    return {v * (v * (v * P)), 16.0 * (a2 * a2 + a2 + 1.0) * mu * (s * s * s)};
}

/// ---- in c = cos(theta) in [cos_small, 1]; s2 = (1 - c)(1 + c), Ac = sqrt(c^2 + a2 s2) = A sin(theta) ----
/// (c < cos_small: mu = c to double precision, and the mu forms' asymptote takes over.)
inline constexpr double cos_small = 1e-100;

/// gamma = 0: 1 / (2 mu (mu + B)) = s2 / (2 c (1 + c)).
inline Ratio ratio0_cos(double c, double s2) { return {s2, 2.0 * c * (1.0 + c)}; }
/// gamma = 1: x = (1 - alpha^2) s2 / ((Ac + 1)(c + Ac)); Lambda = (Ac x + c (x - log1p(x))) / (-2 c ln alpha).
inline Ratio ratio1_cos(double alpha, double c, double s2, double Ac) {
    if (alpha == 1.0) return ratio0_cos(c, s2);
    return ratio1_of_x(alpha, (1.0 - alpha) * (1.0 + alpha) * s2 / ((Ac + 1.0) * (c + Ac)), Ac, c);
}
/// gamma = 2: alpha^2 s2 / (2 c (c + Ac)).
inline Ratio ratio2_cos(double a2, double c, double s2, double Ac) { return {a2 * s2, 2.0 * c * (c + Ac)}; }
/// gamma = 3: with t = c + Ac (w = a2 sin / t, 4 mu s = 4 c t / s2, mu A = c Ac / s2),
///     Lambda = a2^2 s2 (4 c t + (1 + 3 a2) s2) / (4 (1 + a2) c Ac t^2),  num = a2 s2 wc (...), wc = a2 / t.
inline Ratio ratio3_cos(double a2, double c, double s2, double Ac) {
    const double t = c + Ac, wc = a2 / t;
    return {a2 * s2 * (wc * (4.0 * c * t + (1.0 + 3.0 * a2) * s2)), 4.0 * (1.0 + a2) * c * Ac * t};
}
/// gamma = 4: with vc = a2 / Ac and t = c + Ac,  Lambda = vc^3 s2 Pc / (16 k c t^3),
///   Pc = 48 c^4 t + 12 c^2 s2 (t + a2 (5 Ac + 7 c)) + Nc s2^2,  Nc = 3Ac + c + 2 a2 (3Ac + 5c) + a2^2 (15Ac + 37c).
inline Ratio ratio4_cos(double a2, double c, double s2, double Ac) {
    const double t = c + Ac, vc = a2 / Ac, c2 = c * c;
    const double Nc = 3.0 * Ac + c + 2.0 * a2 * (3.0 * Ac + 5.0 * c) + a2 * a2 * (15.0 * Ac + 37.0 * c);
    const double Pc = 48.0 * c2 * c2 * t + s2 * (12.0 * c2 * (t + a2 * (5.0 * Ac + 7.0 * c)) + Nc * s2);
    return {vc * (vc * (vc * s2 * Pc)), 16.0 * (a2 * a2 + a2 + 1.0) * c * (t * t * t)};
}

/// gamma = 0..4 at mu in [mu_small, mu_big] (see above).
inline Ratio ratio(double alpha, int gamma, double mu) {
    const double a2 = alpha * alpha;
    switch (gamma) {
        case 0:
            return ratio0(mu, root_sum_squares(mu, 1.0));
        case 1:
            return ratio1(alpha, mu, root_sum_squares(mu, a2), root_sum_squares(mu, 1.0));
        case 2:
            return ratio2(a2, mu, root_sum_squares(mu, a2));
        case 3:
            return ratio3(a2, mu, root_sum_squares(mu, a2));
        default:
            return ratio4(a2, mu, root_sum_squares(mu, a2));
    }
}

/// gamma = 0..4 at c in [cos_small, 1].
inline Ratio ratio_cos(double alpha, int gamma, double c) {
    const double a2 = alpha * alpha, s2 = (1.0 - c) * (1.0 + c);
    if (gamma == 0) return ratio0_cos(c, s2);
    const double Ac = std::sqrt(c * c + a2 * s2);
    switch (gamma) {
        case 1:
            return ratio1_cos(alpha, c, s2, Ac);
        case 2:
            return ratio2_cos(a2, c, s2, Ac);
        case 3:
            return ratio3_cos(a2, c, s2, Ac);
        default:
            return ratio4_cos(a2, c, s2, Ac);
    }
}

}  // namespace gtr_closed

/// Any integer gamma >= 2, generated. With n = gamma - 2,
///   (r^2 + 1)^n = sum_k C(n, k) (1 - alpha^2)^k (r^2 + alpha^2)^(n - k),
/// so P22 = K alpha^(2 gamma) sum_k C(n,k) (1-alpha^2)^k (r^2 + alpha^2)^-(2+k): a positive sum of Student-t-like slope
/// laws, each with P2 = B(1/2, k+3/2) (q^2 + alpha^2)^-(k+3/2) (Walter 2007 eq. 43). Their Lambda integrals, with
/// q = alpha tan(phi) and sin(phi_0) = mu/A, come to I_k = A^-(2k+1) b_k, where the bracket b_k has two exact forms
/// (closed_forms.cpp, brackets()): one with a polynomial integrated exactly by Gauss-Legendre, used for mu < alpha,
/// and one with every term positive, used for mu >= alpha, where the first would cancel by a factor 2k + 2. Then
///   Lambda = (K/mu) sum_k C(n,k) (1-alpha^2)^k B(1/2, k+3/2) alpha^(2(n-k)+3) (alpha/A)^(2k+1) b_k
///          = (K alpha^2) alpha^2 / (mu A) sum_k C(n,k) B(1/2, k+3/2) b_k rho^k alpha^(2n),   rho = (1 - alpha^2)/A^2,
/// a polynomial in rho with positive coefficients, summed by Horner in rho where rho <= 1 and in 1/rho (with
/// alpha^(2n) rho^n = (alpha^2 rho)^n, alpha^2 rho <= 1) where rho > 1: no term overflows, and a power underflows only
/// where Lambda does. gamma <= 31 keeps k <= 29 within the 30-node rule.
double Lambda_gtr_integer_sum(double alpha, int gamma, double mu);

namespace detail {
/// Lambda_gtr_closed beyond [mu_small, mu_big] (and NaN): the asymptotes, out of line.
double Lambda_gtr_closed_far(double alpha, int gamma, double mu);
}  // namespace detail

/// Lambda for integer gamma in [0, 31] and mu > 0: the hand-derived forms above for gamma = 0..4, the generated sum
/// above. Far from the scales alpha and 1, Lambda is its asymptote to every digit: mu^2 Lambda = C (1 + O((1 + alpha^2)
/// / mu^2)) above mu = 1e50 (every GTR tail is r^-4), and mu Lambda = E[q+] - mu/2 + O(mu / alpha) below 1e-100;
/// the forms would overflow their intermediate products there (mu^3 s^3 at mu = 1e70, 1/mu at 1e-309).
inline double Lambda_gtr_closed(double alpha, int gamma, double mu) {
    if (!(mu >= gtr_closed::mu_small && mu <= gtr_closed::mu_big))
        return detail::Lambda_gtr_closed_far(alpha, gamma, mu);
    if (static_cast<unsigned>(gamma) > 4u) return Lambda_gtr_integer_sum(alpha, gamma, mu);  // < 0: its input_error
    return gtr_closed::ratio(alpha, gamma, mu).Lambda();
}

/// G1 = 1 / (1 + Lambda) of the same forms, one division fewer than through Lambda.
inline double G1_gtr_closed(double alpha, int gamma, double mu) {
    if (!(mu >= gtr_closed::mu_small && mu <= gtr_closed::mu_big) || static_cast<unsigned>(gamma) > 4u)
        return 1.0 / (1.0 + Lambda_gtr_closed(alpha, gamma, mu));
    return gtr_closed::ratio(alpha, gamma, mu).G1();
}

}  // namespace smithlab
