/// @file
/// smithlab/walk/heights.hpp -- the height law of the Smith microsurface: its CDF C1 and the inverse.
///
/// Smith's model makes heights and slopes independent (Hammon 2017 appendix, "PDF of hitting heightfield"), so the
/// walk's answer depends on heights only through C1(h): any continuous law gives the same result (Heitz, Hanika,
/// d'Eon, Dachsbacher 2016, sec. 4, "the height distribution has no influence"). tests/test_walk.cpp checks it by
/// tracing the same cells with both laws. Uniform is the default, as in Heitz et al.'s and Hammon's walks.
#pragma once

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <numbers>

namespace smithlab::walk {

/// Uniform on [-1, 1] (Heitz et al. 2016, MicrosurfaceHeightUniform; Hammon's +-0.0002 alpha is the same law scaled).
struct UniformHeights {
    /// C1(h) = (h + 1) / 2 on [-1, 1], clamped to [0, 1], and its inverse on [0, 1].
    /// @{
    static double C1(double h) { return std::clamp(0.5 * (h + 1.0), 0.0, 1.0); }
    static double invC1(double u) { return std::clamp(2.0 * u - 1.0, -1.0, 1.0); }
    /// @}
};

/// Standard normal (Heitz et al. 2016, MicrosurfaceHeightGaussian): C1 = erfc(-h / sqrt 2) / 2.
struct GaussianHeights {
    /// C1(h) = erfc(-h / sqrt 2) / 2, 1 at h = +inf.
    static double C1(double h) {
        if (h == INFINITY) return 1.0;
        return 0.5 * std::erfc(-h / std::numbers::sqrt2);
    }
    /// The inverse of C1: -sqrt 2 erfc^-1(2u), -inf at u <= 0, +inf at u >= 1.
    static double invC1(double u) {
        if (!(u > 0.0)) return -INFINITY;
        if (!(u < 1.0)) return INFINITY;
        return -std::numbers::sqrt2 * boost::math::erfc_inv(2.0 * u);
    }
};

}  // namespace smithlab::walk
