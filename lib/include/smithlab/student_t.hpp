/// @file
/// smithlab/student_t.hpp -- the Student's t-distribution of slopes (STD): Ribardiere, Bringier, Meneveaux, Simonot
/// 2017, "STD: Student's t-Distribution of Slopes for Microfacet Based BSDFs", Computer Graphics Forum 36(2).
///
/// Its slopes follow a bivariate Student's t law of roughness alpha and shape gamma > 3/2 (here >= 1.65, below):
///     P22(r^2) = (1 / (pi alpha^2)) (1 + r^2 / ((gamma - 1) alpha^2))^-gamma,   D = P22 / cos^4 theta_m,
/// normalized for every gamma > 1 (integral of pi P22 d(r^2) = 1). gamma = 2 is GGX of the same alpha, and as
/// gamma -> inf (1 + r^2/(g alpha^2))^-gamma -> exp(-r^2/alpha^2): Beckmann of the same alpha (the paper and its
/// supplement, "STD = Beckmann when gamma -> inf"; tests/test_student_t.cpp checks both). Lambda needs gamma > 3/2
/// (the slopes' first moment); as gamma -> 3/2 Lambda -> inf at every mu.
#pragma once

namespace smithlab {

/// The STD of Ribardiere et al. 2017 at roughness alpha and shape gamma (the file comment); made by student(), which
/// checks the domain and computes P.
struct StudentT {
    /// The roughness alpha > 0 (the slope scale: the lobe is GGX's at gamma = 2, Beckmann's as gamma -> inf).
    double alpha;
    /// The shape gamma in [student_min_gamma, student_max_gamma]: the slope density's tail falls like r^(-2 gamma).
    double gamma;
    double P;  ///< Lambda's prefactor Gamma(gamma - 1/2) / Gamma(gamma) sqrt(gamma - 1) / (4 (gamma - 3/2) sqrt(pi))

    /// D(cos theta_m) = P22(tan^2) / cos^4, with sin^2 = (1 - c)(1 + c) (exact at the pole); 0 for c <= 0. For
    /// gamma < 2 D grows without bound towards the horizon (like cos^(2 gamma - 4)); it is finite at every c > 0.
    double D(double cos_theta_m) const;
    /// P22(r^2) as above: the power by log1p near r = 0, by pow beyond, one exponential near its underflow; no overflow
    /// at any r^2.
    double slope_density(double r2) const;

    /// Smith's Lambda in closed form (student_t.cpp): the paper's eq. 13, written so that it keeps its digits
    /// (relative error <= 6e-15 measured against a 50-digit quadrature, tests/test_student_t.cpp).
    double Lambda(double mu) const;

    /// D cos sampling. The D cos mass beyond r^2 is pi times the integral of P22 from r^2 to inf:
    ///     S(r^2) = (1 + r^2 / ((gamma - 1) alpha^2))^-(gamma - 1)   (GGX's alpha^2/(alpha^2 + r^2) at gamma = 2,
    /// Beckmann's exp(-r^2/alpha^2) as gamma -> inf), inverted as r^2 = (gamma - 1) alpha^2 (v^(-1/(gamma - 1)) - 1):
    /// the paper's importance sampling of the STD (its tan^2 = (xi^(1/(1-gamma)) - 1)(gamma - 1) alpha^2), in the
    /// survival v = 1 - xi, with expm1/log1p near v = 1 and r = 0 so that both ends keep their digits.
    /// @{
    double Dcos_sf(double r2) const;
    double Dcos_r2(double v) const;
    /// @}

    /// The capability "GGX of this alpha" (ndf.hpp): at gamma = 2 P22 = alpha^2 / (pi (alpha^2 + r^2)^2) is GGX's;
    /// NaN at every other gamma.
    double ggx_alpha() const;
};

/// The accepted domain: alpha in [1e-50, 1e50] (as GGX and Beckmann), gamma in [1.65, 1e6]. Near gamma = 3/2 the
/// slope law's r^(-2 gamma) tail leaves a fraction ~(R / alpha)^(3 - 2 gamma) of Lambda, and of the law P22 r^2 dr
/// the visible normals draw from, beyond any slope R: the NDF-agnostic code cannot hold that (the quadrature routes of
/// smith.hpp reach R ~ 1e100 and miss 1e-10 of Lambda at gamma = 1.55; the visible-normal tables span tan^2 up to 1e100
/// and refuse a law with more than 1e-12 beyond tan^2 = 2e98, which at alpha = 1 is gamma < 1.62), though the closed
/// form has no such limit; at gamma -> 3/2 every Lambda -> inf. At gamma = 1e6 the law is within ~1e-6 of Beckmann's
/// across its lobe (P22 / P22_Beckmann - 1 = (x^2/2 - x) / (gamma - 1), x = r^2 / alpha^2), and 1e6 is where GTR stops.
/// @{
inline constexpr double student_min_gamma = 1.65;
inline constexpr double student_max_gamma = 1e6;
/// @}
/// The STD at (alpha, gamma), with its prefactor P; input_error naming the parameter outside the accepted domain.
StudentT student(double alpha, double gamma);

}  // namespace smithlab
