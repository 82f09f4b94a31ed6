/// @file
/// smithlab/gtr/spline.hpp -- Dimov 2015, section 5 and 6: G1 for any gamma as V-Ray 3.20 ships it.
///
/// A natural cubic spline in gamma through the closed-form G1 at the knots gamma = 0, 1, 2, 3, 4, with gamma
/// clamped to 4 above. Kept exactly, as the baseline that better interpolants must beat.
#pragma once

namespace smithlab {

/// gamma >= 0; gamma > 4 is clamped to 4 (Dimov 2015 sec. 6). mu finite > 0. The spline itself, unclamped.
double G1_gtr_dimov_spline(double alpha, double gamma, double mu);

/// Lambda = (1 - G1)/G1 of an interpolated G1, clamped to [0, 1] first as a renderer must: interpolants leave it
/// (Dimov's spline gives G1 = -0.10 at alpha = 1e-4, mu = 1e-3, gamma = 0.5). Lambda is then 0 or +inf there.
double Lambda_of_interpolated_G1(double g1);

}  // namespace smithlab
