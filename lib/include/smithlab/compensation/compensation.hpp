/// @file
/// smithlab/compensation/compensation.hpp -- energy compensation of specular multiple scattering, for any NDF.
///
/// E(mu), the directional albedo of single scattering off mirror facets (F = 1), with the height-correlated G2
/// (Walter, Marschner, Li, Torrance 2007, eq. 20; smith.hpp, G2_from_Lambdas):
///     E(mu_i) = integral over the hemisphere of f_ss(wi, wo) cos theta_o dwo,  f_ss = D(h) G2 / (4 cos_i cos_o),
/// and its cosine-weighted average E_avg = 2 integral_0^1 E(mu) mu dmu (Kulla and Conty 2017, "Revisiting Physically
/// Based Shading at Imageworks", SIGGRAPH course slides, "Energy compensation"). From them, their compensation lobe
///     f_ms(wi, wo) = (1 - E(mu_i)) (1 - E(mu_o)) / (pi (1 - E_avg)),
/// whose albedo is 1 - E(mu_i), so that single + compensation is a white furnace; for coloured facets it is scaled by
///     F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)),  F_avg = 2 integral_0^1 F(mu) mu dmu
/// (their "Fresnel" slide: the energy after k >= 2 bounces, F_avg^k E_avg (1 - E_avg)^(k-1), summed); and Turquin's
/// scale of the single-scattering lobe, f = f_ss (1 + F0 (1 - E(mu_v)) / E(mu_v)) (Turquin 2019, "Practical multiple
/// scattering compensation for microfacet models", Weta tech report), mu_v the direction held fixed when the albedo
/// is taken: the view direction in a renderer, wi in this library's E(mu_i).
///
/// The quadrature (compensation.cpp): over microfacet normals in slope space, m ~ (p, q, 1) = (r cos phi, r sin phi,
/// 1), phi from wi's azimuth. With D(m) cos(theta_m) dm = P22 dp dq (Walter eq. 42) and wo = reflect(wi, m) (dwo = 4
/// <wo.m> dm, Walter eq. 14),
///     E(mu_i) = (1 / cos_i) integral P22(r^2) (cos_i + sin_i r cos phi) G2(wi, wo(r, phi)) F(wi.m) r dr dphi
/// over wo.z > 0, which is cos phi > -cos_i (1 - r^2) / (2 sin_i r): every phi below r1 = cos_i / (1 + sin_i)
/// (theta_m < 45 - theta_i / 2), |phi| < phi_max(r) up to r_max = (1 + sin_i) / cos_i (theta_m < 45 + theta_i / 2).
/// The horizon is the only kink of the integrand (G2 itself is analytic through wo.z = 0: mu Lambda(mu) is, for
/// a slope law analytic at 0, lambda_table.hpp), so on [0, r1] x [0, pi] and on {r1 < r < r_max, phi < phi_max}
/// in (u, t), r = r1 (r_max / r1)^S(u), S = u^2 (3 - 2u), phi = phi_max(r) t (S' = 0 at both ends turns the
/// (r - r1)^(3/2) and (r_max - r)^(3/2) ends of the radial integrand into powers of u; ln r spreads r_max / r1 ~ 4 /
/// mu^2 at grazing incidence), globally adaptive 21-point Gauss-Kronrod (GSL's QAG, quadrature.hpp) meets its relative
/// tolerance in a few panels. Measured: E within 1e-15 of the integral over wo of the BRDF, 8e-14 of this route at
/// 1e-13; a 32 x 32 GGX table with E_avg in 0.6-0.9 s of one core (tests/test_compensation.cpp). E(0) = 1 is the limit:
/// at grazing incidence G2 / cos_i -> 1 / lim mu Lambda(mu) = 1 / E[q+] and every visible normal reflects upward.
/// Lambda is the NDF's closed form, else a LambdaTable (lambda_table.hpp) of the given tolerance built once per NDF: a
/// relative error d in Lambda moves E by less than d.
///
/// The dielectric albedos (dielectric(mu, eta); compensation.cpp, dielectric_albedos_at): E_R and E_T in one pass over
/// the normals that see wi, in (theta_m, phi), of (wi.m / cos theta_m) {F G2_R, (1 - F) G2_T} (Walter 2007, eqs. 20-22
/// and 40; G2 across the surface B(1 + Lambda_i, 1 + Lambda_o), Heitz 2014 eq. 101). At a fixed theta_m every kink is a
/// value of c = wi.m, which is monotone in phi: the reflected horizon c = cos_i / (2 cos theta_m) and, from inside
/// (eta < 1), the critical angle c = sqrt(1 - eta^2) and the refracted horizon c = (cos_i^2 + cos^2 theta_m (1 -
/// eta^2)) / (2 cos theta_m cos_i). The inner integral is split there (above the critical angle in w, c = c_crit +
/// (c_max - c_crit) sin^2 w, where both of its square-root ends are analytic), the outer one where a break point enters
/// or leaves [0, pi] or two meet, all in closed form; one globally adaptive 21-point Gauss-Kronrod over the pieces
/// takes R and T each to the relative tolerance. Measured (GGX, alpha 0.01 to 1, eta 1.1, 1.5, 2.5 and their inverses,
/// tolerance 1e-8, one core): 0.5-2.9 ms a value, 1.3 on average; R within 2.5e-9 and T within 5e-13 of the integrals
/// over wo of single_scattering.hpp (tests/test_compensation.cpp). At mu = 0 the grazing limits, as for E.
#pragma once

