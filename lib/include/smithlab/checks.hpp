/// @file
/// smithlab/checks.hpp -- the checks every NDF must pass (docs/math.md; Walter 2007
/// sec. 3 and appendix A; Heitz 2014 eq. 2 for the projected-area identity). Each is computed by a route independent
/// of the one it checks.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/smith.hpp"

namespace smithlab {

/// One per-distribution check: what was computed against what it must equal, and whether it is within tolerance.
struct CheckResult {
    std::string name;   ///< what is checked
    std::string where;  ///< at which direction / mu
    double value;       ///< what was computed
    double expected;    ///< what it must equal
    double tolerance;   ///< on the relative residual
    /// |value - expected| / |expected|, 0 where they are equal (infinities included).
    double residual() const { return value == expected ? 0.0 : std::abs(value - expected) / std::abs(expected); }
    /// Whether the relative residual is within the tolerance (a NaN fails).
    bool passed() const { return residual() <= tolerance; }
};

/// How the checks compute the integrals they compare.
struct CheckOptions {
    /// The quadrature library of the integrals (quadrature.hpp).
    Backend backend = Backend::boost;
    bool with_2d = true;  ///< the nested route costs milliseconds per Lambda
};

namespace detail {
/// integral over phi in [0, 2 pi) of max(0, a cos(phi) + b), a >= 0.
double clamped_cosine_azimuth(double a, double b);
std::string format_where(const char* name, double value);

/// D cos^4 at tan^2 = r2 as the checks on D read it: through cos(theta_m), as the user wrote D, while the NDF's core
/// scale is >= 1e-3; below, where cos(theta_m) cannot carry a slope's digits (the rounding of sin^2 = (1-c)(1+c) is
/// 1e-16 / r^2 relative: a few 1e-9 of the integrals at alpha = 1e-4, 1e-7 at 1e-5, all of them from 1e-8 on), through
/// the NDF's slope form P22 (for a D-only NDF that is D again).
template <Ndf N>
double checked_D_cos4(const N& ndf, double r2, double r0) {
    if constexpr (HasSlopeDensity<N>) {
        if (r0 < 1e-3) return ndf.slope_density(r2);
    }
    return D_cos4(ndf, r2);
}
}  // namespace detail

// The integrals over the hemisphere below are written in r = tan(theta_m), where cos(theta) sin(theta) dtheta =
// cos^4(theta) r dr, and integrated on a log axis split at the core scale r0 (and 1, and the kink), so that the peak
// of D at r ~ alpha is found at any alpha. D is read as the user wrote it (detail::checked_D_cos4).

/// 1. integral over the hemisphere of D(m) cos(theta_m) dm = 2 pi integral_0^inf D cos^4 r dr = 1.
template <Ndf N>
double projected_area(const N& ndf, Backend backend = Backend::boost) {
    const double r0 = core_slope_scale(ndf);
    auto f = [&](double r) { return detail::checked_D_cos4(ndf, r * r, r0) * r; };
    return 2.0 * std::numbers::pi * integrate_log_axis(f, {backend, 1e-12}, std::min(r0, 1.0), std::max(r0, 1.0));
}

/// 3. integral of <v.m> D(m) dm over the hemisphere for v at theta_v: the azimuth of the clamped cosine is done in
/// closed form, the polar angle by quadrature in r, split at the kink r = cot(theta_v). Smith's G1 is defined
/// so that G1(v) times this equals cos(theta_v) (Heitz 2014 eq. 2).
template <Ndf N>
double visible_projected_area(const N& ndf, double theta_v, Backend backend = Backend::boost) {
    const double sv = std::sin(theta_v), cv = std::cos(theta_v), r0 = core_slope_scale(ndf), kink = cv / sv;
    // D sin(theta) Phi(sin theta_v sin theta, cos theta_v cos theta) dtheta = D cos^4 r Phi(r sin theta_v, cos theta_v)
    // dr, Phi being homogeneous of degree 1.
    auto f = [&](double r) {
        return detail::checked_D_cos4(ndf, r * r, r0) * r * detail::clamped_cosine_azimuth(sv * r, cv);
    };
    return integrate_log_axis(f, {backend, 1e-12}, std::min(r0, kink), std::max(r0, kink));
}

/// Tolerances. The checks on D itself (1 and 3) read D through cos(theta_m), whose rounding near the pole is a
/// relative error of ~1e-16/theta^2 in sin^2(theta): at alpha = 1e-4 that is 1e-8 in D across the peak. Integrated,
/// it averages down to a few 1e-9, so those checks are held to 1e-8; the slope-space ones to 1e-9 and tighter.
/// The Lambda comparisons run at mu = {0.1, 1, 10} s, s = min(max(1, r0), 1e11), inside the quadrature routes'
/// domain (smith.hpp); an NDF whose core scale r0 exceeds 1e22 leaves them none, and is refused (input_error).
template <Ndf N>
std::vector<CheckResult> run_checks(const N& ndf, const CheckOptions& opts = {}) {
    std::vector<CheckResult> out;
    const QuadratureOptions q{opts.backend, 1e-12};
    const double r0 = core_slope_scale(ndf);
    require(r0 <= 1e22, "checks: the ndf's slope scale 1/sqrt(pi P22(0))",
            "<= 1e22 (alpha <= 1e22), where the "
            "quadrature routes the checks compare have a mu to run at",
            r0);
    out.push_back({"integral D cos dm = 1", "", projected_area(ndf, opts.backend), 1.0, 1e-8});
    if (opts.with_2d) {
        const double p2 = 2.0 *
            integrate_log_axis([&](double x) { return P2(ndf, x, q); }, {opts.backend, 1e-11}, std::min(r0, 1.0),
                               std::max(r0, 1.0));
        out.push_back({"integral P2 dq = 1", "", p2, 1.0, 1e-9});
    }
    LambdaOptions lo;
    lo.backend = opts.backend;
    for (double deg : {30.0, 60.0, 80.0, 89.0}) {
        const double th = deg * std::numbers::pi / 180.0;
        const double mu = std::cos(th) / std::sin(th);
        out.push_back({"G1(v) int <v.m> D dm = cos theta_v", detail::format_where("theta_v(deg)", deg),
                       G1(ndf, mu, lo) * visible_projected_area(ndf, th, opts.backend), std::cos(th), 1e-8});
    }
    const double scale = std::min(std::max(1.0, r0), 1e11);
    for (double m : {0.1, 1.0, 10.0}) {
        const double mu = m * scale;
        const double l1 = Lambda_1d(ndf, mu, q);
        if (opts.with_2d)
            out.push_back({"Lambda 1D = 2D", detail::format_where("mu", mu), l1, Lambda_2d(ndf, mu, q), 1e-8});
        if (has_closed_Lambda(ndf)) {
            lo.method = Method::closed;
            out.push_back({"Lambda 1D = closed form", detail::format_where("mu", mu), l1, Lambda(ndf, mu, lo), 1e-10});
        }
    }
    // 4. An analytic D cos sampler inverts the right law: the D cos mass beyond its quantile, 2 pi integral_r^inf
    // D cos^4 r dr from D itself, is the probability it was asked for.
    if constexpr (HasDcosSampler<N>) {
        if (has_Dcos_sampler(ndf))
            for (double v : {0.9, 0.5, 0.1, 1e-3}) {
                const double r_q = std::sqrt(ndf.Dcos_r2(v));
                auto f = [&](double r) { return r > r_q ? detail::checked_D_cos4(ndf, r * r, r0) * r : 0.0; };
                out.push_back({"D cos sampler: mass beyond its quantile", detail::format_where("v", v),
                               2.0 * std::numbers::pi * integrate_log_axis(f, q, r_q, std::max(r_q, std::max(r0, 1.0))),
                               v, 1e-8});
            }
    }
    return out;
}

}  // namespace smithlab
