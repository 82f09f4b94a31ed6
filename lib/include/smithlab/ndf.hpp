/// @file
/// smithlab/ndf.hpp -- what an isotropic normal distribution function (NDF) is.
///
/// An NDF is any type with `double D(double cos_theta_m) const`, normalized so that
///     integral over the hemisphere of D(m) cos(theta_m) dm = 1                 (Walter et al. 2007, eq. 4).
/// Everything else is optional and detected at compile time:
///   double slope_density(double r2) const  P22 as a function of r^2 = p^2 + q^2 = tan^2(theta_m)
///                                          (Walter 2007 eq. 42: P22 = D cos^4). Built-ins supply it because
///                                          cos(theta_m) near the pole cannot carry the digits of a tiny slope.
///   double Lambda(double mu) const         a closed-form Smith Lambda for mu > 0.
///   double Lambda_spline(double mu) const  an interpolated Lambda (e.g. Dimov's spline across GTR gamma).
///   double Dcos_sf(double r2) const        with m distributed as D(m) cos(theta_m), the survival function of
///                                          r^2 = tan^2(theta_m): pi * integral_r2^inf P22(s) ds (the azimuth
///                                          is uniform);
///   double Dcos_r2(double v) const         and its inverse on (0, 1]: together, an analytic D cos sampler
///                                          (sampling.hpp tabulates one for an NDF without them). The survival
///                                          side keeps the tail's digits: Hammon's sampler draws from a tail of
///                                          mass 1e-15.
///   double ggx_alpha() const               capabilities: the alpha of the GGX (Beckmann) distribution this NDF is
///   double beckmann_alpha() const          exactly, NaN when it is not (at its parameters: GTR is GGX at gamma = 2).
///                                          smithlab then uses that family's closed forms (visible normals in closed
///                                          form, the approximations made for it) without knowing the NDF's name.
#pragma once

#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>

