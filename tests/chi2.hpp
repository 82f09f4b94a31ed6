// tests/chi2.hpp -- a chi-square goodness-of-fit test for normal samplers, after Mitsuba 3's chi2 harness and
// pbrt-v4's bsdfs_test: sample, histogram, integrate the sampler's pdf over every bin, pool the bins expecting
// fewer than 5 (a pool still below 5 joins the smallest cell), and compare.
//
// Bins are equal-area in (phi, cos theta') on the hemisphere of normals whose slopes are divided by `scale` (the
// NDF's typical slope): at alpha = 1e-3 equal-area bins in cos theta itself would put every sample in one bin.
// In z' = cos theta', tan theta = scale tan theta', and d omega = scale^2 (scale^2 + z'^2 (1 - scale^2))^{-3/2} dz'
// dphi.
//
// The harness shares nothing with what it judges but the sampler's interface (BoundSampler: sample, pdf): the map
// from the bins' (z', phi) to normals is its own (Bins::normal), and so is the quadrature (Boost's Gauss-Kronrod and
// tanh-sinh, not smithlab's integrate).
#pragma once

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <functional>
#include <numbers>
#include <smithlab/samplers.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace chi2 {

struct Result {
    double p_value = 0.0;
    double statistic = 0.0;
    int dof = 0;
    double pdf_integral = 0.0;    // of the pdf over the hemisphere (must be 1)
    std::size_t bad_samples = 0;  // NaN, zero pdf, pdf not the pdf() of m, below the horizon
    std::string note;             // why p = 0, if it is
};

struct Bins {
    int n_theta = 16, n_phi = 32;
    double scale = 1.0;
    int index(const smithlab::Vec3& m) const {
        const double x = m.x() / scale, y = m.y() / scale, zp = m.z() / std::sqrt(x * x + y * y + m.z() * m.z());
        double phi = std::atan2(m.y(), m.x());
        if (phi < 0.0) phi += 2.0 * std::numbers::pi;
        const int i = std::min(n_theta - 1, static_cast<int>(zp * n_theta));
        const int j = std::min(n_phi - 1, static_cast<int>(phi / (2.0 * std::numbers::pi) * n_phi));
        return i * n_phi + j;
    }
    // Optional: a direction w across whose great circle w.m = 0 the pdf may jump (Hammon's facing boundary) or kink
    // (the visible normals' <w.m>^+). Zero: none. The bin integrals are then split exactly where the circle crosses a
    // bin, in phi and in z' (split_phi, split_z): the same integrals to the same tolerances, each piece smooth. Without
    // the splits an adaptive rule bisects towards a jump to its depth limit and stops ~1e-4 off, and that error,
    // jumping from one z' to the next, made the outer rule bisect to its limit all along the circle: 97% of the
    // evaluations of the [slow] cases, for a worse answer. (A split is exact for any pdf: a jump elsewhere is still
    // integrated, only at the old cost; the chi-square and the pdf's integral see the same pdf as before.)
    smithlab::Vec3 crease = smithlab::Vec3::Zero();
    // The azimuths in (a, b) where the circle crosses slope tan(theta) = t, in increasing order.
    std::vector<double> split_phi(double t, double a, double b) const {
        std::vector<double> x;
        const double rho = std::hypot(crease.x(), crease.y());
        if (!(rho > 0.0) || !(t > 0.0)) return x;
        const double c = -crease.z() / (rho * t);  // w.m = 0 at cos(phi - phi_w) = c
        if (!(std::abs(c) < 1.0)) return x;
        const double phi_w = std::atan2(crease.y(), crease.x()), d = std::acos(c), two_pi = 2.0 * std::numbers::pi;
        for (double phi : {phi_w - d, phi_w + d}) {
            phi = std::fmod(phi, two_pi);
            if (phi < 0.0) phi += two_pi;
            if (phi > a && phi < b) x.push_back(phi);
        }
        std::sort(x.begin(), x.end());
        return x;
    }
    // The z' in (z0, z1) where the circle crosses the bin's edges phi = a, phi = b, or touches a slope (tangency,
    // where the facing arc grows as a square root), in increasing order.
    std::vector<double> split_z(double a, double b, double z0, double z1) const {
        std::vector<double> x;
        const double rho = std::hypot(crease.x(), crease.y());
        if (!(rho > 0.0)) return x;
        const double phi_w = std::atan2(crease.y(), crease.x());
        std::vector<double> ts = {std::abs(crease.z()) / rho};  // tangency: |c| = 1
        for (double phi : {a, b}) ts.push_back(-crease.z() / (rho * std::cos(phi - phi_w)));
        for (double t : ts) {
            if (!(t > 0.0) || !std::isfinite(t)) continue;
            const double tp = t / scale, zp = 1.0 / std::sqrt(1.0 + tp * tp);  // tan(theta') = tan(theta) / scale
            if (zp > z0 && zp < z1) x.push_back(zp);
        }
        std::sort(x.begin(), x.end());
        return x;
    }
    // The unit normal at bin coordinates (z', phi), z' in (0, 1]: the direction (sin theta' cos phi, sin theta' sin
    // phi, z') with its slope multiplied by scale, (scale sin theta' cos phi, scale sin theta' sin phi, z') / sqrt(q),
    // q = scale^2 sin^2 theta' + z'^2, sin^2 theta' = (1 - z')(1 + z') (exact near the pole).
    smithlab::Vec3 normal(double zp, double phi) const {
        const double st = std::sqrt((1.0 - zp) * (1.0 + zp)), x = scale * st, len = std::sqrt(x * x + zp * zp);
        return {x * std::cos(phi) / len, x * std::sin(phi) / len, zp / len};
    }
    // integral of pdf over bin (i, j), in (z', phi): inner adaptive Gauss-Kronrod (15 points, bisecting where the
    // pdf jumps or kinks, as at Hammon's facing boundary and the visible normals' wi.m = 0, where `crease` does not
    // already split it).
    double integral(const std::function<double(const smithlab::Vec3&)>& pdf, int i, int j) const {
        using rule = boost::math::quadrature::gauss_kronrod<double, 15>;
        const double k2 = scale * scale, dphi = 2.0 * std::numbers::pi / n_phi;
        const double z0 = static_cast<double>(i) / n_theta, z1 = static_cast<double>(i + 1) / n_theta;
        const double phi0 = j * dphi, phi1 = (j + 1) * dphi;
        auto over_phi = [&](double zp) {
            if (zp <= 0.0) return 0.0;
            const double q = k2 + zp * zp * (1.0 - k2), jac = k2 / (q * std::sqrt(q));
            const double t = scale * std::sqrt((1.0 - zp) * (1.0 + zp)) / zp;  // tan(theta) = scale tan(theta')
            auto f = [&](double phi) { return pdf(normal(zp, phi)); };
            double sum = 0.0, lo = phi0;
            for (double hi : split_phi(t, phi0, phi1)) sum += rule::integrate(f, lo, hi, 7, 1e-6), lo = hi;
            return jac * (sum + rule::integrate(f, lo, phi1, 7, 1e-6));
        };
        // Outer, in the first and last rows: tanh-sinh (relative tolerance 1e-7), whose nodes crowd the ends, where a
        // peaked core (z' -> 1) or the horizon sits; elsewhere adaptive Gauss-Kronrod.
        auto outer = [&](double lo, double hi) {
            if (i != 0 && i != n_theta - 1) return rule::integrate(over_phi, lo, hi, 7, 1e-6);
            boost::math::quadrature::tanh_sinh<double> ends;  // not const: Boost 1.74 defines integrate() without it
            const double r = ends.integrate(over_phi, lo, hi, 1e-7);
            if (!std::isfinite(r)) throw std::runtime_error("chi2: a bin's integral is not finite");
            return r;
        };
        double sum = 0.0, lo = z0;
        for (double hi : split_z(phi0, phi1, z0, z1)) sum += outer(lo, hi), lo = hi;
        return sum + outer(lo, z1);
    }
};

