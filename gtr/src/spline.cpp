#include "smithlab/gtr/spline.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "smithlab/gtr/closed_forms.hpp"

namespace smithlab {

namespace {

// G1 at the knots gamma = 0..4 for mu in [1e-100, 1e100]: G1 = 1 / (1 + Lambda_gtr_closed(alpha, k, mu)) to a few ulp,
// by the forms of closed_forms.hpp (ratio0..ratio4, their derivations there) sharing their roots A = sqrt(mu^2 +
// alpha^2), B = sqrt(mu^2 + 1) and their reciprocals: two roots, two logs and four divisions for the five knots
// (five separate closed forms, each with its own hypot and log1pmx, would cost about three times as much).
// gamma = 0 and 2 as 2 mu / (mu + B), 2 mu / (mu + A) (Walter 2007 eq. 34 times mu / mu; B^2 = mu^2 + 1 makes
// 1 + 1 / (2 mu (mu + B)) = (mu + B)^2 / (2 mu (mu + B))). Beyond mu_big = 1e50 (where G1 = 1 to 1e-100) the forms'
// own asymptote, through Lambda_gtr_closed.
std::array<double, 5> knot_G1(double alpha, double mu) {
    std::array<double, 5> y;
    if (mu > gtr_closed::mu_big) {
        for (int k = 0; k < 5; ++k) y[k] = 1.0 / (1.0 + Lambda_gtr_closed(alpha, k, mu));
        return y;
    }
    const double a2 = alpha * alpha;
    const double A = gtr_closed::root_sum_squares(mu, a2), B = gtr_closed::root_sum_squares(mu, 1.0);
    // The four reciprocals the forms need, 1/(mu + A), 1/(mu + B), 1/(A + B), 1/A, from one division (each within
    // ~2 ulp): t1 t2 lies in [1e-100, 1e201] on mu in [1e-100, 1e50], alpha in [1e-50, 1].
    const double s = mu + A, t1 = s * (mu + B), t2 = (A + B) * A, R = 1.0 / (t1 * t2);
    const double inv_s = R * (mu + B) * t2, inv_muB = R * s * t2, inv_AB = R * t1 * A, inv_A = R * t1 * (A + B);
    y[0] = 2.0 * mu * inv_muB;
    y[1] = alpha == 1.0 ? y[0]
                        : gtr_closed::ratio1_of_x(alpha, (1.0 - alpha) * (1.0 + alpha) * inv_AB * inv_s, A, mu).G1();
    y[2] = 2.0 * mu * inv_s;
    {  // ratio3 with w = a2 / s
        const double w = a2 * inv_s;
        const gtr_closed::Ratio r{w * (w * (4.0 * mu * s + 1.0 + 3.0 * a2)), 4.0 * (1.0 + a2) * mu * A};
        y[3] = r.G1();
    }
    {  // ratio4 with v = a2 / A
        const double v = a2 * inv_A, mu2 = mu * mu;
        const double N = 3.0 * A + mu + 2.0 * a2 * (3.0 * A + 5.0 * mu) + a2 * a2 * (15.0 * A + 37.0 * mu);
        const double P = 48.0 * mu2 * mu2 * s + 12.0 * mu2 * (s + a2 * (5.0 * A + 7.0 * mu)) + N;
        const gtr_closed::Ratio r{v * (v * (v * P)), 16.0 * (a2 * a2 + a2 + 1.0) * mu * (s * s * s)};
        y[4] = r.G1();
    }
    return y;
}

}  // namespace

double G1_gtr_dimov_spline(double alpha, double gamma, double mu) {
    // Beyond mu in [1e-100, 1e100] the knots' Lambda is its asymptote (closed_forms.hpp), C/mu^2 or E[q+]/mu: the
    // spline's Lambda at the end of the range is carried out the same way, so that no 1 - G1 of a G1 within 1e-300
    // of 0 or 1 turns into NaN (mu = 1e307).
    constexpr double big = 1e100, small = 1e-100;
    if (mu > big || mu < small) {
        const double edge = mu > big ? big : small, g = G1_gtr_dimov_spline(alpha, gamma, edge);
        if (!(g > 0.0 && g < 1.0)) return g;
        const double scale = mu > big ? (big / mu) * (big / mu) : small / mu;
        return 1.0 / (1.0 + (1.0 - g) / g * scale);
    }
    const std::array<double, 5> y = knot_G1(alpha, mu);
    // Natural cubic spline on unit-spaced knots: M0 = M4 = 0 and, for the second derivatives M1..M3,
    //   M_{i-1} + 4 M_i + M_{i+1} = 6 (y_{i-1} - 2 y_i + y_{i+1}).
    // The 3x3 system has the fixed inverse (1/56) [[15,-4,1],[-4,16,-4],[1,-4,15]]. Carried as m = M / 6 (the spline
    // uses only M / 6), with 1/56 as a multiplication: divisions cost more than the rest of the spline together.
    constexpr double inv56 = 1.0 / 56.0;
    const double e1 = y[0] - 2.0 * y[1] + y[2];
    const double e2 = y[1] - 2.0 * y[2] + y[3];
    const double e3 = y[2] - 2.0 * y[3] + y[4];
    const std::array<double, 5> m = {0.0, (15.0 * e1 - 4.0 * e2 + e3) * inv56,
                                     (-4.0 * e1 + 16.0 * e2 - 4.0 * e3) * inv56, (e1 - 4.0 * e2 + 15.0 * e3) * inv56,
                                     0.0};
    const double g = std::min(gamma, 4.0);
    const int i = std::min(static_cast<int>(g), 3);
    const double b = g - i, a = 1.0 - b;  // distances to the right and left knots
    return m[i] * a * a * a + m[i + 1] * b * b * b + (y[i] - m[i]) * a + (y[i + 1] - m[i + 1]) * b;
}

double Lambda_of_interpolated_G1(double g1) { return g1 >= 1.0 ? 0.0 : g1 <= 0.0 ? INFINITY : (1.0 - g1) / g1; }

}  // namespace smithlab
