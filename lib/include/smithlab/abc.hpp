/// @file
/// smithlab/abc.hpp -- the ABC microfacet NDF of Low, Kronander, Ynnerman, Unger 2012, "BRDF Models for Accurate and
/// Efficient Rendering of Glossy Surfaces", ACM TOG 31(1): the distribution of their microfacet model.
///
/// D(m) = A / (1 + b (1 - cos theta_m))^c, b > 0, c > 0 (Low et al. 2012, the ABC form A / (1 + B x)^C with
/// x = 1 - cos theta_m; A here is not a free parameter but fixed by smithlab's normalization, below). Fitted to
/// measured BRDFs (the MERL set among them), it reproduces what neither GGX nor Beckmann does with one parameter: a
/// sharp peak (b c large) on a wide glossy base. D falls monotonically from A at the pole to A (1 + b)^-c at the
/// horizon, so for every b, c > 0 the slope density keeps a GGX-like tail P22 ~ A (1 + b)^-c r^-4 (r = tan theta_m);
/// nothing grows towards the horizon. Near the pole 1 - cos ~ r^2 / 2 and (1 + b r^2 / 2)^-c ~ exp(-b c r^2 / 2) for
/// large c: the lobe is Beckmann's of alpha = sqrt(2 / (b c)), i.e. b = 2 / (c alpha^2) (abc_b_from_alpha; the tests
/// measure the gap in Lambda, which shrinks like 1/c where alpha is small). Normalization, as for every NDF here
/// (ndf.hpp): integral over the hemisphere of D(m) cos(theta_m) dm = 1, that is
///     A = 1 / (2 pi I(b, c)),   I(b, c) = integral_0^1 (1 - x) (1 + b x)^-c dx   (x = 1 - cos theta_m),
/// I in closed form (detail::abc_integral below, derivation there). Header only: no Lambda in closed form (smithlab's
/// quadrature routes take the slope form), no sampler (sampling.hpp tabulates one).
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/errors.hpp"

