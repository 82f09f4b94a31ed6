#include "smithlab/detail/radial_table.hpp"

#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <functional>
#include <string>

#include "smithlab/errors.hpp"

namespace smithlab::detail {

namespace {

constexpr double y_min = -230.0, y_max = 230.0, h = 1.0 / 32.0;
constexpr std::size_t guide_steps = 4096;

// integral of g over [a, b], 8-point Gauss-Legendre (Boost.Math's nodes: 0 is not one of them for 8).
template <class G>
double gauss8(const G& g, double a, double b) {
    using rule = boost::math::quadrature::gauss<double, 8>;
    const double c = 0.5 * (a + b), r = 0.5 * (b - a);
    double sum = 0.0;
    for (std::size_t i = 0; i < rule::abscissa().size(); ++i)
        sum += rule::weights()[i] * (g(c - r * rule::abscissa()[i]) + g(c + r * rule::abscissa()[i]));
    return sum * r;
}

}  // namespace

RadialTable::RadialTable(const std::function<double(double s)>& w) {
    // In y = ln s the density is s w(s) dy.
    auto g = [&](double y) {
        const double s = std::exp(y), v = w(s);
        if (!(v >= 0.0 && v < INFINITY))
            throw input_error("cannot tabulate a density that is " + std::to_string(v) +
                              " at tan^2 = " + std::to_string(s));
        return s * v;
    };
    const auto n = static_cast<std::size_t>(std::lround((y_max - y_min) / h));
    S_.assign(n + 1, 0.0);
    dS_.assign(n + 1, 0.0);
    std::vector<double> mid(n);  // exact S at the cell midpoints (unnormalized)
    for (std::size_t k = n; k-- > 0;) {
        const double a = y_min + h * static_cast<double>(k);
        mid[k] = S_[k + 1] + gauss8(g, a + 0.5 * h, a + h);
        S_[k] = mid[k] + gauss8(g, a, a + 0.5 * h);
    }
    total_ = S_[0];
    if (!(total_ > 0.0 && total_ < INFINITY))
        throw input_error("cannot tabulate a density whose integral is " + std::to_string(total_));
    // The law must live well inside the range: at most 1e-12 of it within 4 (in ln tan^2) of either end.
    const auto edge = static_cast<std::size_t>(4.0 / h);
    if ((S_[0] - S_[edge]) / total_ > 1e-12 || S_[n - edge] / total_ > 1e-12)
        throw input_error(
            "cannot tabulate a law of tan^2(theta_m) with mass near 1e-100 or 1e100 (alpha beyond ~1e-45 "
            "or ~1e45?): the table spans tan^2 in [1e-100, 1e100]");
    for (std::size_t k = 0; k <= n; ++k) {
        S_[k] /= total_;
        dS_[k] = -h * g(y_min + h * static_cast<double>(k)) / total_;
    }
    // Fritsch-Carlson: slopes at most 3x the neighbouring secants keep each cubic monotone.
    for (std::size_t k = 0; k <= n; ++k) {
        const double left = k > 0 ? S_[k - 1] - S_[k] : INFINITY, right = k < n ? S_[k] - S_[k + 1] : INFINITY;
        dS_[k] = -std::min({-dS_[k], 3.0 * left, 3.0 * right});
    }
    for (std::size_t k = 0; k < n; ++k) error_ = std::max(error_, std::abs(hermite(k, 0.5) - mid[k] / total_));
    // The cell of v (isf) is the last k < n with S_k >= v; guide_[j] is that of v = (j + 1) / guide_steps, the first
    // cell any v of step j can be in.
    guide_.resize(guide_steps);
    std::size_t k = 0;
    for (std::size_t j = guide_steps; j-- > 0;) {
        const double v = static_cast<double>(j + 1) / static_cast<double>(guide_steps);
        while (k + 1 < n && S_[k + 1] >= v) ++k;
        guide_[j] = static_cast<unsigned>(k);
    }
}

double RadialTable::hermite(std::size_t k, double t) const {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * S_[k] + (t3 - 2 * t2 + t) * dS_[k] + (-2 * t3 + 3 * t2) * S_[k + 1] +
        (t3 - t2) * dS_[k + 1];
}

double RadialTable::sf(double s) const {
    if (!(s > 0.0)) return 1.0;
    const double x = (std::log(s) - y_min) / h;
    if (x >= static_cast<double>(S_.size() - 1)) return 0.0;
    if (x < 0.0) return 1.0;
    const auto k = static_cast<std::size_t>(x);
    return hermite(k, x - static_cast<double>(k));
}

double RadialTable::isf(double v) const {
    // The cell whose range of S holds v (S decreases), then Newton on the cubic, kept inside the bracket [lo, hi]. A
    // step below 2^-30 leaves an error of about its square: it is taken and the solve ends.
    const std::size_t n = S_.size() - 1;
    const double vj = v > 0.0 ? std::min(v, 1.0) : 0.0;  // a NaN too: the index is a number
    const auto j = std::min(guide_steps - 1, static_cast<std::size_t>(vj * static_cast<double>(guide_steps)));
    std::size_t k = guide_[j];
    while (k + 1 < n && S_[k + 1] >= v) ++k;
    double lo = 0.0, hi = 1.0, t = S_[k] > S_[k + 1] ? (S_[k] - v) / (S_[k] - S_[k + 1]) : 0.5;
    for (int i = 0; i < 60; ++i) {
        const double f = hermite(k, t) - v;  // decreasing in t
        if (f == 0.0) break;
        if (f < 0.0) hi = t;
        else lo = t;
        const double t2 = t * t;
        const double d =
            (6 * t2 - 6 * t) * (S_[k] - S_[k + 1]) + (3 * t2 - 4 * t + 1) * dS_[k] + (3 * t2 - 2 * t) * dS_[k + 1];
        double next = d < 0.0 ? t - f / d : 0.5 * (lo + hi);
        if (std::abs(next - t) <= 0x1p-30 && next >= 0.0 && next <= 1.0) {
            t = next;
            break;
        }
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        t = next;
        if (hi - lo <= 1e-15) break;
    }
    return std::exp(y_min + h * (static_cast<double>(k) + t));
}

}  // namespace smithlab::detail