#include <cmath>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "smithlab/compensation/albedo_grid.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fast_lambda.hpp"
#include "smithlab/fresnel.hpp"
#include "smithlab/lambda_table.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::compensation {

/// The tables' quadrature tolerance: values to ~1e-8 relative, far below their interpolation error ~5e-4 (albedo_grid).
inline constexpr double table_tolerance = 1e-8;

/// How E(mu) and E_avg are computed: the quadrature's tolerance, the G2 form and the LambdaTable of an NDF without a
/// closed-form Lambda.
struct AlbedoOptions {
    double tolerance = 1e-10;  ///< relative, of each Gauss-Kronrod integral (inner ones at a tenth of it)
    /// The G2 the single scattering uses: height-correlated (Walter 2007 eq. 20's Smith G2 as Heitz 2014 eq. 99 and
    /// 101 write it) or separable, G1(wi) G1(wo) (G2Form::uncorrelated; Heitz 2014 eq. 98), as renderers differ.
    G2Form g2 = G2Form::height_correlated;
    /// For an NDF without a closed-form Lambda: the LambdaTable's (its estimate is ~5x pessimistic, README).
    LambdaTableOptions lambda_table = {.tolerance = 1e-8};
};

namespace detail {
/// The quadrature above for one mu in [0, 1] of a reflection off facets of reflectance F(cos wi.m) (null: mirror
/// facets, 1), with G2 of the given form; P22(r^2), Lambda(cot theta >= 0). slope_scale > 0 (masking_cot) splits the
/// slopes below r1 into panels [0, s], [s, 4 s], [4 s, 16 s], ...: a slope law with a light tail (Beckmann's
/// exp(-r^2 / alpha^2)) is 0 to the last bit at every node of one panel [0, r1] at small alpha (E(1) was 0 for
/// Beckmann at alpha 5e-5), never at those of its own panel.
double single_scattering_albedo(FunctionRef P22, FunctionRef Lambda, const FunctionRef* F, double mu, double tolerance,
                                G2Form form = G2Form::height_correlated, double slope_scale = 0.0);
/// {E_R, E_T} of a dielectric interface of relative index eta (below over above) for one mu in [0, 1], both G2 forms:
/// the quadrature of the last paragraph of this header's comment (the grazing limits at mu = 0).
std::pair<double, double> dielectric_albedos(FunctionRef P22, FunctionRef Lambda, double mu, double tolerance,
                                             double eta, G2Form form);
/// 2 integral_0^1 e(mu) mu dmu, tanh-sinh (smooth or log-like behaviour at mu = 0 costs no extra panels).
double cosine_average(FunctionRef e, double tolerance);
}  // namespace detail

/// E(mu) and E_avg of one NDF: holds its Lambda (closed form or table), built once; read-only after construction.
template <Ndf N>
class SingleScatteringAlbedo {
public:
    /// Holds a copy of `ndf` and builds its Lambda (a LambdaTable of opts.lambda_table where it has no closed form).
    explicit SingleScatteringAlbedo(const N& ndf, const AlbedoOptions& opts = {})
        : ndf_(ndf),
          Lambda_(ndf_, opts.lambda_table),
          opts_(opts),
          masking_cot_(compensation::masking_cot([this](double m) { return Lambda_(m); })) {}