namespace smithlab {

/// An NDF: a type with `double D(double cos_theta_m) const`, normalized as the file comment says (Walter et al. 2007,
/// eq. 4).
template <class N>
concept Ndf = requires(const N& n, double c) {
    { n.D(c) } -> std::convertible_to<double>;
};

/// An NDF's own slope form: `double slope_density(double r2) const`, P22 at r^2 = tan^2(theta_m).
template <class N>
concept HasSlopeDensity = requires(const N& n, double r2) {
    { n.slope_density(r2) } -> std::convertible_to<double>;
};

/// An NDF's closed-form Smith Lambda: `double Lambda(double mu) const` for mu > 0.
template <class N>
concept HasClosedLambda = requires(const N& n, double mu) {
    { n.Lambda(mu) } -> std::convertible_to<double>;
};

/// An NDF's interpolated Lambda: `double Lambda_spline(double mu) const`.
template <class N>
concept HasSplineLambda = requires(const N& n, double mu) {
    { n.Lambda_spline(mu) } -> std::convertible_to<double>;
};

/// An NDF's analytic D cos sampler: the survival function `Dcos_sf(r2)` of r^2 = tan^2(theta_m) and its inverse
/// `Dcos_r2(v)` on (0, 1].
template <class N>
concept HasDcosSampler = requires(const N& n, double x) {
    { n.Dcos_sf(x) } -> std::convertible_to<double>;
    { n.Dcos_r2(x) } -> std::convertible_to<double>;
};

/// The capability `double ggx_alpha() const`: the alpha of the GGX distribution the NDF is, NaN when it is not.
template <class N>
concept HasGgxAlpha = requires(const N& n) {
    { n.ggx_alpha() } -> std::convertible_to<double>;
};

/// The capability `double beckmann_alpha() const`: the alpha of the Beckmann distribution the NDF is, NaN when it is
/// not.
template <class N>
concept HasBeckmannAlpha = requires(const N& n) {
    { n.beckmann_alpha() } -> std::convertible_to<double>;
};

namespace detail {
[[noreturn]] void throw_nonfinite_D(double cos_theta_m, double d);

/// D(m) cos^4(theta_m) at tan^2(theta_m) = r2, from D itself.
template <Ndf N>
double D_cos4(const N& ndf, double r2) {
    if (!(r2 <= 1e120)) return 0.0;
    const double c2 = 1.0 / (1.0 + r2), c = std::sqrt(c2);
    const double d = ndf.D(c);
    if (!std::isfinite(d)) throw_nonfinite_D(c, d);
    return d * c2 * c2;
}
}  // namespace detail

/// P22 as a function of r^2 = tan^2(theta_m): D(m) cos^4(theta_m) (Walter 2007 eq. 42; Hammon 2017 appendix,
/// "Completing (theta_m, phi_m) to (p, q)"). Uses the NDF's own slope form when it has one.
/// From D alone, slopes beyond tan(theta_m) = 1e60 are not evaluated: a slope density falling like r^-4 or faster
/// (every NDF here) puts less than 1e-48 of Lambda there for mu <= 1e12, while a D written with cos^4 in a
/// denominator overflows there. A D that returns inf or NaN anywhere else is an error, not a silent NaN.
template <Ndf N>
double slope_density(const N& ndf, double r2) {
    if constexpr (HasSlopeDensity<N>) return ndf.slope_density(r2);
    else return detail::D_cos4(ndf, r2);
}

/// The core slope scale r0 = 1/sqrt(pi P22(0)) (alpha for GGX and Beckmann: the slope where a lobe of P22(0)'s height
/// would hold all the mass), 1 where P22(0) is 0 or not finite (a plug-in's D(1) = 0): where the quadrature routes put
/// their grazing features and panels (smith.hpp, lambda_fixed.hpp), what their domain is measured in, and where the
/// checks (checks.hpp) split their integrals.
inline double core_slope_scale(double P22_at_pole) {
    return P22_at_pole > 0.0 && P22_at_pole < INFINITY ? 1.0 / std::sqrt(std::numbers::pi * P22_at_pole) : 1.0;
}
/// The core slope scale of `ndf`, from its P22 at the pole.
template <Ndf N>
double core_slope_scale(const N& ndf) {
    return core_slope_scale(slope_density(ndf, 0.0));
}

/// D(m) = P22 / cos^4 = P22(s) (1 + s)^2 (Walter 2007 eq. 42), from the slope density at s = tan^2(theta_m).
inline double D_from_P22(double P22, double s) { return P22 * (1.0 + s) * (1.0 + s); }

/// N seen through D alone: what smithlab derives for a plugged-in NDF (slope form from D, Lambda by quadrature,
/// tabulated samplers), to set beside what N's own members give.
template <Ndf N>
struct DOnly {
    /// The NDF whose D is all that is shown.
    N ndf;
    /// N's D, nothing else of it.
    double D(double cos_theta_m) const { return ndf.D(cos_theta_m); }
};

/// Whether `ndf` has its own slope form P22(r^2) (else smithlab derives it from D through cos theta_m, which
/// cannot carry a slope's digits near the pole: smith.hpp refuses that route below a core scale of 1e-3).
/// Type-erased NDFs answer at run time.
template <Ndf N>
bool has_slope_density(const N& ndf) {
    if constexpr (requires { ndf.has_slope_density(); }) return ndf.has_slope_density();
    else return HasSlopeDensity<N>;
}

/// Whether `ndf` offers a closed-form / spline Lambda. Type-erased NDFs answer at run time.
template <Ndf N>
bool has_closed_Lambda(const N& ndf) {
    if constexpr (requires { ndf.has_closed_Lambda(); }) return ndf.has_closed_Lambda();
    else return HasClosedLambda<N>;
}

/// Whether `ndf` offers an analytic D cos sampler (Dcos_sf and Dcos_r2). Type-erased NDFs answer at run time.
template <Ndf N>
bool has_Dcos_sampler(const N& ndf) {
    if constexpr (requires { ndf.has_Dcos_sampler(); }) return ndf.has_Dcos_sampler();
    else return HasDcosSampler<N>;
}

/// Whether `ndf` offers a spline Lambda. Type-erased NDFs answer at run time.
template <Ndf N>
bool has_spline_Lambda(const N& ndf) {
    if constexpr (requires { ndf.has_spline_Lambda(); }) return ndf.has_spline_Lambda();
    else return HasSplineLambda<N>;
}

/// The capabilities: the alpha of the GGX (Beckmann) distribution `ndf` is, or NaN. Type-erased NDFs answer at run
/// time.
/// @{
template <Ndf N>
double ggx_alpha(const N& ndf) {
    if constexpr (HasGgxAlpha<N>) return ndf.ggx_alpha();
    else return std::numeric_limits<double>::quiet_NaN();
}

template <Ndf N>
double beckmann_alpha(const N& ndf) {
    if constexpr (HasBeckmannAlpha<N>) return ndf.beckmann_alpha();
    else return std::numeric_limits<double>::quiet_NaN();
}
/// @}

}  // namespace smithlab
