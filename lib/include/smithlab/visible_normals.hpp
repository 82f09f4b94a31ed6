/// @file
/// smithlab/visible_normals.hpp -- the visible normals of a direction anywhere on the sphere, for one NDF, templated on
/// it (no virtual call, std::function, allocation or exception in a sample): what the microsurface walk draws its hit
/// normals from, and what the type-erased VisibleNormalSampler (sampling.hpp) wraps.
///
/// For a unit v the law is D_v(m) = <v.m>^+ D(m) / A(v) over m.z > 0, with the projected area
///     A(v) = (1 + Lambda(v)) cos(theta_v)  over the whole sphere, Smith's Lambda(-mu) = -1 - Lambda(mu)
/// (Heitz, Hanika, d'Eon, Dachsbacher 2016, "Multiple-scattering microfacet BSDFs with the Smith model", sec. 4, the
/// microflake view of the Smith volume): A(v) = (1 + Lambda(mu)) v.z above the horizon, Lambda(|mu|) |v.z| below.
/// Both are |v_xy| W(|mu|) + max(v.z, 0) with W(a) = a Lambda(a) = integral_a^inf (q - a) P2(q) dq (Walter 2007 eq. 48
/// times a), so A(v) - A(-v) = v.z. Above the horizon D_v = G1(v) <v.m> D / cos(theta_v) (Heitz 2014).
///
/// In slope space, with v turned into the xz-plane and mu = cot(theta_v) of either sign, the visible slopes have
/// density P22(x, y) (mu - x)^+ (Heitz & d'Eon 2014, eq. 5-6; its integral is |v_xy|-free: W(|mu|) + max(mu, 0)).
/// Routes (VisibleRoute):
///   closed form   when the NDF is GGX or Beckmann by its capability (ndf.hpp: ggx_alpha(), beckmann_alpha()):
///                 detail/visible_normals_closed.hpp.
///   mixture       any NDF a mixture of GGX lobes bounds (tails no heavier than r^-4): GGX visible normals of the
///                 mixture, accepted with P22 / (K Q), exact (detail/visible_normals_mixture.hpp). What the walk uses
///                 for every NDF but GGX; below the horizon, where the NDF's Lambda falls under 1/8 of the mixture's (a
///                 lighter tail than GGX's, Beckmann's, seen from steeply below), the rejection route's mu < 0.
///   rejection     any NDF, exact up to the tables it reads:
///     mu >= 0: in polar slopes (r, phi) the target is P22 r (mu - r cos phi)^+, drawn from P22 r (mu + r) x uniform
///              phi -- a mixture of the D cos law of r (weight mu) and the law P22 r^2 dr (weight 2 pi M, M its
///              integral: a detail::RadialTable) -- accepting with (mu - r cos phi)^+ / (mu + r). Acceptance
///              mu (1 + Lambda) / (mu + 2 pi M): 1 at normal incidence, 1/pi at grazing.
///     mu < 0:  with a = -mu and x' = -x, the target P22 (x' - a)^+ is the marginal of P22(x'^2 + y^2) 1[a < xi < x']:
///              draw xi from its marginal, the half-plane mass U0(xi) = P(X > xi) on xi > a, whose survival is
///              W(xi) / W(a) (dW/dx = -U0), by solving W(xi) = (1 - u) W(a) in ln xi (Illinois regula falsi, on the
///              NDF's FastLambda); then (x', y) from P22 on the half-plane x' > xi: s = r^2 from the D cos law
///              truncated to s > xi^2 (its survival drawn in (0, S(xi^2)]), phi uniform on the arc |phi| < delta,
///              cos delta = xi / r, accepted with delta / (pi / 2) (exact: the target over the proposal is 2 delta).
///              Acceptance E[delta] / (pi / 2): O(1) for tails P22 ~ r^-4 (GGX, GTR), falling like alpha / a for a
///              Gaussian tail (Beckmann; its closed form has no such loss), where the law P22 r^2 dr truncated to
///              r > a, the direct proposal, falls like (alpha / a)^3.
///   tabulated     rejection with the D cos law tabulated too (what a D-only NDF gets).
/// A sampler that cannot draw returns no_normal() (dcos_law.hpp): v straight down (A = 0), a projected area that
/// underflows, or max_tries rejections.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "smithlab/dcos_law.hpp"
#include "smithlab/detail/radial_table.hpp"
#include "smithlab/detail/visible_normals_closed.hpp"
#include "smithlab/detail/visible_normals_mixture.hpp"
#include "smithlab/fast_lambda.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/ndf.hpp"
#include "smithlab/quadrature.hpp"
#include "smithlab/rng.hpp"
#include "smithlab/turn.hpp"

