/// @file
/// smithlab/lambda_fixed.hpp -- the reduced 1D Lambda by fixed Gauss-Kronrod panels with precomputed nodes.
///
/// The integral (smith.hpp, Lambda_1d; docs/math.md)
///   Lambda(mu) = (2/mu) integral_mu^inf f(r^2) r (sqrt(r^2 - mu^2) - mu acos(mu/r)) dr,   f(r^2) = P22,
/// in u = acosh(r/mu) (r = mu cosh u, sqrt(r^2 - mu^2) = mu sinh u, acos(mu/r) = gd u = atan(sinh u)):
///   Lambda(mu) = 2 integral_0^inf f(r^2) r^2 H(u) du,   H(u) = sinh u (sinh u - gd u) / cosh u.
/// (This is the t-form of smith.hpp with sec t = cosh u, t = gd u.) Two facts make a fixed rule work:
///  - every geometric factor depends on u alone, not on mu: on fixed nodes u_k, r_k^2 = mu^2 cosh^2 u_k, and
///    Lambda = 2 sum_k w_k H(u_k) r_k^2 f(r_k^2) is a dot product with precomputed coefficients, one f per node;
///  - u ~ ln(2 r/mu) for large u: a feature of f at a slope scale r_f (the core r0 = 1/sqrt(pi P22(0)), a GTR tail
///    bending at r ~ 1) sits at u ~ ln(2 r_f/mu) and is O(1) wide there, whatever mu is; the singularities of the
///    integrand nearest to the real u-axis (GGX's pole r^2 = -alpha^2, GTR's branch point r^2 = -1, gd's at
///    u = i pi/2) are pi/2 away from it. The integrand is even in u (sinh u - gd u is odd), zero like u^4 at u = 0.
/// Rule: Gauss-Kronrod 15-31 (Kronrod 1965; the nodes and weights are Boost.Math's gauss_kronrod<double, 31>) on
/// panels [2j, 2j + 2] of u, j < J, then the tail u >= 2J in s = pi/2 - t = atan(1/sinh u) in [0, s_J] (the t-form
/// of smith.hpp, where a power tail of f is smooth: f ~ r^-4 makes the integrand tend to a constant as s -> 0),
/// with J the first panel edge beyond ln(2 max(r0, 1)/mu), at least 1 (the tail then starts past every feature it
/// knows of: its nearest singularity, at s ~ i mu/r_f, is at least one tail length off its end point s = 0). A panel of
/// width 2 puts a singularity pi/2 off its middle at Bernstein ellipse parameter rho = 3.4 (Trefethen 2008, "Is Gauss
/// quadrature better than Clenshaw-Curtis?", thm 4.5: error ~ rho^-2n): 15-point Gauss ~ 1e-16, 31-point Kronrod far
/// below, of the panel's size. (Gauss-Kronrod 10-21 on these panels stopped ~1e-9 short of QUADPACK's test at u ~ 0,
/// where the triple pole of 1/cosh^3 sits, and bisected there.) Error estimate per piece: QUADPACK's QK21 (Piessens, de
/// Doncker-Kapenga, Ueberhuber, Kahaner 1983, sec. 3.2),
///   E = resasc min(1, (200 |K - G| / resasc)^1.5), at least 50 eps resabs;
/// accepted when the sum of E over the pieces is <= tolerance x |Lambda| (tests/test_quadrature.cpp checks that E
/// bounds the error). Otherwise the worst piece is bisected (nodes computed on the fly), up to max_pieces pieces;
/// if that does not converge either, the answer is the adaptive route Lambda_1d (opts.backend) -- the stiff corners
/// (Beckmann at mu/alpha >~ 5, heavy Student-t tails) take that path.
/// No allocation, no exceptions, no virtual call in the loop: it is a template on the concrete NDF.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "smithlab/detail/fixed_rule.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"

namespace smithlab {

/// Lambda with its error estimate, as the fixed rule found it, and how: the number of slope-density evaluations
/// and whether the estimate met the tolerance (else Lambda_fixed returns the adaptive route's value).
struct FixedLambda {
    double Lambda = 0.0;     ///< the fixed rule's value (also when it did not converge)
    double error = 0.0;      ///< its estimated absolute error (sum of QUADPACK's per-piece estimates)
    int evaluations = 0;     ///< slope-density evaluations
    bool converged = false;  ///< error <= tolerance x Lambda
};

/// The fixed rule alone (no fallback), for mu in (0, inf) with the scale r0 = 1/sqrt(pi P22(0)) (1 if P22(0) is 0
/// or not finite). Lambda_fixed() below validates the domain and falls back; this is the core, for tests and benches.
template <Ndf N>
FixedLambda Lambda_fixed_rule(const N& ndf, double mu, double tolerance = 1e-12) {
    using namespace detail::fixed_rule;
    const Tables& T = tables();
    const double r0 = core_slope_scale(ndf);
    const double u_end = std::log(2.0 * std::fmax(r0, 1.0) / mu) + 0.0;
    FixedLambda out;
    out.evaluations = 1;
    if (!(u_end <= max_panels * panel_width)) return out;  // beyond the tables: not converged
    const int J = u_end <= panel_width ? 1 : static_cast<int>(std::ceil(u_end / panel_width));
    const double mu2 = mu * mu;
    // The pieces: J panels and the tail, then the bisection's halves until the estimate meets the tolerance or the
    // pieces run out.
    OpenPieces p;
    start_pieces(ndf, T, mu2, J, p);
    out.evaluations += nodes * p.n;
    int untabled = 0;
    while (!(p.E <= tolerance * std::abs(p.K)) && p.n < max_pieces) {
        if (!bisect_worst(ndf, mu2, p, untabled)) break;
        out.evaluations += 2 * nodes;
    }
    out.Lambda = 2.0 * p.K;
    out.error = 2.0 * p.E;
    out.converged = p.E <= tolerance * std::abs(p.K) && std::isfinite(p.K);
    return out;
}

}  // namespace smithlab
