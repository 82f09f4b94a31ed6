/// @file
/// smithlab/gtr/gtr.hpp -- the Generalized Trowbridge-Reitz distribution (Burley 2012, eq. in appendix B;
/// Dimov 2015 eq. 1**) for alpha in (0, 1] and every real gamma >= 0:
///     D(theta) = c / (1 + (alpha^2 - 1) cos^2 theta)^gamma,
///     c = (gamma - 1)(alpha^2 - 1) / (pi (1 - alpha^{2(1-gamma)})).
/// gamma = 2 is GGX, gamma = 1 the log limit c = (alpha^2 - 1) / (pi ln alpha^2), gamma = 0 and alpha = 1 give 1/pi.
#pragma once

#include <cmath>
#include <numbers>

#include "smithlab/gtr/closed_forms.hpp"

namespace smithlab {

/// The GTR distribution at (alpha, gamma) with its prefactor K (the file comment); made by gtr(), which checks the
/// domain.
struct Gtr {
    /// The roughness alpha in [1e-50, 1] (GGX's alpha at gamma = 2).
    double alpha;
    /// The shape gamma in [0, gtr_max_gamma]: 2 is GGX, 1 the log limit, larger gamma a narrower, Beckmann-like lobe.
    double gamma;
    double K;  ///< P22 prefactor, see gtr_K

    /// D = K t^gamma with t = alpha^2 / (sin^2 + alpha^2 cos^2) in [alpha^2, 1] (sin^2 = (1-c)(1+c): exact at the
    /// pole).
    double D(double cos_theta_m) const;
    /// Burley 2012's D as a slope density, overflow-safe (docs/math.md): with
    /// w = alpha^2/(r^2 + alpha^2), t = w (1 + r^2) in [alpha^2, 1],
    ///     P22 = K t^(gamma - 2) w^2.
    /// Written as (1 + r^2)^(gamma-2) (r^2 + alpha^2)^-gamma it overflows to inf*0 in the far tail at gamma = 7.
    double slope_density(double r2) const;

    /// Closed forms exist for every integer gamma (Dimov 2015 sec. 3 for 0..4, generated above); see closed_forms.hpp.
    /// Inline: the closed forms are a renderer's hot path; the throw is out of line.
    /// @{
    bool has_closed_Lambda() const { return gtr_has_closed_form(gamma); }
    double Lambda(double mu) const {
        if (!has_closed_Lambda()) no_closed_Lambda();
        return Lambda_gtr_closed(alpha, static_cast<int>(gamma), mu);
    }
    /// @}
    [[noreturn]] void no_closed_Lambda() const;  ///< input_error naming gamma
    /// Dimov 2015 section 5: natural cubic spline in gamma through G1 at gamma = 0..4, gamma clamped to 4 above;
    /// the spline's G1 clamped to [0, 1] (Lambda_of_interpolated_G1).
    double Lambda_spline(double mu) const;

    /// D cos sampling, Burley 2012 appendix B (its cos^2 inversion), written for the survival S = 1 - F in r^2 with
    /// t = sin^2 + alpha^2 cos^2 = (alpha^2 + r^2)/(1 + r^2): with e = 1 - gamma, L = ln(1/alpha^2) and
    /// L_c = ln(1/t) = log1p((1 - alpha^2) / (alpha^2 + r^2)),
    ///     S = exp(e (L - L_c)) expm1(e L_c) / expm1(e L)   (-> L_c / L at gamma = 1; 1/(1 + r^2) at alpha = 1),
    ///     L_c(v) = -log1p(v expm1(-e L)) / e,  r^2 = (1 - alpha^2) / expm1(L_c) - alpha^2.
    /// @{
    double Dcos_sf(double r2) const;
    double Dcos_r2(double v) const;
    /// @}