    /// E(mu), mu = cos theta_i in [0, 1] (input_error outside), mirror facets.
    double operator()(double mu) const { return albedo(mu, nullptr); }
    /// The same with facets of Fresnel reflectance F(cos wi.m) (e.g. fresnel_conductor): the single-scattering
    /// albedo of coloured facets, E_F(mu).
    template <class Fresnel>
    double operator()(double mu, const Fresnel& F) const {
        const FunctionRef f(F);
        return albedo(mu, &f);
    }
    /// A dielectric interface of relative index eta (below over above; 1 / n from inside a medium of index n): the
    /// directional albedos of single reflection, E_R (facets of reflectance F(wi.m), Walter 2007 eq. 20 and 22), and
    /// of single transmission, E_T (eq. 21). Their sum is the albedo Turquin 2019 divides the dielectric BSDF by.
    struct Dielectric {
        /// E_R, the albedo of single reflection, and E_T, that of single transmission, each in [0, 1].
        ///@{
        double R = 0.0, T = 0.0;
        ///@}
    };
    /// E_R and E_T at mu = cos theta_i in [0, 1] for relative index eta, with the options' G2 and tolerance.
    Dielectric dielectric(double mu, double eta) const {
        auto P22 = [&](double r2) { return slope_density(ndf_, r2); };
        auto L = [&](double m) { return Lambda_(m); };
        const auto [R, T] = detail::dielectric_albedos(P22, L, mu, opts_.tolerance, eta, opts_.g2);
        return {R, T};
    }
    /// E_avg = 2 integral_0^1 E(mu) mu dmu (Kulla and Conty 2017).
    /// The average's own tolerance is 100x E's, its values of E at 10x (a relative error of 1e-9 in E moves E_avg by
    /// less than that).
    double average() const {
        return detail::cosine_average([&](double mu) { return albedo(mu, nullptr, 10.0 * opts_.tolerance); },
                                      100.0 * opts_.tolerance);
    }
    /// 1 - E_avg = 2 integral_0^1 (1 - E(mu)) mu dmu, to a relative tolerance of its own (100x E's): the energy single
    /// scattering misses, which Kulla and Conty's lobe is divided by. At small alpha it is ~alpha^2 (1e-7 at alpha
    /// 1e-4 for GGX), far below what 1 - average() keeps; E's own error (its tolerance, relative to E ~ 1) bounds it.
    double missing() const {
        return detail::cosine_average([&](double mu) { return 1.0 - albedo(mu, nullptr); }, 100.0 * opts_.tolerance);
    }

    /// The scale of a table's warped cosine axis for this NDF (albedo_grid.hpp: warp_scale of its masking_cot).
    double warp_scale() const { return compensation::warp_scale(masking_cot_); }

private:
    double albedo(double mu, const FunctionRef* F) const { return albedo(mu, F, opts_.tolerance); }
    double albedo(double mu, const FunctionRef* F, double tolerance) const {
        auto P22 = [&](double r2) { return slope_density(ndf_, r2); };
        auto L = [&](double m) { return Lambda_(m); };
        return detail::single_scattering_albedo(P22, L, F, mu, tolerance, opts_.g2, masking_cot_);
    }
    N ndf_;
    FastLambda<N> Lambda_;
    AlbedoOptions opts_;
    double masking_cot_;  ///< the slope scale (albedo_grid.hpp, masking_cot): the radial quadrature's first panel
};

/// One-off conveniences (each builds the Lambda table again for an NDF without a closed form): E(mu) and E_avg.
///@{
template <Ndf N>
double directional_albedo(const N& ndf, double mu, const AlbedoOptions& opts = {}) {
    return SingleScatteringAlbedo<N>(ndf, opts)(mu);
}
template <Ndf N>
double average_albedo(const N& ndf, const AlbedoOptions& opts = {}) {
    return SingleScatteringAlbedo<N>(ndf, opts).average();
}
///@}

