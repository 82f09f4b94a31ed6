/// @file
/// smithlab/fresnel.hpp -- Fresnel reflectance of a facet: Schlick's approximation, and the exact unpolarized
/// reflectance of a conductor (complex index eta + i k) and of a dielectric. cos_i = |wi . m|, in [0, 1].
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>

namespace smithlab {

/// Schlick 1994, "An inexpensive BRDF model for physically-based rendering", eq. 24: F0 + (1 - F0)(1 - cos)^5.
inline double fresnel_schlick(double f0, double cos_i) {
    const double c = 1.0 - std::clamp(cos_i, 0.0, 1.0), c2 = c * c;
    return f0 + (1.0 - f0) * (c2 * c2 * c);
}

/// Unpolarized Fresnel reflectance of a conductor of complex relative index eta + i k (Born & Wolf, "Principles of
/// Optics", sec. 14.2; pbrt-v4 FrComplex, sec. 9.3.6): the mean of |r_parallel|^2 and |r_perpendicular|^2 with
/// cos_t = sqrt(1 - sin^2 / n^2) on the principal branch.
inline double fresnel_conductor(double cos_i, double eta, double k) {
    using C = std::complex<double>;
    const double c = std::clamp(cos_i, 0.0, 1.0), sin2 = (1.0 - c) * (1.0 + c);
    const C n(eta, k);
    const C cos_t = std::sqrt(1.0 - sin2 / (n * n));
    const C r_parl = (n * c - cos_t) / (n * c + cos_t);
    const C r_perp = (c - n * cos_t) / (c + n * cos_t);
    return 0.5 * (std::norm(r_parl) + std::norm(r_perp));
}

/// Unpolarized Fresnel reflectance of a dielectric interface, eta = eta_t / eta_i, cos_i on the incident side
/// (Walter et al. 2007, eq. 22); 1 past total internal reflection.
inline double fresnel_dielectric(double cos_i, double eta) {
    const double c = std::clamp(cos_i, 0.0, 1.0);
    const double g2 = eta * eta - 1.0 + c * c;
    if (g2 < 0.0) return 1.0;
    const double g = std::sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

}  // namespace smithlab
