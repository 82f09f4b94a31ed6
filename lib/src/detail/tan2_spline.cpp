#include "smithlab/detail/tan2_spline.hpp"

#include <algorithm>

namespace smithlab::detail {

namespace {

// The cubic through (0, f0), (1/3, f1), (2/3, f2), (1, f3) in powers of u.
std::array<double, 4> cubic_through(double f0, double f1, double f2, double f3) {
    return {f0, 0.5 * (-11.0 * f0 + 18.0 * f1 - 9.0 * f2 + 2.0 * f3),
            0.5 * (18.0 * f0 - 45.0 * f1 + 36.0 * f2 - 9.0 * f3), 0.5 * (-9.0 * f0 + 27.0 * f1 - 27.0 * f2 + 9.0 * f3)};
}

double horner(const std::array<double, 4>& c, double u) { return ((c[3] * u + c[2]) * u + c[1]) * u + c[0]; }

// Where the cubic's error is checked: the extremes of the node polynomial u (u - 1/3) (u - 2/3) (u - 1), at
// u = 1/2 and 1/2 +- sqrt(5) / 6, where an error led by the fourth derivative peaks.
constexpr std::array<double, 3> checks = {0.5 - 0.37267799624996495, 0.5, 0.5 + 0.37267799624996495};

}  // namespace

Tan2Spline::Tan2Spline(const std::function<double(double)>& f, double tolerance, double floor)
    : tolerance_(tolerance), floor_(floor) {
    const double lo = std::ldexp(1.0, lowest_binade);
    first_ = std::bit_cast<std::uint64_t>(lo) >> shift;
    const std::uint64_t end = std::bit_cast<std::uint64_t>(std::ldexp(1.0, highest_binade)) >> shift;
    coef_.resize(end - first_);
    in_log_.resize(coef_.size());
    const double none = std::numeric_limits<double>::quiet_NaN();
    std::size_t good = 0;
    for (std::uint64_t i = 0; i < coef_.size(); ++i) {
        // The piece's ends: t0 and t1 (the next piece's first value), u linear between them.
        const double t0 = std::bit_cast<double>((first_ + i) << shift);
        const double t1 = std::bit_cast<double>((first_ + i + 1) << shift);
        auto at = [&](double u) { return f(t0 + (t1 - t0) * u); };
        const double f0 = at(0.0), f1 = at(1.0 / 3.0), f2 = at(2.0 / 3.0), f3 = at(1.0);
        const std::array<double, 3> mid = {at(checks[0]), at(checks[1]), at(checks[2])};
        auto meets = [&](const std::array<double, 4>& c, bool in_log) {
            for (int j = 0; j < 3; ++j) {
                const double p = horner(c, checks[j]), v = in_log ? std::exp(p) : p;
                if (!(std::abs(v - mid[j]) <= 0.5 * tolerance * std::max(mid[j], floor))) return false;
            }
            return true;
        };
        coef_[i] = {none, none, none, none};
        const bool finite = std::isfinite(f0 + f1 + f2 + f3 + mid[0] + mid[1] + mid[2]);
        const bool positive = f0 > 0.0 && f1 > 0.0 && f2 > 0.0 && f3 > 0.0;
        if (!finite) continue;
        if (const std::array<double, 4> c = cubic_through(f0, f1, f2, f3); meets(c, false)) {
            coef_[i] = c, ++good;
        } else if (const std::array<double, 4> l =
                       positive ? cubic_through(std::log(f0), std::log(f1), std::log(f2), std::log(f3)) : c;
                   positive && meets(l, true)) {
            coef_[i] = l, in_log_[i] = true, ++good;
        }
    }
    answered_ = static_cast<double>(good) / static_cast<double>(coef_.size());
}

}  // namespace smithlab::detail