/// The node cluster of a dielectric's tables (albedo_grid.hpp) at relative index eta (below over above) on a grid whose
/// first alpha is alpha_min: from inside (eta < 1), b = 0.35 of the axis about the critical cosine mu_c =
/// sqrt(1 - eta^2), where E_T rises like sqrt(mu - mu_c) smoothed over ~alpha sin(theta_c) = alpha eta, at width
/// w = 2 alpha_min eta, twice the narrowest kink the grid holds; from outside, none. Measured in albedo_grid.hpp.
NodeCluster dielectric_cluster(double eta, double alpha_min);
/// A dielectric's grid: E's alphas and warp scales, n_x cosines a row, dielectric_cluster(eta, E's first alpha).
AlbedoGrid dielectric_grid(const AlbedoGrid& E, int n_x, double eta);

/// F_avg = 2 integral_0^1 F(mu) mu dmu (Kulla and Conty 2017), F a callable of the cosine.
template <class Fresnel>
double average_fresnel(const Fresnel& F, double tolerance = 1e-10) {
    return detail::cosine_average(F, tolerance);
}

/// Kulla and Conty 2017's Fresnel factor F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)): f_ms F_ms is the lobe of
/// coloured facets (f_ms, compensation_lobe below).
double fresnel_ms(double F_avg, double E_avg);
/// Turquin 2019's scale 1 + F0 (1 - E) / E, E = E(mu_v) of the direction held fixed (the view direction).
double turquin_scale(double E_view, double F0);
/// Fdez-Aguera 2019 ("A Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting", JCGT 8(1); its
/// series summed): the albedo of coloured facets, single scattering E_F(mu) and bounces that each escape with
/// E(mu) (mirror facets' albedo) and reflect F_avg, E_F / (1 - F_avg (1 - E(mu))).
double fdez_aguera_albedo(double E_F, double E, double F_avg);

/// Kulla and Conty 2017's lobe as a renderer evaluates it from the tables: f_ms(wi, wo) = (1 - E(alpha, mu_i))
/// (1 - E(alpha, mu_o)) / (pi m(alpha)), E looked up (AlbedoTable::lookup) and m = 1 - E_avg by lookup_missing from
/// `missing` (1 - E_avg at E's alphas).
double compensation_lobe(const AlbedoTable& E, const std::vector<double>& missing, double alpha, double mu_i,
                         double mu_o);
/// The albedo of that lobe times F_ms, integrated over wo:
///     F_ms (1 - E(alpha, mu_i)) 2 integral_0^1 (1 - E(alpha, mu)) mu dmu / m(alpha),
/// F_ms = fresnel_ms(F_avg, 1 - m(alpha)) (1 for mirror facets, F_avg = 1). The integral over the table's cells in mu
/// (8-point Gauss-Legendre a cell: the lookup is linear in x, smooth in mu within a cell).
double kulla_conty_albedo(const AlbedoTable& E, const std::vector<double>& missing, double alpha, double mu_i,
                          double F_avg = 1.0);
/// Its factor that does not depend on mu_i: 2 integral_0^1 (1 - E(alpha, mu)) mu dmu / m(alpha), 1 where m is the
/// table's own (table_missing) at E's alphas.
double kulla_conty_ratio(const AlbedoTable& E, const std::vector<double>& missing, double alpha);
/// The table's own 1 - E_avg at alpha: 2 integral_0^1 (1 - E(alpha, mu)) mu dmu of the lookup; and at each of its
/// alphas. Given to a renderer as its 1 - E_avg, it makes Kulla and Conty's lobe put back exactly 1 - E(alpha, mu_i)
/// of the table at its alphas (and, with lookup_missing between them, within the furnace measured by
/// compensation/furnace.hpp): the exact 1 - E_avg (SingleScatteringAlbedo::missing) would leave the table's error in E,
/// integrated, divided by 1 - E_avg, which is ~alpha^2 at small alpha (4e-3 in the furnace of GGX's 32 x 48 table at
/// alpha 0.03).
///@{
double table_missing(const AlbedoTable& E, double alpha);
std::vector<double> table_missing(const AlbedoTable& E);
///@}

/// "smithlab_" + the family name made an identifier: runs of other characters than letters and digits become one '_'
/// ("gtr(gamma=1.5)" -> smithlab_gtr_gamma_1_5); the names of the renderer formats start with it
/// (compensation_formats.hpp).
std::string compensation_header_name(std::string_view family_name);

}  // namespace smithlab::compensation
