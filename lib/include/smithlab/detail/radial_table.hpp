/// @file
/// smithlab/detail/radial_table.hpp -- sampling a law on s = tan^2(theta_m) in (0, inf) given only its density, by a
/// tabulated inverse survival function (1 - CDF). It is how an NDF without an analytic sampler is sampled (D cos:
/// density pi P22(s)), and the second proposal of the generic visible-normal sampler (density P22(s) sqrt(s) / 2, i.e.
/// P22 r^2 dr).
///
/// The survival function S is tabulated in y = ln s on [-230, 230] (s from 1e-100 to 1e100) at steps of 1/32:
/// each cell integrated by 8-point Gauss-Legendre, so the knots carry the integral to ~1e-16; between knots a
/// cubic Hermite in y with the exact derivative dS/dy = -s w(s) / W (Fritsch-Carlson limited, so it stays
/// monotone); an inverse finds its cell from a guide table (Chen & Asau 1974: for each of 4096 equal steps of S, the
/// cell where it starts, then a short forward search) and solves the cubic there by a safeguarded Newton method. The
/// samples then follow the Hermite S exactly, and error_estimate() bounds how far that is from the true S: the largest
/// difference at the cell midpoints, where the exact value is integrated separately (~1e-10 for the built-in NDFs). The
/// error is absolute, in probability: a tail holding less than that is not resolved.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace smithlab::detail {

/// A law on s = tan^2(theta_m) in (0, inf), tabulated from its density: survival function and inverse (see the file
/// comment).
class RadialTable {
public:
    /// w: the (unnormalized) density in s, finite and >= 0. input_error when it has no mass, is not finite, or has
    /// more than 1e-12 of its mass near the ends of the range (a peak at tan^2 ~ 1e-100: alpha ~ 1e-50).
    explicit RadialTable(const std::function<double(double s)>& w);

    double total() const { return total_; }  ///< integral of w over (0, inf), as tabulated
    double sf(double s) const;               ///< P(tan^2 > s), in [0, 1]
    double isf(double v) const;              ///< s with sf(s) = v, for v in (0, 1]
    /// The largest difference between the tabulated and the true survival function at the cells' midpoints: absolute,
    /// in probability.
    double error_estimate() const { return error_; }

private:
    double hermite(std::size_t k, double t) const;  ///< S in cell k at t in [0, 1]
    std::vector<double> S_, dS_;                    ///< normalized survival function and h dS/dy at the knots
    std::vector<unsigned> guide_;                   ///< guide_[j]: the cell of S = (j + 1) / guide_steps (isf)
    double total_ = 0.0, error_ = 0.0;
};

}  // namespace smithlab::detail
