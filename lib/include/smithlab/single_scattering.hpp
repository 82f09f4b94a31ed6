/// @file
/// smithlab/single_scattering.hpp -- the single-scattering microfacet BSDF, the reference the walk's first bounce is
/// tested against:
///   reflection    f(wi, wo) = F(wi.h) D(h) G2(wi, wo) / (4 |wi.n| |wo.n|),  h = normalize(wi + wo)
///                 (Walter, Marschner, Li, Torrance 2007, eq. 20);
///   transmission  f(wi, wo) = |wi.h| |wo.h| / (|wi.n| |wo.n|) eta_o^2 (1 - F(wi.h)) D(h) G2(wi, wo)
///                             / (eta_i (wi.h) + eta_o (wo.h))^2,  h = -normalize(eta_i wi + eta_o wo)   (eq. 21, 16),
/// with the height-correlated G2 (smith.hpp, G2_from_Lambdas). F is a callable of cos(wi.h). wi and wo point away.
#pragma once

#include <cmath>

#include "smithlab/geometry.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

/// D(m) of a unit normal m, from the slope density at s = tan^2(theta_m) (Walter 2007 eq. 42); 0 for m.z <= 0.
template <Ndf N>
double D_of_normal(const N& ndf, const Vec3& m) {
    if (!(m.z() > 0.0)) return 0.0;
    const double s = tan2_theta(m);
    return D_from_P22(slope_density(ndf, s), s);
}

/// f(wi, wo) |cos theta_o| in reflection (wi.z > 0, wo.z > 0; 0 otherwise).
template <Ndf N, class Fresnel>
double single_scattering_reflection(const N& ndf, const Vec3& wi, const Vec3& wo, Fresnel F,
                                    const LambdaOptions& opts = {}) {
    if (!(wi.z() > 0.0 && wo.z() > 0.0)) return 0.0;
    const Vec3 h = (wi + wo).normalized();
    const double G2 = G2_from_Lambdas(Lambda(ndf, cot_theta(wi), opts), Lambda(ndf, cot_theta(wo), opts), true,
                                      G2Form::height_correlated);
    return F(wi.dot(h)) * D_of_normal(ndf, h) * G2 / (4.0 * wi.z());
}

/// f(wi, wo) |cos theta_o| in transmission through a dielectric interface, eta_i above, eta_o below
/// (wi.z > 0 > wo.z; 0 otherwise). F is the reflectance at cos(wi.h).
template <Ndf N, class Fresnel>
double single_scattering_transmission(const N& ndf, const Vec3& wi, const Vec3& wo, double eta_i, double eta_o,
                                      Fresnel F, const LambdaOptions& opts = {}) {
    if (!(wi.z() > 0.0 && wo.z() < 0.0)) return 0.0;
    Vec3 h = -(eta_i * wi + eta_o * wo).normalized();
    if (h.z() < 0.0) h = -h;
    const double ci = wi.dot(h), co = wo.dot(h);
    if (!(ci > 0.0 && co < 0.0)) return 0.0;  // a facet sees wi from above and wo from below
    const double G2 = G2_from_Lambdas(Lambda(ndf, cot_theta(wi), opts), Lambda(ndf, -cot_theta(wo), opts), false,
                                      G2Form::height_correlated);
    const double denom = eta_i * ci + eta_o * co;
    return std::abs(ci * co) / wi.z() * eta_o * eta_o * (1.0 - F(ci)) * D_of_normal(ndf, h) * G2 / (denom * denom);
}

}  // namespace smithlab
