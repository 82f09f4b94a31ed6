/// @file
/// smithlab/gtr/interpolants.hpp -- G1 / Lambda of GTR at any real gamma, interpolated across gamma through the
/// closed forms at integer knots gamma = 0..K (K <= 31; gamma clamped to K above, as Dimov 2015 sec. 6 clamps to 4).
/// Dimov's natural cubic spline of G1 through 0..4 (spline.hpp) is the baseline these try to beat: other GSL
/// interpolants (Akima; Steffen's monotone one), other quantities (Lambda, log Lambda), more knots.
#pragma once

#include <string>

namespace smithlab {

/// How an interpolant across gamma is made: the GSL interpolant, the quantity it interpolates and the last knot.
struct GammaInterpolant {
    /// The interpolant: GSL's natural cubic spline, Akima's, or Steffen 1990's monotone one.
    enum class Kind { cspline, akima, steffen } kind = Kind::cspline;  ///< GSL: natural cubic, Akima, Steffen 1990
    /// The quantity interpolated at the knots: G1, Lambda or ln Lambda.
    enum class Quantity { G1, Lambda, log_Lambda } quantity = Quantity::log_Lambda;  ///< ln Lambda by default
    int max_knot = 4;  ///< knots at gamma = 0, 1, ..., max_knot; 4 <= max_knot <= 31
};

/// "interp-akima-loglambda-k10" and the like, and a one-line description for --list-methods.
/// @{
std::string name_of(const GammaInterpolant& how);
std::string description_of(const GammaInterpolant& how);
/// @}

/// alpha in (0, 1], gamma >= 0, mu finite > 0. An interpolated G1 outside [0, 1] (Akima overshoots both ways at
/// small alpha) is clamped to it, i.e. Lambda = 0 or +inf, and an interpolated Lambda below 0 is clamped to 0: the
/// report shows such failures rather than hiding them. Outside mu in [1e-100, 1e100] the interpolant at the end of
/// that range is carried on by the asymptotes C/mu^2 and E[q+]/mu, as the knots are.
double Lambda_gtr_interpolated(double alpha, double gamma, double mu, const GammaInterpolant& how);

}  // namespace smithlab
