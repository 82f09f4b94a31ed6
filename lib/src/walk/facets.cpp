#include "smithlab/walk/facets.hpp"

#include <cmath>

namespace smithlab::walk {

namespace detail {

double hammon_lobe_cos(double u) {
    auto Y =
        [](double c) {  // Horner form of the slide's polynomial, c^3 (7/2 - 21/4 c + 21/5 c^2 - 7/4 c^3 + 3/10 c^4)
            return c * c * c * (3.5 + c * (-5.25 + c * (4.2 + c * (-1.75 + c * 0.3))));
        };
    auto dY = [](double c) {  // (21/10) c (1 - (1 - c)^5)
        const double t = 1.0 - c, t2 = t * t;
        return 2.1 * c * (1.0 - t2 * t2 * t);
    };
    if (!(u > 0.0)) return 0.0;
    if (!(u < 1.0)) return 1.0;
    // Shirley's rational first guess, as printed on the slide; below u = 1e-3, where it is poor (it tends to 0.011,
    // not 0), the leading term of Y = 7/2 c^3 (1 + O(c)). From either, Newton's method is quadratic: the step that
    // is below 2^-26 c leaves an error of about its square, 2^-52 (tests/test_walk.cpp: within 2e-15 of a long-double
    // inversion; 3 steps on average). A step out of the bracket [lo, hi] that the residuals keep is replaced by
    // bisection.
    double c = u < 1e-3
        ? std::cbrt(u / 3.5)
        : (0.0114813 + u * (154.4 + u * (13002.4 + u * 38295.9))) / (1.0 + u * (1483.57 + u * (33596.4 + u * 16520.2)));
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < 100; ++i) {
        const double r = Y(c) - u;
        if (r == 0.0) return c;
        (r > 0.0 ? hi : lo) = c;
        double next = c - r / dY(c);
        if (std::abs(next - c) <= 0x1p-26 * c) return next;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        c = next;
    }
    return c;
}

}  // namespace detail

}  // namespace smithlab::walk
