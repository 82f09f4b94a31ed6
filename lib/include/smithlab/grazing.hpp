/// @file
/// smithlab/grazing.hpp -- Lambda and G1 near grazing (mu -> 0), where no quadrature resolves the integrand.
///
/// From Lambda(mu) = (1/mu) integral_mu^inf (q - mu) P2(q) dq (Walter 2007 eq. 48; Heitz 2014 eq. 72) and
/// integral_0^inf P2 = 1/2 (P2 is an even density):
///   mu Lambda(mu) = c - mu/2 + R(mu),   c = integral_0^inf q P2(q) dq = E[max(q, 0)],
///   R(mu) = integral_0^mu (mu - q) P2(q) dq = P2(0) mu^2 / 2 + E(mu),
/// and in polar slope coordinates (q = r sin phi over the upper half plane) c = 2 integral_0^inf r^2 P22(r^2) dr:
/// GGX alpha/2, Beckmann alpha/(2 sqrt(pi)). The grazing law keeps the first three terms,
///   Lambda(mu) = c/mu - 1/2 + P2(0) mu/2,      G1 = 1/(1 + Lambda) = mu / (c + mu/2 + P2(0) mu^2/2),
/// G1 in its own form so that it holds where c/mu overflows (mu = 4.9e-324: Lambda = +inf, G1 a denormal).
/// Its error is E(mu)/mu = (1/mu) integral_0^mu (mu - q) (P2(q) - P2(0)) dq: at most (mu/2) max |P2(q) - P2(0)| over
/// [0, mu], so relative to Lambda at most P2(0) mu^2 / (2c - mu) for a P22 that does not increase with the slope
/// (0 <= P2 <= P2(0)); O((mu/r0)^2), r0 the core slope scale (GGX: (mu/alpha)^2 / 2). Where P22 is smooth in r^2, as
/// for every built-in family, P2(q) - P2(0) = P2''(0) q^2/2 + .. and the error is |P2''(0)| mu^4 / (24 c) relative,
/// O((mu/r0)^4). smithlab answers by the law below the quadrature routes' domain (mu < 1e-12 and mu < 1e-12 r0)
/// and only at mu <= 1e-8 r0 (smith.hpp), where the first bound is ~1e-16, at double rounding; between 1e-8 r0 and
/// 1e-12 (r0 < 1e-4) neither holds and the quadrature's refusal stands. The tabulated Lambda (lambda_table.hpp) ends
/// in the same law, its first two terms, with c measured from its knots.
/// An NDF whose c is infinite (a slope tail P22 ~ r^-3 or heavier) has no such law: mu Lambda grows without bound.
#pragma once

#include <algorithm>
#include <cmath>
#include <mutex>
#include <optional>

#include "smithlab/errors.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"

namespace smithlab {

/// The constants of the grazing law of one NDF.
struct GrazingLaw {
    double c = 0.0;     ///< E[q+] = 2 integral_0^inf r^2 P22(r^2) dr
    double P2_0 = 0.0;  ///< P2(0) = 2 integral_0^inf P22(p^2) dp (Walter 2007 eq. 43 at q = 0)
};

/// Lambda(mu) = c/mu - 1/2 + P2(0) mu/2, for 0 < mu below the quadrature domain; +inf where c/mu overflows.
inline double Lambda_grazing(const GrazingLaw& law, double mu) { return law.c / mu - 0.5 + 0.5 * law.P2_0 * mu; }
/// G1 = mu / (c + mu/2 + P2(0) mu^2/2): the same law, without the overflow of c/mu.
inline double G1_grazing(const GrazingLaw& law, double mu) { return mu / (law.c + mu * (0.5 + 0.5 * law.P2_0 * mu)); }

namespace detail {
/// input_error unless T(r) = r^3 P22(r^2) (the log-axis integrand of c) falls at least like r^-0.05 between r = R
/// and 10 R, R = 1e20 max(r0, 1) (past every slope scale): a tail P22 ~ r^-k with k <= 3.05 leaves c infinite or out
/// of reach (integral_R^inf r^2 P22 dr = T(R)/(k - 3)).
void require_finite_grazing_c(double T_R, double T_10R, double R);
/// input_error unless c and P2(0) came out finite and c > 0.
void require_grazing_constants(double c, double P2_0);
}  // namespace detail

/// The grazing law of ndf: c and P2(0) by quadrature on a log axis split at the core scale r0 and at 1 (a GTR tail
/// bends there), to opts.tolerance (relative). Through the NDF's own slope form where it has one, else through D,
/// refused as the quadrature routes refuse it below r0 = 1e-3 (smith.hpp, require_slope_digits). An NDF that names
/// its quadrature (a tabulated D: its kinks) is integrated by that backend. input_error where c is infinite.
template <Ndf N>
GrazingLaw grazing_law(const N& ndf, QuadratureOptions opts = {}) {
    if constexpr (requires { ndf.quadrature_backend(); })
        if (const std::optional<Backend> b = ndf.quadrature_backend()) opts.backend = *b;
    const double r0 = core_slope_scale(ndf);
    // r^(2k) P22(r^2), 0 where r^2 overflows (r > 1e154: a tail that keeps c finite leaves below 1e-100 of it there
    // for r0 <= 1e50)
    auto moment = [&](double r, bool second) {
        const double r2 = r * r;
        if (!(r2 < INFINITY)) return 0.0;
        const double f = slope_density(ndf, r2);
        return second ? r2 * f : f;
    };
    const double R = 1e20 * std::max(r0, 1.0);
    if (100.0 * R * R < INFINITY)
        detail::require_finite_grazing_c(R * moment(R, true), 10.0 * R * moment(10.0 * R, true), R);
    const double lo = std::min(r0, 1.0), hi = std::max(r0, 1.0);
    GrazingLaw law;
    law.c = 2.0 * integrate_log_axis([&](double r) { return moment(r, true); }, opts, lo, hi);
    law.P2_0 = 2.0 * integrate_log_axis([&](double p) { return moment(p, false); }, opts, lo, hi);
    detail::require_grazing_constants(law.c, law.P2_0);
    return law;
}

/// The grazing law of one NDF, computed on first use and then shared: any number of threads may call get() at once
/// (std::call_once). A refusal (input_error) is thrown to every caller that asks, each time.
class GrazingLawOnce {
public:
    /// The grazing law of `ndf` (grazing_law), computed by the first call that succeeds; later calls return it,
    /// whatever NDF they pass.
    template <Ndf N>
    const GrazingLaw& get(const N& ndf, const QuadratureOptions& opts) {
        std::call_once(once_, [&] { law_ = grazing_law(ndf, opts); });  // a throw leaves it to the next call
        return law_;
    }

private:
    std::once_flag once_;
    GrazingLaw law_;
};

}  // namespace smithlab