namespace smithlab {

class NdfRegistry;  // registry.hpp

namespace detail {

/// b - ln(1 + b) for b >= 0 without the cancellation of the difference (it is ~b^2 / 2). With u = b / (2 + b),
/// ln(1 + b) = 2 atanh(u) = 2 sum_{j odd} u^j / j and b = 2 u / (1 - u) = 2 sum_{j >= 1} u^j, so
///     b - ln(1 + b) = 2 sum_{j >= 2} u^j (1 - [j odd] / j),
/// positive terms, u <= 1/2 for b <= 2 (55 terms at most). Beyond b = 2 the difference loses at most a factor 2.2.
inline double abc_b_minus_log1p(double b) {
    if (b > 2.0) return b - std::log1p(b);
    const double u = b / (2.0 + b);
    double p = u * u, sum = 0.0;
    for (int j = 2; j < 200; ++j, p *= u) {
        const double term = j % 2 ? p * (1.0 - 1.0 / j) : p;
        sum += term;
        if (term < 1e-17 * sum) break;
    }
    return 2.0 * sum;
}

/// phi2(-z) = (e^-z - 1 + z) / z^2 for z >= 0 (phi2(0) = 1/2). Up to z = 4 as e^-z - 1 + z = e^-z (1 - e^z + z e^z)
/// = e^-z sum_{k >= 2} (k - 1) z^k / k!, positive terms:
///     phi2(-z) = e^-z sum_{j >= 0} (j + 1) z^j / (j + 2)!;
/// beyond, directly (the difference z - (1 - e^-z) loses at most a factor 1.33).
inline double abc_phi2_neg(double z) {
    if (z > 4.0) return (std::expm1(-z) + z) / (z * z);
    double t = 0.5, sum = 0.0;  // t = z^j / (j + 2)!
    for (int j = 0; j < 200; ++j) {
        const double term = (j + 1) * t;
        sum += term;
        if (term < 1e-17 * sum) break;
        t *= z / (j + 3);
    }
    return std::exp(-z) * sum;
}

/// I(b, c) = integral_0^1 (1 - x) (1 + b x)^-c dx, b in [1e-8, 1e16], c in (0, 1e4] (abc() below). Derivation:
/// with y = ln(1 + b) and 1 + b x = e^t, b^2 I = N = integral_0^y (e^y - e^t) e^((1 - c) t) dt, and
///  (i)   N = (1 + b) E(1 - c) - E(2 - c),   E(a) = integral_0^y e^(a t) dt = expm1(a y) / a   (= y at a = 0),
///        the printed closed form. It cancels as b -> 0, at every c (N ~ b^2 / 2 against terms ~ b: a factor ~1/b,
///        1e8 at b = 1e-8), and the binomial series in b that would replace it, sum_k binom(-c, k) b^k / ((k+1)(k+2)),
///        alternates with terms ~ (b c)^k / k! (a loss ~e^(b c): 1e280 at b = 0.5, c = 1e3). Used for c < 2, b > 4
///        only, where it loses at most a factor ~3 (measured), with (1 + b)^(1 - c) = (1 + b) (1 + b)^-c by pow
///        (the exponent -c exact: 1 - c rounded would add up to ln(1 + b) x 1.1e-16, 4e-15 at b = 1e16) where
///        |a| y >= 1.
///  (ii)  With m = c - 2, (i) is N = ((1 + b)^-m - 1 + m b) / (m (m + 1)), and (1 + b)^-m - 1 + m b =
///        (e^(-m y) - 1 + m y) + m (b - y):
///            N = (m y^2 phi2(-m y) + (b - ln(1 + b))) / (m + 1),
///        for c >= 2 (m >= 0) two positive terms over a positive denominator, at every b.
///  (iii) With a = 2 - c, N = (e^(a y) - 1 - a b) / (a (a - 1)); since b - y = e^y - 1 - y = sum_{k >= 2} y^k / k!,
///            N = sum_{k >= 2} (y^k / k!) (1 + a + ... + a^(k-2)),
///        positive terms for c < 2 (a in (0, 2)); for b <= 4 (y <= 1.61) at most ~40 of them.
/// Relative error against a 50-digit quadrature of the integral (tests/test_abc.cpp, held to 1e-15): <= 3.9e-16 on its
/// grid and seams; 8e-16 at worst over 4000 random points of the domain against 200 digits.
inline double abc_integral(double b, double c) {
    const double y = std::log1p(b);
    double N;
    if (c >= 2.0) {
        const double m = c - 2.0;  // (ii)
        N = (m * y * y * abc_phi2_neg(m * y) + abc_b_minus_log1p(b)) / (m + 1.0);
    } else if (b <= 4.0) {
        const double a = 2.0 - c;  // (iii): t = y^k / k!, h = 1 + a + ... + a^(k-2)
        double t = 0.5 * y * y, h = 1.0, sum = 0.0;
        for (int k = 2; k < 200; ++k) {
            const double term = t * h;
            sum += term;
            if (term < 1e-17 * sum) break;
            t *= y / (k + 1);
            h = 1.0 + a * h;
        }
        N = sum;
    } else {
        const double X = 1.0 + b, P1 = X * std::pow(X, -c), P2 = X * P1;  // (1 + b)^(1 - c), (1 + b)^(2 - c)
        auto E = [y](double a, double P) {  // (P - 1) / a, P = (1 + b)^a; expm1 where a y is small (a -> 0 at c = 1, 2)
            return a == 0.0 ? y : std::abs(a) * y < 1.0 ? std::expm1(a * y) / a : (P - 1.0) / a;
        };
        N = X * E(1.0 - c, P1) - E(2.0 - c, P2);  // (i)
    }
    return N / (b * b);
}

/// A (1 + q)^-c / t^2 for q >= 0, t >= 1, by exp(-c log1p(q)) (log1p keeps q's digits where 1 + q would drop them;
/// the error is ~c ln(1 + q) ulp, <= ~745 ulp wherever the power is above the underflow), divided by t twice (t^2
/// overflows past t = 1.3e154); where (1 + q)^-c nears its underflow but the quotient need not (A up to 2e19), as one
/// exponential.
inline double abc_scaled_power(double A, double q, double c, double t = 1.0) {
    const double X = c * std::log1p(q), p = std::exp(-X);
    return p > 1e-280 ? A * p / t / t : std::exp(std::log(A) - X - 2.0 * std::log(t));
}

}  // namespace detail

/// The accepted domain: b in [1e-8, 1e16], c in (0, 1e4].
/// b: below 1e-8, D stays within b c <= 1e-4 of the uniform 1/pi (Blinn-Phong of n = 0); above 1e16 the whole peak
/// (1 - cos theta_m ~ 1/b) lies between cos = 1 and the next double below it, where D(cos theta_m) resolves nothing
/// (the slope form would, but D is what a renderer calls). c: fitted ABC lobes have c of order 0.1-10; at c = 1e4
/// (1 + b x)^-c is within ~(b c x)^2 / (2 c) of its limit exp(-b c x) across the lobe, and larger c adds nothing a
/// Gaussian in 1 - cos theta_m does not. Every b, c in the domain keeps A, D and P22 finite (A <= ~2e19 at b = 1e16,
/// c = 1e4, where alpha = sqrt(2 / (b c)) = 1.4e-10, inside the quadrature routes' domain).
///@{
inline constexpr double abc_min_b = 1e-8;
inline constexpr double abc_max_b = 1e16;
inline constexpr double abc_max_c = 1e4;
///@}

/// The ABC NDF D(m) = A (1 + b (1 - cos theta_m))^-c (Low et al. 2012), normalized so that D cos theta_m integrates
/// to 1 over the hemisphere.
struct Abc {
    double b;  ///< the lobe's sharpness B (b > 0); b = 2 / (c alpha^2) matches Beckmann's alpha near the pole
    double c;  ///< the falloff exponent C (c > 0); large c tends to a Gaussian in 1 - cos theta_m
    double A;  ///< 1 / (2 pi I(b, c)): D at the pole

