#include "smithlab/checks.hpp"
#include "smithlab/csv.hpp"

#include <cmath>
#include <numbers>

namespace smithlab::detail {

double clamped_cosine_azimuth(double a, double b) {
    if (b >= a) return 2.0 * std::numbers::pi * b;
    if (b <= -a) return 0.0;
    const double phi0 = std::acos(-b / a);
    return 2.0 * (a * std::sin(phi0) + b * phi0);
}

std::string format_where(const char* name, double value) { return std::string(name) + "=" + format_shortest(value); }

}  // namespace smithlab::detail
