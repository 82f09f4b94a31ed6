// smithlab/gtr/spline.hpp -- Dimov 2015, section 5 and 6: G1 for any gamma as V-Ray 3.20 ships it.
//
// A natural cubic spline in gamma through the closed-form G1 at the knots gamma = 0, 1, 2, 3, 4, with gamma
// clamped to 4 above. Kept exactly, as the baseline that better interpolants must beat.
#pragma once

namespace smithlab {

// gamma >= 0; gamma > 4 is clamped to 4 (Dimov 2015 sec. 6). mu finite > 0.
double G1_gtr_dimov_spline(double alpha, double gamma, double mu);

}  // namespace smithlab