namespace smithlab {

/// The mixture of GGX lobes that bounds the NDF's slope density (detail/visible_normals_mixture.hpp), at the slope
/// scale of the median of its D cos law; none where no mixture does.
template <Ndf N>
std::optional<detail::GgxMixture> fit_ggx_mixture(const N& ndf, const DcosLaw<N>& dcos) {
    return detail::GgxMixture::fit([ndf](double s) { return slope_density(ndf, s); }, std::sqrt(dcos.isf(0.5)));
}

/// automatic: GGX's closed form, else the mixture where it bounds the NDF, else Beckmann's closed form, else rejection
/// (with the NDF's analytic D cos law if any). closed: the closed form where the NDF offers one, else rejection.
/// mixture: the mixture where it bounds the NDF, else rejection.
enum class VisibleRoute { automatic, closed, mixture, rejection, tabulated };

/// The visible normals of an NDF N for directions anywhere on the sphere, by the route VisibleRoute picks (the file
/// comment).
template <Ndf N>
class VisibleNormals {
public:
    /// Prepares the route for `ndf`: the D cos law, the Lambda table, the mixture fitted or the tables of the rejection
    /// route; `route` other than automatic forces one (tabulated: the rejection route with the D cos law tabulated
    /// too).
    explicit VisibleNormals(const N& ndf, VisibleRoute route = VisibleRoute::automatic)
        : dcos_(ndf, route == VisibleRoute::tabulated), Lambda_(ndf) {
        if (route == VisibleRoute::automatic || route == VisibleRoute::closed) ggx_ = ggx_alpha(ndf);
        if (std::isnan(ggx_) && (route == VisibleRoute::automatic || route == VisibleRoute::mixture))
            mixture_ = fit_ggx_mixture(ndf, dcos_);
        if (std::isnan(ggx_) && !mixture_ && (route == VisibleRoute::automatic || route == VisibleRoute::closed))
            beckmann_ = beckmann_alpha(ndf);
        auto r2_law = [ndf](double s) { return 0.5 * slope_density(ndf, s) * std::sqrt(s); };  // P22 r^2 dr in s
        if (!closed_form() && !mixture_) r_law_ = std::make_shared<const detail::RadialTable>(r2_law);
        // W(0) = E[x^+] = 2 M, the projected area of a horizontal direction.
        if (r_law_) W0_ = 2.0 * r_law_->total();
        else if (!Lambda_.tabulated()) W0_ = 1e-100 * Lambda_(1e-100);  // W(0) - 1e-100 / 2
        if (!(W0_ > 0.0 && W0_ < INFINITY)) W0_ = 2.0 * integrate_log_axis(r2_law);
        if (mixture_) mixture_below2_ = mixture_reach_below();
    }

    /// A normal m (m.z > 0, v.m > 0) from D_v, for a unit v with A(v) > 0; no_normal() when it cannot draw. The
    /// closed forms inline where they are called; the rejection routes, out of line, keep them small.
    template <class G>
    Vec3 sample(const Vec3& v, G& g) const {
        if (ggx_ > 0.0) return detail::sample_ggx_visible_normal(ggx_, v, g);
        if (mixture_) {
            if (v.z() < 0.0 && v.z() * v.z() > mixture_below2_ * (v.x() * v.x() + v.y() * v.y())) [[unlikely]]
                return sample_by_rejection(v, g);
            return mixture_->sample(
                v, [this](double s) { return dcos_.P22(s); }, g);
        }
        if (beckmann_ > 0.0) return detail::sample_beckmann_visible_normal(beckmann_, v, g);
        return sample_by_rejection(v, g);
    }

    /// The rejection route for any NDF (the file comment), whatever route was prepared: a normal from D_v for a unit v,
    /// no_normal() when it cannot draw.
    template <class G>
    [[gnu::noinline]] Vec3 sample_by_rejection(const Vec3& v, G& g) const {
        const double sin_v = norm_xy(v);
        if (sin_v == 0.0) return v.z() > 0.0 ? dcos_.sample(g) : no_normal();  // straight up: D_v = D cos
        const double mu = v.z() / sin_v, c = v.x() / sin_v, sn = v.y() / sin_v;
        for (int k = 0; k < 100; ++k) {
            const Slope p = mu >= 0.0 ? slope_above(mu, g) : slope_below(-mu, g);
            if (!(p.s >= 0.0)) return no_normal();
            // The normal of slope (x, y) is (-x, -y, 1) / |.|, turned back to v's azimuth.
            const double n = 1.0 / std::sqrt(1.0 + p.s);
            const Vec3 m((-p.x * c + p.y * sn) * n, (-p.x * sn - p.y * c) * n, n);
            if (v.dot(m) > 0.0) return m;  // not, only by rounding at grazing slopes
        }
        return no_normal();
    }

