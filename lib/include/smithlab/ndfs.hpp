/// @file
/// smithlab/ndfs.hpp -- the classic isotropic NDFs: GGX (Trowbridge-Reitz), Beckmann, Blinn-Phong.
///
/// Each gives D(cos theta_m), its slope form P22(r^2) (Walter 2007 eq. 42), and Lambda in closed form where one
/// exists. Factories validate their parameters and throw input_error naming the bad one. The Student-t (Ribardiere et
/// al. 2017), between GGX and Beckmann, has its own header, included here.
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/student_t.hpp"

namespace smithlab {

/// GGX / Trowbridge-Reitz, Walter 2007 eq. 33: D = alpha^2 / (pi cos^4 (alpha^2 + tan^2)^2).
struct Ggx {
    /// The roughness alpha > 0, the slope scale (made by ggx(), which checks it).
    double alpha;
    /// sin^2 + alpha^2 cos^2 with sin^2 = (1 - c)(1 + c): exact near the pole, where 1 + (alpha^2 - 1) c^2 is not.
    double D(double c) const {
        if (c <= 0.0) return 0.0;
        const double s = (1.0 - c) * (1.0 + c) + alpha * alpha * c * c;
        return alpha * alpha / (std::numbers::pi * s * s);
    }
    /// P22(r^2) = alpha^2 / (pi (alpha^2 + r^2)^2) (Walter 2007 eq. 33 in slopes).
    double slope_density(double r2) const {
        const double s = r2 + alpha * alpha;
        return alpha * alpha / (std::numbers::pi * s * s);
    }
    /// Heitz 2014 eq. 72, rewritten: (sqrt(1 + alpha^2/mu^2) - 1)/2 = alpha^2 / (2 mu (mu + A)), A = sqrt(mu^2 +
    /// alpha^2), as (alpha / (mu + A)) (alpha / (2 mu)): each factor stays in range where alpha^2 / (2 mu (mu + A))
    /// would not (alpha = 1e-50 at mu = 1e-308: the denominator underflows; the true Lambda is 2e257). A by sqrt,
    /// within 1.25 ulp as hypot's is: mu^2 underflowing is harmless (A = alpha then); past mu = 1e150, where mu^2 would
    /// overflow (a predictable branch), by hypot. Between mu = 1e-100 and 1e150 (a predictable branch) as one quotient:
    /// 2 mu (mu + A) lies in [2e-150, 8e300].
    double Lambda(double mu) const {
        if (mu >= 1e-100 && mu < 1e150) return alpha * alpha / (2.0 * mu * (mu + std::sqrt(mu * mu + alpha * alpha)));
        return alpha / (mu + A_of(mu)) * (alpha / (2.0 * mu));
    }
    /// G1 = 1 / (1 + Lambda) = 2 mu / (mu + A), Walter 2007 eq. 34 (2 / (1 + sqrt(1 + alpha^2 tan^2))) times mu / mu:
    /// one root and one division. mu > 0; mu = inf gives 1.
    double G1(double mu) const {
        if (!(mu < 1e150)) return 1.0 / (1.0 + Lambda(mu));
        return 2.0 * mu / (mu + A_of(mu));
    }
    /// A = sqrt(mu^2 + alpha^2), by hypot past mu = 1e150.
    double A_of(double mu) const { return mu < 1e150 ? std::sqrt(mu * mu + alpha * alpha) : std::hypot(mu, alpha); }
    /// D cos sampling, Walter 2007 eq. 35-36 (the blog's arctan form), in v = 1 - u: S = alpha^2 / (alpha^2 + r^2),
    /// tan^2 = alpha^2 (1 - v) / v.
    /// @{
    double Dcos_sf(double r2) const { return alpha * alpha / (alpha * alpha + r2); }
    double Dcos_r2(double v) const { return alpha * alpha * (1.0 - v) / v; }
    /// @}
    /// The capability "GGX of this alpha" (ndf.hpp): visible normals in closed form, the GGX approximations.
    double ggx_alpha() const { return alpha; }
};

/// Beckmann, Walter 2007 eq. 25: D = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4).
struct Beckmann {
    /// The roughness alpha > 0, the slope scale (made by beckmann(), which checks it).
    double alpha;
    /// D(cos theta_m) = exp(-tan^2 / alpha^2) / (pi alpha^2 cos^4); 0 for c <= 0.
    double D(double c) const;
    /// P22(r^2) = exp(-r^2 / alpha^2) / (pi alpha^2).
    double slope_density(double r2) const;
    /// Walter 2007 eq. 26: Lambda = (erf-based) = ierfc(a) / (2 a), a = mu / alpha, ierfc(a) = e^{-a^2}/sqrt(pi) - a
    /// erfc(a), the first repeated integral of erfc (Abramowitz & Stegun 7.2.5), evaluated without cancellation.
    double Lambda(double mu) const;
    /// D cos sampling, Walter 2007 eq. 28-29 (the blog's arctan form): S = exp(-r^2/alpha^2), tan^2 = -alpha^2 ln v.
    /// @{
    double Dcos_sf(double r2) const { return std::exp(-r2 / (alpha * alpha)); }
    double Dcos_r2(double v) const { return -alpha * alpha * std::log(v); }
    /// @}
    /// The capability "Beckmann of this alpha" (ndf.hpp): visible normals in closed form, Walter's rational G1.
    double beckmann_alpha() const { return alpha; }
};

/// Blinn-Phong normalized for D cos: D = (n + 2) / (2 pi) cos^n (Walter 2007 eq. 30). No closed-form Lambda.
struct BlinnPhong {
    /// The exponent n >= 0 (made by blinn(), which checks it).
    double n;
    /// D(cos theta_m) = (n + 2) / (2 pi) cos^n; 0 for c < 0.
    double D(double c) const;
    double slope_density(double r2) const;  ///< (n+2)/(2 pi) (1 + r^2)^{-(n+4)/2}
    /// D cos sampling, Walter 2007 eq. 31-32 in r^2 (the blog's cos = v^{1/(n+2)}): S = cos^{n+2} = (1 +
    /// r^2)^{-(n+2)/2}.
    /// @{
    double Dcos_sf(double r2) const { return std::exp(-0.5 * (n + 2.0) * std::log1p(r2)); }
    double Dcos_r2(double v) const { return std::expm1(-2.0 / (n + 2.0) * std::log(v)); }
    /// @}
};

namespace detail {
/// For a >= 6, by their asymptotic series (A&S 7.1.23, and integrated once; at a >= 6 the smallest term is below
/// e^{-36} = 2e-16 of the sum): sqrt(pi) e^{a^2} erfc(a) and sqrt(pi) e^{a^2} ierfc(a), ierfc(a) = integral_a^inf erfc
/// = e^{-a^2} / sqrt(pi) - a erfc(a) (A&S 7.2.5).
double erfc_scaled_asymptotic(double a);
double ierfc_scaled_asymptotic(double a);
}  // namespace detail

/// G1 and Lambda from c = cos(theta_v) (a renderer holds the cosine), Walter 2007 eq. 34 and Heitz 2014 eq. 72 with
/// tan^2 = s2 / c^2, s2 = sin^2 = (1 - c)(1 + c) (exact near c = 1, where 1 - c^2 is not), Ac = sqrt(c^2 + alpha^2 s2):
///     G1 = 2 c / (c + Ac),   Lambda = alpha^2 s2 / (2 c (c + Ac)),
/// no cancellation from grazing (c -> 0: G1 = 2c / (c + alpha)) to normal (c = 1: s2 = 0, Lambda = 0, G1 = 1).
/// c > 1 (rounding) is read as 1. G1 takes |c| (Walter 2007 eq. 44); Lambda below the surface (c < 0) is Smith's
/// -1 - Lambda(|c|), as smithlab::Lambda(ndf, mu) gives; NaN gives NaN. Generic NDFs: smith.hpp's templates of the
/// same names.
inline double G1_from_cos(const Ggx& ndf, double c) {
    const double a = std::abs(c) > 1.0 ? 1.0 : std::abs(c), a2 = ndf.alpha * ndf.alpha;  // NaN stays NaN
    return 2.0 * a / (a + std::sqrt(a * a + a2 * ((1.0 - a) * (1.0 + a))));
}
/// Lambda from c = cos(theta_v), as above.
inline double Lambda_from_cos(const Ggx& ndf, double c) {
    if (c >= 1e-100) {  // and not NaN. Below, mu = c to double precision: den = 2 c (c + Ac) could underflow.
        c = c > 1.0 ? 1.0 : c;
        const double a2 = ndf.alpha * ndf.alpha, s2 = (1.0 - c) * (1.0 + c);
        return a2 * s2 / (2.0 * c * (c + std::sqrt(c * c + a2 * s2)));
    }
    return c < 0.0 ? -1.0 - Lambda_from_cos(ndf, -c) : ndf.Lambda(c);  // c = 0: inf
}

Ggx ggx(double alpha);            ///< alpha in [1e-50, 1e50]
Beckmann beckmann(double alpha);  ///< alpha in [1e-50, 1e50]
BlinnPhong blinn(double n);       ///< n >= 0

}  // namespace smithlab