inline Result test(const smithlab::BoundSampler& sampler, const Bins& bins, std::size_t n, smithlab::Rng& rng) {
    Result r;
    const int nb = bins.n_theta * bins.n_phi;
    std::vector<double> observed(nb, 0.0), expected(nb, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
        const smithlab::NormalSample s = sampler.sample(rng);
        const bool ok = std::isfinite(s.m.x()) && std::isfinite(s.m.y()) && std::isfinite(s.m.z()) && s.m.z() >= 0.0 &&
            s.pdf > 0.0 && std::abs(s.m.norm() - 1.0) < 1e-12 && std::abs(s.pdf - sampler.pdf(s.m)) <= 1e-12 * s.pdf;
        if (!ok) {
            ++r.bad_samples;
            continue;
        }
        observed[bins.index(s.m)] += 1.0;
    }
    for (int i = 0; i < bins.n_theta; ++i)
        for (int j = 0; j < bins.n_phi; ++j) {
            expected[i * bins.n_phi + j] = bins.integral(sampler.pdf, i, j);
            r.pdf_integral += expected[i * bins.n_phi + j];
        }
    // Pool the bins expecting < 5 samples; a pool that itself expects < 5 joins the smallest of the other cells (as
    // Mitsuba's harness merges it), so that no cell expects fewer than 5: one legitimate sample in a pool expecting
    // 0.01 would otherwise add 100 to the statistic. (A sample where the pdf is 0 is caught above, sample by sample.)
    double pooled_o = 0.0, pooled_e = 0.0;
    std::vector<std::pair<double, double>> cells;  // (observed, expected)
    for (int b = 0; b < nb; ++b) {
        const double e = expected[b] * static_cast<double>(n);
        if (e < 5.0) {
            pooled_o += observed[b];
            pooled_e += e;
        } else {
            cells.emplace_back(observed[b], e);
        }
    }
    if (pooled_e >= 5.0 || (pooled_e > 0.0 && cells.empty())) {
        cells.emplace_back(pooled_o, pooled_e);
    } else if (pooled_e > 0.0) {
        auto smallest = std::min_element(cells.begin(), cells.end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
        smallest->first += pooled_o;
        smallest->second += pooled_e;
    }
    for (const auto& [o, e] : cells) r.statistic += (o - e) * (o - e) / e;
    const int n_cells = static_cast<int>(cells.size());
    r.dof = n_cells - 1;
    if (r.dof < 1) {
        r.note = "fewer than two cells after pooling";
        return r;
    }
    r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(r.dof), r.statistic));
    return r;
}

// The median tan(theta_m) of n samples: a slope scale for the bins that follows the sampler (Hammon's upward rays
// see only steep facets). From its own generator, so the bins do not depend on the samples they count.
inline double median_slope(const smithlab::BoundSampler& sampler, std::size_t n, smithlab::Rng rng) {
    std::vector<double> t(n);
    for (double& x : t) {
        const smithlab::Vec3 m = sampler.sample(rng).m;
        x = std::sqrt((m.x() * m.x() + m.y() * m.y()) / (m.z() * m.z()));
    }
    std::nth_element(t.begin(), t.begin() + n / 2, t.end());
    return t[n / 2];
}

// Sidak: the per-test significance that keeps the family-wise rate at `alpha` over `tests` tests.
inline double sidak(double alpha, std::size_t tests) {
    return 1.0 - std::pow(1.0 - alpha, 1.0 / static_cast<double>(tests));
}

}  // namespace chi2