    /// The capability "GGX of this alpha" (smithlab/ndf.hpp): at gamma = 2, D = alpha^2 / (pi (1 + (alpha^2 - 1)
    /// cos^2)^2) is GGX (Burley 2012, appendix B); NaN at every other gamma.
    double ggx_alpha() const;
};

/// K = (1 - alpha^2)/(pi alpha^2) * (gamma - 1) / (1 - alpha^{2(gamma - 1)}), evaluated with expm1/log1p so that
/// the 0/0 at gamma -> 1 (-> 1/(-2 ln alpha)) and at alpha -> 1 (-> 1/pi overall) keep every digit.
/// Inline: the family generator (gtr/tools/family_gen.cpp) uses it without the library.
inline double gtr_K(double alpha, double gamma) {
    constexpr double pi = std::numbers::pi;
    if (alpha == 1.0) return 1.0 / pi;                          // uniform D
    const double one_minus_a2 = (1.0 - alpha) * (1.0 + alpha);  // not 1 - alpha*alpha: 5 digits at alpha = 0.999999
    const double log_a = std::log(alpha);
    const double y = 2.0 * (gamma - 1.0) * log_a;  // (gamma - 1) is exact near 1 (Sterbenz)
    // (gamma - 1) / (-expm1(y)) = 1 / (-2 ln alpha * expm1(y)/y), and expm1(y)/y -> 1 as y -> 0.
    const double exprel = (y == 0.0) ? 1.0 : std::expm1(y) / y;
    return one_minus_a2 / (pi * alpha * alpha) / (-2.0 * log_a * exprel);
}

/// The accepted domain: alpha in [1e-50, 1] (below, alpha^6 underflows in the closed forms), gamma in [0, 1e6].
/// Large gamma is a Beckmann-like lobe of width alpha / sqrt(gamma) (t^gamma ~ exp(-gamma r^2 / alpha^2)); P22, D and
/// the D cos sampler are written for it (log1p of 1 - t), and the 1D quadrature matches the 50-digit reference there
/// (tests/test_domain.cpp); 1e6 is as far as that reference reaches (its (r^2 + alpha^2)^gamma at r^2 = 1e120 leaves
/// cpp_bin_float's exponent range near gamma = 2.7e6), and a lobe narrower than alpha / 1000 is no material.
inline constexpr double gtr_max_gamma = 1e6;
/// GTR at (alpha, gamma), its K computed (gtr_K); input_error naming the parameter outside the accepted domain.
Gtr gtr(double alpha, double gamma);

/// Lambda and G1 from c = cos(theta_v) (a renderer holds the cosine; mu = cot = c / sqrt(1 - c^2) costs a root and a
/// division more, and 1 - c^2 loses digits near c = 1). Integer gamma <= 4 by the forms in c (closed_forms.hpp,
/// gtr_closed::ratio_cos): exact to a few ulp from grazing (c -> 0, Lambda -> inf) to normal (c = 1: Lambda = 0,
/// G1 = 1), with sin^2 as (1 - c)(1 + c). Other gamma: mu = c / sqrt((1 - c)(1 + c)), then the mu route
/// (Lambda_from_cos in smith.hpp). c in [0, 1]; c > 1 (rounding) is read as 1; c < 0 (below the surface): G1 takes |c|
/// (Walter 2007 eq. 44) and Lambda is Smith's -1 - Lambda(|c|), as smithlab::Lambda(ndf, mu) gives; NaN gives NaN.
double Lambda_from_cos_slow(const Gtr& ndf, double c);  ///< gamma > 4, non-integer gamma, c < cos_small, c < 0, NaN
/// Lambda from c = cos(theta_v), as described above: the forms in c for integer gamma <= 4, else Lambda_from_cos_slow.
inline double Lambda_from_cos(const Gtr& ndf, double c) {
    if (c >= gtr_closed::cos_small && ndf.gamma <= 4.0 && ndf.has_closed_Lambda())
        return c >= 1.0 ? 0.0 : gtr_closed::ratio_cos(ndf.alpha, static_cast<int>(ndf.gamma), c).Lambda();
    return Lambda_from_cos_slow(ndf, c);
}
/// G1 = 1 / (1 + Lambda(|c|)) from c = cos(theta_v), by the same routes.
inline double G1_from_cos(const Gtr& ndf, double c) {
    const double a = std::abs(c);
    if (a >= gtr_closed::cos_small && ndf.gamma <= 4.0 && ndf.has_closed_Lambda())
        return a >= 1.0 ? 1.0 : gtr_closed::ratio_cos(ndf.alpha, static_cast<int>(ndf.gamma), a).G1();
    return 1.0 / (1.0 + Lambda_from_cos_slow(ndf, a));
}

}  // namespace smithlab