    /// D_v(m) = <v.m>^+ D(m) / A(v); 0 where A(v) = 0.
    double pdf(const Vec3& v, const Vec3& m) const {
        const double vm = v.dot(m);
        if (!(m.z() > 0.0 && vm > 0.0)) return 0.0;
        const double A = projected_area(v);
        return A > 0.0 ? vm * D(m) / A : 0.0;
    }

    /// A(v) = |v_xy| W(|mu|) + max(v.z, 0), Smith's convention over the whole sphere.
    double projected_area(const Vec3& v) const {
        const double sin_v = norm_xy(v);
        if (sin_v == 0.0) return std::max(v.z(), 0.0);
        return sin_v * W(std::abs(v.z()) / sin_v) + std::max(v.z(), 0.0);
    }

    /// D(m) from the slope form, P22(s) (1 + s)^2 (Walter 2007 eq. 42), exact near the pole; within 1e-50 of the
    /// horizon, where (1 + s)^2 and P22's own powers of s overflow, the NDF's D(cos theta_m); 0 for m.z <= 0.
    double D(const Vec3& m) const {
        if (!(m.z() > 0.0)) return 0.0;
        const double s = tan2_theta(m);
        return s < 1e100 ? D_from_P22(dcos_.P22(s), s) : dcos_.ndf().D(m.z());
    }

    /// The NDF's Lambda for the walk (fast_lambda.hpp).
    const FastLambda<N>& Lambda() const { return Lambda_; }
    /// The NDF's D cos law.
    const DcosLaw<N>& dcos() const { return dcos_; }
    /// Whether the route is a closed form (GGX's or Beckmann's visible normals).
    bool closed_form() const { return ggx_ > 0.0 || beckmann_ > 0.0; }
    /// The mixture of GGX lobes the route draws through, if any.
    const std::optional<detail::GgxMixture>& mixture() const { return mixture_; }
    /// The worst of its tables' estimates: the CDF tables' in probability, the Lambda table's relative.
    double table_error() const {
        return std::max({dcos_.table_error(), r_law_ ? r_law_->error_estimate() : 0.0, Lambda_.error_estimate()});
    }

private:
    struct Slope {
        double x, y, s;  // s = x^2 + y^2, carried from the law of s (exact near the pole); NaN: gave up
    };
    static Slope none() { return {0.0, 0.0, std::numeric_limits<double>::quiet_NaN()}; }

    /// W(a) = a Lambda(a). Where a tabulated Lambda hands the call to quadrature and that refuses (a < 1e-12,
    /// a > 1e12), and wherever a Lambda(a) would over- or underflow (a < 1e-100), the ends of W: W(0) - a/2 (dW/da =
    /// -U0, U0(0) = 1/2; the next term, a^2 P2(0) / 2, is below 1e-24 / r0 there), and W(1e12) 1e12 / a (Lambda ~ C /
    /// mu^2 for every tail P22 ~ r^-4 or lighter).
    double W(double a) const {
        constexpr double near = 1e-12, far = 1e12;
        if (a < 1e-100 || (Lambda_.tabulated() && a < near)) return W0_ - 0.5 * a;
        if (!(a < INFINITY)) return 0.0;
        if (Lambda_.tabulated() && a > far) return far * Lambda_(far) * (far / a);
        return a * Lambda_(a);
    }

    /// The square of the greatest a = |cot theta_v| below the horizon up to which the mixture's acceptance there,
    /// Lambda(a) / (K Lambda_Q(a)), stays above 1 / (8 K) (from a = 1e-4 r0 up in steps of 2^(1/4), r0 the NDF's
    /// core slope scale); inf when it does so to 1e4 r0, where every ratio has reached its limit (tails as GGX's:
    /// Lambda ~ C / a^2 for both).
    double mixture_reach_below() const {
        const double r0 = core_slope_scale(dcos_.ndf());
        for (double a = 1e-4 * r0; a <= 1e4 * r0; a *= 1.189207115002721)
            if (!(Lambda_(a) >= 0.125 * mixture_->Lambda_Q(a))) return a * a / 1.4142135623730951;  // the step before
        return INFINITY;
    }

