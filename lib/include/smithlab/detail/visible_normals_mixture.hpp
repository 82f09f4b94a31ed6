/// @file
/// smithlab/detail/visible_normals_mixture.hpp -- exact visible normals of any isotropic NDF whose slope density a
/// mixture of a few GGX lobes bounds: a GGX visible normal drawn from the mixture, accepted with the ratio of the
/// densities.
///
/// For a unit v the law is D_v(m) = <v.m>^+ D(m) / A(v) (visible_normals.hpp). Let Q = sum_k w_k P22_k be a mixture of
/// GGX slope densities (P22_k(s) = alpha_k^2 / (pi (alpha_k^2 + s)^2), Walter 2007 eq. 33 in slopes; sum w_k = 1) with
/// P22(s) <= K Q(s) for every s = tan^2(theta_m). The mixture's visible normals are drawn exactly: lobe k with
/// probability w_k A_k(v) / sum_j w_j A_j(v), then a visible normal of that lobe (Dupuy & Benyoub 2023,
/// detail/visible_normals_closed.hpp), since <v.m>^+ Q / A_Q(v) = sum_k (w_k A_k / A_Q) <v.m>^+ D_k / A_k. A_k(v),
/// GGX's projected area over the whole sphere in Smith's convention, is (R_k + v.z) / 2 with R_k = sqrt(v.z^2 +
/// alpha_k^2 |v_xy|^2) (Heitz 2014 eq. 72: (1 + Lambda) cos theta; below the horizon alpha_k^2 |v_xy|^2 / (2 (R_k -
/// v.z)), no cancellation). The target over the proposal is proportional to rho(s) = P22(s) / Q(s), a function of the
/// normal's slope alone, not of v; accepting with rho / K gives D_v exactly (von Neumann's rejection), with probability
/// A(v) / (K A_Q(v)). Above the horizon A / A_Q stays near 1 (both are v.z at the pole and c |v_xy| at grazing); below
/// it A / A_Q = Lambda(a) / Lambda_Q(a), a = |cot theta_v|, which falls off for an NDF with a lighter tail than the
/// lobes' (Beckmann: e^(-a^2 / alpha^2)): the caller draws those directions by another route (visible_normals.hpp).
///
/// The ratio rho is bounded by a table over x = s / (s + r0^2) in [0, 1) (r0: the NDF's slope scale), 256 bins with
/// the least and the greatest rho of each bin from 65 points (its ends included), widened by a quarter of the bin's
/// range. It is also a squeeze (Marsaglia 1977): a draw whose U K falls below the bin's least is accepted and one at or
/// above its greatest rejected without evaluating the NDF; only the draws between call P22. K is the greatest bound of
/// all bins. The tail s > 16383 r0^2 is checked out to 1e15 r0^2 (rho must not grow there: a tail heavier than GGX's
/// r^-4 has no bound).
///
/// Fitting (once per NDF, 3-15 ms): lobes alpha = r0 2^(j/2), j = -24..24, weighted by expectation-maximization on
/// the D cos law of s; the eight heaviest kept, their weights and widths moved to lower K, and the lightest dropped
/// while that (refitted) raises K by less than 0.05: a lobe costs a root a draw, a try a GGX visible normal and the
/// squeeze, about fifteen times more. A mixture is not used when K > max_bound.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <vector>

#include "smithlab/dcos_law.hpp"
#include "smithlab/detail/visible_normals_closed.hpp"
#include "smithlab/geometry.hpp"
#include "smithlab/rng.hpp"

namespace smithlab::detail {

/// A mixture of up to max_lobes GGX lobes whose slope density Q bounds an NDF's, P22 <= K Q, and the exact visible
/// normals drawn through it (the file comment).
class GgxMixture {
public:
    /// The most lobes a mixture keeps.
    static constexpr int max_lobes = 8;
    /// The bins of the table that bounds P22 / Q over x = s / (s + r0^2).
    static constexpr int bins = 256;
    static constexpr double max_bound = 3.0;  ///< acceptance at least 1/3 (times A(v) / A_Q(v))

    /// The mixture for the slope density P22 (s -> P22(s), s = tan^2(theta_m)) of slope scale r0 > 0; none when no
    /// mixture of the lobes bounds it within max_bound.
    static std::optional<GgxMixture> fit(const std::function<double(double)>& P22, double r0);

    /// A normal m (m.z > 0, v.m > 0) from D_v for a unit v; no_normal() when none is visible (v straight down) or
    /// `tries` draws are rejected. P22 is the NDF's slope density, the one the mixture was fitted to.
    template <class P22Fn, class G>
    Vec3 sample(const Vec3& v, const P22Fn& P22, G& g, long tries = max_tries) const {
        std::array<GgxCap, max_lobes> cap;
        std::array<double, max_lobes> cum{};
        double total = 0.0;
        for (int k = 0; k < lobes_; ++k) {
            cap[k] = ggx_cap(alpha_[k], v);
            total += weight_[k] * cap[k].P;  // w_k 2 A_k(v)
            cum[k] = total;
        }
        if (!(total > 0.0)) return no_normal();
        Vec3 h, m;
        for (long n = 0; n < tries; ++n) {
            int k = 0;
            if (lobes_ > 1)
                for (const double u = uniform01(g) * total; k < lobes_ - 1 && u >= cum[k];) ++k;
            while (!ggx_cap_try(cap[k], g, h)) {}
            const double s = (h.x() * h.x() + h.y() * h.y()) / (h.z() * h.z()), x = s / (s + r02_);
            const double UK = uniform01(g) * K_;
            const int b = x < 1.0 ? static_cast<int>(x * bins) : bins - 1;  // s = inf or NaN (h.z underflowing): last
            if (UK >= hi_[b] || (UK >= lo_[b] && !(UK * Q(s) < P22(s)))) continue;
            if (ggx_cap_normal(h, v, m)) return m;
        }
        return no_normal();
    }

    /// The mixture's slope density Q(s) = sum_k w_k P22_k(s).
    double Q(double s) const {
        double q = 0.0;
        for (int k = 0; k < lobes_; ++k) {
            const double d = alpha2_[k] + s;
            q += weight_[k] * alpha2_[k] / (d * d);
        }
        return q * std::numbers::inv_pi;
    }

    /// The mixture's Lambda at mu = a > 0, sum_k w_k Lambda_k(a) (Heitz 2014 eq. 72): below the horizon its projected
    /// area is |v.z| times this, and the acceptance there Lambda(a) / (K Lambda_Q(a)).
    double Lambda_Q(double a) const {
        double L = 0.0;
        for (int k = 0; k < lobes_; ++k) {
            const double q = alpha2_[k] / (a * a);
            L += weight_[k] * q / (2.0 * (1.0 + std::sqrt(1.0 + q)));
        }
        return L;
    }

    double bound() const { return K_; }  ///< K: P22 <= K Q
    /// The number of lobes, and lobe k's alpha and weight w_k (the weights sum to 1).
    /// @{
    int lobes() const { return lobes_; }
    double alpha(int k) const { return alpha_[k]; }
    double weight(int k) const { return weight_[k]; }
    /// @}

private:
    GgxMixture() = default;

    std::array<double, max_lobes> alpha_{}, alpha2_{}, weight_{};
    int lobes_ = 0;
    double r02_ = 1.0, K_ = 1.0;
    std::array<double, bins> lo_{}, hi_{};  ///< the squeeze: lo_ <= rho <= hi_ over each bin of x
};

}  // namespace smithlab::detail