    /// D(cos theta_m) = A (1 + b (1 - cos))^-c (Low et al. 2012); 1 - cos is exact for cos >= 1/2 (Sterbenz). cos > 1
    /// (rounding) reads as 1; 0 for cos <= 0.
    double D(double cos_theta_m) const {
        if (!(cos_theta_m > 0.0)) return 0.0;
        return detail::abc_scaled_power(A, cos_theta_m < 1.0 ? b * (1.0 - cos_theta_m) : 0.0, c);
    }
    /// P22(r^2) = D cos^4 = A (1 + b (1 - cos))^-c / (1 + r^2)^2 (Walter 2007 eq. 42) with 1 - cos = 1 - 1/s =
    /// r^2 / (s (1 + s)), s = sqrt(1 + r^2): no cancellation near the pole, where cos theta_m cannot carry r^2 (at
    /// r^2 = 1e-20 it is 1). No overflow at any r^2 (where s (1 + s) overflows, P22 is 0 in double anyway); 0 at inf.
    double slope_density(double r2) const {
        if (!(r2 < INFINITY)) return 0.0;
        const double s = std::sqrt(1.0 + r2);
        return detail::abc_scaled_power(A, b * (r2 / (s * (1.0 + s))), c, 1.0 + r2);
    }
};

/// b, c in the domain above; throws input_error naming the parameter otherwise.
inline Abc abc(double b, double c) {
    require(b >= abc_min_b && b <= abc_max_b, "abc: b", "in [1e-8, 1e16]", b);
    require(c > 0.0 && c <= abc_max_c, "abc: c", "in (0, 1e4]", c);
    return {b, c, 1.0 / (2.0 * std::numbers::pi * detail::abc_integral(b, c))};
}

/// The b whose lobe near the pole is Beckmann's of roughness alpha at this c: exp(-b c r^2 / 2) = exp(-r^2 / alpha^2),
/// b = 2 / (c alpha^2) (the header's correspondence; exact as c -> inf and alpha -> 0). alpha > 0 and c > 0 finite.
inline double abc_b_from_alpha(double alpha, double c) {
    require(alpha > 0.0 && alpha < INFINITY, "abc_b_from_alpha: alpha", "finite and > 0", alpha);
    require(c > 0.0 && c < INFINITY, "abc_b_from_alpha: c", "finite and > 0", c);
    return 2.0 / (c * alpha * alpha);
}

/// Its registration (abc.cpp), one call in the list of built-ins (registry.cpp): abc(b, c) for every command; a
/// roughness alpha (the fitter's, a scene's grid.alpha) sets b = 2 / (c alpha^2) at the entry's c.
void register_abc(NdfRegistry& r);

}  // namespace smithlab
