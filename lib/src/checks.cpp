#include "smithlab/checks.hpp"

#include <charconv>

namespace smithlab::detail {

double clamped_cosine_azimuth(double a, double b) {
    if (b >= a) return 2.0 * std::numbers::pi * b;
    if (b <= -a) return 0.0;
    const double phi0 = std::acos(-b / a);
    return 2.0 * (a * std::sin(phi0) + b * phi0);
}

std::string format_where(const char* name, double value) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, value);
    return std::string(name) + "=" + std::string(buf, r.ptr);
}

}  // namespace smithlab::detail
