// What `smithlab brdf` (and the Python module's brdf) print beside the walk's estimate: the single-scattering BSDF
// times |cos theta_o| in closed form (Walter 2007 eq. 20 and 21, with the height-correlated G2), where the facets
// have one: mirror and conductor facets, dielectric facets lit from above.
#pragma once

#include <variant>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fresnel.hpp"
#include "smithlab/single_scattering.hpp"
#include "smithlab/walk/facets.hpp"

namespace smithlab::trace {

inline bool has_single_analytic(const walk::Material& m, bool light_from_below) {
    return (m.get_if<walk::Mirror>() != nullptr) || (m.get_if<walk::Conductor>() != nullptr) ||
        ((m.get_if<walk::Dielectric>() != nullptr) && !light_from_below);
}

// The value at (wi, wo), for facets that have it (has_single_analytic); wo below the surface is transmission.
inline double single_analytic(const AnyNdf& ndf, const walk::Material& m, const Vec3& wi, const Vec3& wo) {
    auto reflection = [&](auto F) { return single_scattering_reflection(ndf, wi, wo, F); };
    if (const auto* c = m.get_if<walk::Conductor>())
        return reflection([c](double x) { return fresnel_conductor(x, c->eta, c->k); });
    if (const auto* d = m.get_if<walk::Dielectric>()) {
        auto F = [d](double x) { return fresnel_dielectric(x, d->eta); };
        return wo.z() > 0.0 ? reflection(F) : single_scattering_transmission(ndf, wi, wo, 1.0, d->eta, F);
    }
    return reflection([](double) { return 1.0; });
}

}  // namespace smithlab::trace
