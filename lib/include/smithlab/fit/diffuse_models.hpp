/// @file
/// smithlab/fit/diffuse_models.hpp -- the diffuse BRDFs the fitter fits and compares: each model as a free
/// function of its own physical parameters, with its source, and a table of them in the fitter's one shape
/// (DiffuseModel: f(wi, wo, alpha, albedo, constants)).
///
/// Conventions throughout: f is the BRDF (no cosine); wi points toward the light and wo toward the viewer, unit vectors
/// in the macrosurface frame (z = normal), both with z > 0; every model is symmetric in wi and wo. alpha is the GGX
/// roughness (Disney's perceptual roughness squared), albedo in [0, 1]. The functions allocate nothing and never throw;
/// for z > 0 and alpha in (0, 1] none returns NaN.
#pragma once

#include <cmath>
#include <cstddef>
#include <string_view>
#include <vector>

#include "smithlab/geometry.hpp"

namespace smithlab::fit {

// ---- the models in their own parameters -------------------------------------------------------------------------

/// Lambert: albedo / pi.
double lambert(double albedo);

/// Burley 2012, "Physically-Based Shading at Disney" (SIGGRAPH course notes), sec. 5.3:
///     f = albedo/pi (1 + (FD90 - 1)(1 - cos_l)^5)(1 + (FD90 - 1)(1 - cos_v)^5),  FD90 = 0.5 + 2 r cos^2(theta_d),
/// r the perceptual roughness (sqrt(alpha)), theta_d the angle between wi and the half vector.
double disney_diffuse(const Vec3& wi, const Vec3& wo, double perceptual_roughness, double albedo);

/// Oren and Nayar 1994, "Generalization of Lambert's Reflectance Model" (SIGGRAPH), the full functional approximation:
/// its direct term L1 (with C1, C2, C3) plus its interreflection term L2, both divided by E0 cos(theta_i):
///     f = albedo/pi [C1 + cos(phi) C2 tan(beta) + (1 - |cos(phi)|) C3 tan((alpha' + beta)/2)]
///       + 0.17 albedo^2/pi sigma^2/(sigma^2 + 0.13) [1 - cos(phi) (2 beta/pi)^2],
/// alpha' = max(theta_i, theta_o), beta = min, phi the azimuth between them, sigma the standard deviation of the
/// facets' slope angle (radians); C1 = 1 - 0.5 sigma^2/(sigma^2 + 0.33), C2 = 0.45 sigma^2/(sigma^2 + 0.09) sin(alpha')
/// where cos(phi) >= 0 and 0.45 sigma^2/(sigma^2 + 0.09)(sin(alpha') - (2 beta/pi)^3) otherwise,
/// C3 = 0.125 sigma^2/(sigma^2 + 0.09) (4 alpha' beta/pi^2)^2. Can dip below 0 (forward scattering, both grazing, at
/// sigma >~ 0.7): smithlab returns max(0, f).
double oren_nayar(const Vec3& wi, const Vec3& wo, double sigma, double albedo);
/// The same paper's qualitative model (L2 dropped, C3 dropped, C2 simplified): albedo/pi (A + B max(0, cos(phi))
/// sin(alpha') tan(beta)), A = 1 - 0.5 sigma^2/(sigma^2 + 0.33), B = 0.45 sigma^2/(sigma^2 + 0.09).
double oren_nayar_qualitative(const Vec3& wi, const Vec3& wo, double sigma, double albedo);

/// Fujii 2012/2013, "A tiny improvement of Oren-Nayar reflectance model" (mimosa-pudica.net/improved-oren-nayar.html):
///     f = albedo/pi (A + B s/t),  s = wi.wo - (n.wi)(n.wo),  t = 1 if s <= 0 else max(n.wi, n.wo),
///     A = 1/(1 + (1/2 - 2/(3 pi)) sigma),  B = sigma A.
/// Negative where sigma > 1 and s < 0 (A + B s >= A (1 - sigma)): smithlab returns max(0, f) (a guard, not Fujii's).
double fujii(const Vec3& wi, const Vec3& wo, double sigma, double albedo);

/// Portsmouth, Kutz and Hill 2025, "EON: A Practical Energy-Preserving Rough Diffuse BRDF", JCGT 14(1) (the OpenPBR
/// diffuse lobe), roughness r in [0, 1]: the FON single-scattering lobe (Fujii's model at sigma = r, rho = albedo)
/// plus the paper's energy-compensation lobe
///     f_ms = rho_ms/pi (1 - E_F(mu_i))(1 - E_F(mu_o)) / (1 - `<E_F>`),
///     rho_ms = rho^2 `<E_F>` / (1 - rho (1 - `<E_F>`)),
/// with the paper's exact E_F (eon_fon_albedo) and its closed-form average `<E_F>` (eon_fon_average_albedo).
double eon(const Vec3& wi, const Vec3& wo, double r, double albedo);
/// E_F(mu), the FON lobe's directional albedo at rho = 1 (the paper's exact, analytic form; not its fitted
/// approximation): A (1 + r G(mu)/pi), G(mu) = S (acos(mu) - S mu) + (2/3)((S/mu)(1 - S^3) - S), S = sqrt(1 - mu^2).
double eon_fon_albedo(double mu, double r);
/// `<E_F>` = 2 int_0^1 E_F(mu) mu dmu = A (1 + (2/3 - 28/(15 pi)) r).
double eon_fon_average_albedo(double r);
/// EON's directional albedo (the paper's E_EON): rho E_F(mu) + rho_ms (1 - E_F(mu)); exactly 1 at rho = 1.
double eon_albedo(double mu, double r, double albedo);

/// Chan 2018, "Material Advances in Call of Duty: WWII" (SIGGRAPH course, Physically Based Shading), as Unreal
/// Engine 5 writes it (Engine/Shaders/Private/BRDF.ush, Diffuse_Chan), a2 = alpha^2:
///     g = saturate(log2(2/a2 - 1)/18),  Fd = lerp(F0, FdV FdL, saturate(2.2 g - 0.5)),
///     F0 = VoH + (1 - VoH)^5,  FdX = 1 - 0.75 (1 - NoX)^5,
///     Fb = ((34.5 g - 59) g + 24.5) VoH 2^(-max(73.2 g - 21.2, 8.9) sqrt(NoH)) * retro_weight,
///     f = albedo/pi (Fd + Fb).
double chan_2018(const Vec3& wi, const Vec3& wo, double alpha, double albedo, double retro_weight = 1.0);

/// Hammon 2017, "PBR Diffuse Lighting for GGX+Smith Microsurfaces" (GDC), slide "GGX Diffuse Approximation":
///     facing = 0.5 + 0.5 L.V,  rough = facing (a - b facing)(c + N.H)/N.H,
///     smooth = k (1 - (1 - N.L)^5)(1 - (1 - N.V)^5),  single = (1/pi) lerp(smooth, rough, alpha),  multi = m alpha,
/// with the published (a, b, c, k, m) = (0.9, 0.4, 0.5, 1.05, 0.1159). The slide's last line lost its superscripts;
/// its two readings are hammon_2017, albedo (single + albedo multi), and hammon_2017_linear, albedo (single + multi).
/// Read as the BRDF f (no N.L): k = 1.05 = 21/20 is what makes smooth/pi integrate against cos to exactly
/// 1 - (1 - N.V)^5 <= 1 (his normalisation k = 21/(20 pi)); an f cos reading would need N.L on the slide.
struct HammonConstants {
    /// The slide's (a, b, c, k, m), at their published values.
    /// @{
    double rough_a = 0.9, rough_b = 0.4, rough_c = 0.5, smooth = 1.05, multi = 0.1159;
    /// @}
};
/// Hammon's single term, (1/pi) lerp(smooth, rough, alpha).
double hammon_2017_single(const Vec3& wi, const Vec3& wo, double alpha, const HammonConstants& k);
/// The first reading: albedo (single + albedo multi).
double hammon_2017(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const HammonConstants& k = {});
/// The second reading: albedo (single + multi).
double hammon_2017_linear(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const HammonConstants& k = {});

/// smithlab's own family (designed from the traced data, `smithlab fit`): Hammon's single term with the roughness
/// blend t = alpha^p instead of alpha (the traced single-event light turns rough faster than linearly in alpha), and a
/// multiple-scattering lobe that grows as alpha^q with a term in 1 - facing, so that it can lean toward or away from
/// forward scattering (the traced k >= 2 light of GGX alpha = 1 is 1.85x brighter toward forward grazing than at
/// normal incidence, and dimmer toward grazing retro-reflection):
///     single = (1/pi) lerp(smooth, rough, alpha^p)   (smooth, rough as Hammon's, constants a, b, c, k),
///     multi  = m alpha^q (1 + u (1 - facing)),  facing = 0.5 + 0.5 L.V,
///     f = albedo (single + albedo multi).
/// At (p, q, u) = (1, 1, 0) it is Hammon 2017: those are its starting constants.
struct Smithlab2026Constants {
    /// Hammon's constants a, b, c, k and m.
    HammonConstants hammon;
    /// The roughness blend's exponent p, the multiple-scattering lobe's exponent q and its weight u of 1 - facing.
    /// @{
    double p = 1.0, q = 1.0, u = 0.0;
    /// @}
};
/// The model at constants k, as above.
double smithlab_2026(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const Smithlab2026Constants& k);

// ---- the fitter's table -----------------------------------------------------------------------------------------

/// f(wi, wo): the BRDF (no cosine), wi toward the light, wo toward the viewer, unit vectors in the macrosurface frame
/// (z = normal), both z > 0; alpha the GGX roughness (Disney's perceptual roughness squared); albedo in [0, 1];
/// c the model's free constants (parameters.size() of them; may be null when there are none).
using DiffuseFn = double (*)(const Vec3& wi, const Vec3& wo, double alpha, double albedo, const double* c);

/// The values a free constant can take where the model means what its source says: lo < c < hi (an infinite bound where
/// none applies), and why. A fit whose constant ends at or beyond a bound has left the model's own domain.
struct ParameterRange {
    /// The bounds, lo < c < hi.
    /// @{
    double lo = -INFINITY, hi = INFINITY;
    /// @}
    std::string_view why;  ///< one line, e.g. "sigma = s alpha, a slope angle's standard deviation: at most pi/2"
};

/// A diffuse model of the fitter's table: its name, free constants and their published values, its source, and f.
struct DiffuseModel {
    std::string_view name;                     ///< e.g. "hammon-2017"
    std::vector<std::string_view> parameters;  ///< names of the free constants; empty for a fixed baseline
    std::vector<double> published;             ///< their published values (a fit's start, the fixed baseline)
    std::string_view source;                   ///< citation, one line
    /// The BRDF.
    DiffuseFn f;
    /// Its starting constants make a model of its own, measured as a baseline; false where they make another one
    /// (smithlab-2026 starts at hammon-2017).
    bool own_baseline = true;
    std::vector<ParameterRange> ranges = {};  ///< per parameter (empty: none bounded)
};

/// Where constant i of m is at or beyond its range: the range, else nullptr.
const ParameterRange* outside_range(const DiffuseModel& m, std::size_t i, double value);

/// All of them, in a fixed order: lambert, disney, oren-nayar (sigma = s alpha, s free, published 0.5: Hammon's
/// comparison), oren-nayar-sqrt2 (sigma = alpha/sqrt(2)), oren-nayar-qualitative (sigma = 0.5 alpha), fujii
/// (sigma = s alpha, s free, start 1), eon (r = clamp(c alpha, 0, 1), c free, start 1), chan-2018 (retro weight 1),
/// hammon-2017, hammon-2017-linear (rough_a, rough_b, rough_c, smooth, multi free), smithlab-2026 (Hammon's constants
/// and p, q, u free; no baseline of its own).
const std::vector<DiffuseModel>& diffuse_models();
/// The model named `name`; input_error naming it and listing the known names otherwise.
const DiffuseModel& find_diffuse_model(std::string_view name);

}  // namespace smithlab::fit
