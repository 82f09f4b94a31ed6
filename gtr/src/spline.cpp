#include "smithlab/gtr/spline.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "smithlab/gtr/closed_forms.hpp"

namespace smithlab {

double G1_gtr_dimov_spline(double alpha, double gamma, double mu) {
    // Beyond mu in [1e-100, 1e100] the knots' Lambda is its asymptote (closed_forms.cpp), C/mu^2 or E[q+]/mu: the
    // spline's Lambda at the end of the range is carried out the same way, so that no 1 - G1 of a G1 within 1e-300
    // of 0 or 1 turns into NaN (mu = 1e307).
    constexpr double big = 1e100, small = 1e-100;
    if (mu > big || mu < small) {
        const double edge = mu > big ? big : small, g = G1_gtr_dimov_spline(alpha, gamma, edge);
        if (!(g > 0.0 && g < 1.0)) return g;
        const double scale = mu > big ? (big / mu) * (big / mu) : small / mu;
        return 1.0 / (1.0 + (1.0 - g) / g * scale);
    }
    std::array<double, 5> y;
    for (int k = 0; k < 5; ++k) y[k] = 1.0 / (1.0 + Lambda_gtr_closed(alpha, k, mu));
    // Natural cubic spline on unit-spaced knots: M0 = M4 = 0 and, for the second derivatives M1..M3,
    //   M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i + y_{i+1}).
    // The 3x3 system has the fixed inverse (1/56) [[15,-4,1],[-4,16,-4],[1,-4,15]].
    const double d1 = 6.0 * (y[0] - 2.0 * y[1] + y[2]);
    const double d2 = 6.0 * (y[1] - 2.0 * y[2] + y[3]);
    const double d3 = 6.0 * (y[2] - 2.0 * y[3] + y[4]);
    const std::array<double, 5> M = {0.0, (15.0 * d1 - 4.0 * d2 + d3) / 56.0, (-4.0 * d1 + 16.0 * d2 - 4.0 * d3) / 56.0,
                                     (d1 - 4.0 * d2 + 15.0 * d3) / 56.0, 0.0};
    const double g = std::min(gamma, 4.0);
    const int i = std::min(static_cast<int>(g), 3);
    const double b = g - i, a = 1.0 - b;  // distances to the right and left knots
    return M[i] * a * a * a / 6.0 + M[i + 1] * b * b * b / 6.0 + (y[i] - M[i] / 6.0) * a + (y[i + 1] - M[i + 1] / 6.0) * b;
}

double Lambda_of_interpolated_G1(double g1) { return g1 >= 1.0 ? 0.0 : g1 <= 0.0 ? INFINITY : (1.0 - g1) / g1; }

}  // namespace smithlab