    /// mu >= 0: the mixture proposal, accepted with (mu - x)^+ / (mu + r).
    template <class G>
    Slope slope_above(double mu, G& g) const {
        constexpr double pi = std::numbers::pi;
        const double p_dcos = mu / (mu + 2.0 * pi * r_law_->total());
        for (long tries = 0; tries < max_tries; ++tries) {
            const double u = 1.0 - uniform01(g);
            const double s = uniform01(g) < p_dcos ? dcos_.isf(u) : r_law_->isf(u);
            const double r = std::sqrt(s);
            const CosSin phi = cos_sin_turn(uniform01(g));
            const double x = r * phi.c;
            if (uniform01(g) * (mu + r) < mu - x) return {x, r * phi.s, s};
        }
        return none();
    }

    /// mu = -a < 0: xi, then the half-plane beyond it.
    template <class G>
    Slope slope_below(double a, G& g) const {
        const double Wa = W(a);
        if (!(Wa > 0.0)) return none();
        for (long tries = 0; tries < max_tries;) {
            const double xi = solve_W(a, Wa, (1.0 - uniform01(g)) * Wa);
            const double S_xi = dcos_.sf(xi * xi);
            ++tries;
            if (!(S_xi > 0.0)) continue;
            for (; tries < max_tries; ++tries) {
                const double s = dcos_.isf(S_xi * (1.0 - uniform01(g)));
                const double delta = std::atan2(std::sqrt(std::max(0.0, s - xi * xi)), xi);  // r cos(delta) = xi
                if (uniform01(g) * (0.5 * std::numbers::pi) >= delta) continue;
                const double phi = delta * (2.0 * uniform01(g) - 1.0), r = std::sqrt(s);
                return {-r * std::cos(phi), r * std::sin(phi), s};
            }
        }
        return none();
    }

    /// xi >= a with W(xi) = T, T in (0, W(a)]: F(y) = ln W(e^y) - ln T is decreasing in y = ln xi and >= 0 at ln a.
    /// Bracketed by secant steps from a first step of 1/64 (at least doubling, at most 64-fold), then Illinois (regula
    /// falsi halving the stale end), bisecting where F is not finite (W underflows); to |F| <= 1e-14 (the survival's
    /// relative error) or a bracket of 1e-15 in ln xi.
    double solve_W(double a, double Wa, double T) const {
        const double lnT = std::log(T);
        auto F = [&](double y) { return std::log(W(std::exp(y))) - lnT; };
        double lo = std::log(a), f_lo = std::log(Wa) - lnT;
        if (!(f_lo > 1e-14)) return a;
        double hi = lo + 1.0 / 64.0, f_hi = F(hi);
        for (int i = 0; i < 60 && f_hi > 0.0; ++i) {
            const double step = hi - lo, slope = (f_hi - f_lo) / step;
            const double next = hi + std::clamp(slope < 0.0 ? -f_hi / slope : INFINITY, 2.0 * step, 64.0 * step);
            lo = hi, f_lo = f_hi;
            hi = next, f_hi = F(hi);
        }
        int side = 0;
        for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(lo)); ++i) {
            double y = std::isfinite(f_hi) ? (lo * f_hi - hi * f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
            if (!(y > lo && y < hi)) y = 0.5 * (lo + hi);
            const double f = F(y);
            if (std::abs(f) <= 1e-14) return std::exp(y);
            if (f > 0.0) {
                lo = y, f_lo = f;
                if (side == 1) f_hi *= 0.5;
                side = 1;
            } else {
                hi = y, f_hi = f;
                if (side == -1) f_lo *= 0.5;
                side = -1;
            }
        }
        return std::exp(0.5 * (lo + hi));
    }

    DcosLaw<N> dcos_;
    FastLambda<N> Lambda_;
    std::optional<detail::GgxMixture> mixture_;
    double mixture_below2_ = INFINITY;  ///< below the horizon, cot^2 theta_v beyond this: the rejection route
    std::shared_ptr<const detail::RadialTable> r_law_;  ///< the law P22 r^2 dr in s = r^2; rejection routes only
    double ggx_ = std::numeric_limits<double>::quiet_NaN(), beckmann_ = std::numeric_limits<double>::quiet_NaN();
    double W0_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace smithlab
