/// @file
/// smithlab/walk/steps.hpp -- what every walk of walk.hpp and position_free.hpp shares: the tallies by scattering
/// order and diffuse events, the limits of a walk, one event's scattering and phase on the side the ray is on, and the
/// eval estimators' sample with its next-event tally.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"

namespace smithlab::walk {

/// Tallies by scattering order: 1, 2, 3, 4+.
inline constexpr int order_bins = 4;
/// The bin of scattering order `order` (1 or more): order - 1, the orders from order_bins on in the last.
inline int order_bin(std::int64_t order) { return static_cast<int>(std::min<std::int64_t>(order, order_bins)) - 1; }

/// Where a walk stops short of escaping: a highest order asked for, and a cap on its hits.
struct WalkLimits {
    int max_order = 0;  ///< > 0: the walk ends after this many hits (the orders beyond are not asked for)
    std::int64_t max_events = 1'000'000;  ///< a walk still inside after this many hits ends as `capped` (never a hang)
};

/// Tallies by the number of diffuse events on the way: 0 .. diffuse_bins - 2, and diffuse_bins - 1 or more. Light that
/// scattered diffusely k times carries albedo^k (each diffuse event of lambert and fresnel-diffuse facets multiplies
/// by the albedo, and nothing else depends on it), so a walk traced at albedo 1 and split by k gives the result at
/// every albedo a as sum_k a^k f_k (the fitter's data: fit/dataset.hpp).
inline constexpr int diffuse_bins = 16;
/// The bin of k diffuse events: k, those from diffuse_bins - 1 on in the last.
inline int diffuse_bin(int k) { return std::min(k, diffuse_bins - 1); }

/// One walk of eval_walk: its estimate of f(wi, wo) `|`cos theta_o`|`, split by scattering order, component and
/// diffuse events.
struct EvalSample {
    /// f `|`cos theta_o`|` by order bin (order_bin) and component.
    ///@{
    std::array<double, order_bins> specular{}, diffuse{};
    ///@}
    std::array<double, diffuse_bins> by_diffuse{};  ///< the same by diffuse events (diffuse_bin), all orders
    std::int64_t events = 0;  ///< hits of the walk (of the reversed one for EvalEstimator::reciprocal)
    bool capped = false;      ///< it ended at max_events hits or where no normal could be drawn (no estimate where the
                              ///< microsurface's hits do not draw visible normals)
};

namespace detail {
/// One event of a walk on the side the ray is on (the local frame): the material's scattering, told the side when it
/// has two. A ray it lets through moves to the other side's frame: direction and height negated.
template <class M, class G>
Scatter scatter(const M& material, const Vec3& v, const Vec3& m, G& g, bool above) {
    if constexpr (TwoSided<M>) return material.sample(v, m, g, above);
    else return material.sample(v, m, g);
}
template <class Microsurface, class M, class G>
Phase phase(const Microsurface& ms, const M& material, const Vec3& v, const Vec3& wo, G& g, bool above) {
    if constexpr (TwoSided<M>) return material.phase(ms, v, wo, g, above);
    else return material.phase(ms, v, wo, g);
}

/// The microsurface with the visible normal of the direction at hand already drawn: a material's phase() asked for a
/// visible normal gets that one (EvalEstimator::expected_first shares the hit normal with the phase estimate).
template <class Microsurface>
struct DrawnNormal {
    const Microsurface& ms;
    Vec3 m;
    template <class G>
    Vec3 visible_normal(const Vec3&, G&) const {
        return m;
    }
    decltype(auto) normals() const { return ms.normals(); }
};

/// E[C1(h1)^Lambda(wo)] over the height h1 where a ray travelling along w (down) from above the surface first hits
/// it: a / (a + Lambda(wo)), a = -Lambda(w) (EvalEstimator::expected_first); 1 where wo is straight up (Lambda = 0),
/// 0 where it is horizontal. A stand-in microsurface without Lambda (a test's) gets the sampled chance at h1.
template <class Microsurface>
double expected_first_escape(const Microsurface& ms, const Vec3& w, const Vec3& wo, double h1) {
    if (!(wo.z() > 0.0)) return 0.0;
    if constexpr (!requires { ms.Lambda(w); }) return ms.escape(wo, h1);
    else {
        const double a = -ms.Lambda(w), L = ms.Lambda(wo);
        if (L == 0.0) return 1.0;
        if (a == INFINITY) return 1.0;
        if (!(L < INFINITY)) return 0.0;
        return a / (a + L);
    }
}
/// A next event's term, w (the path's weight times the escape chance) times the phase, tallied at its order after
/// `diffuse` diffuse events: the phase's specular part adds no diffuse event to the path, its diffuse part one.
inline void scale(EvalSample& s, double c) {
    for (double& x : s.specular) x *= c;
    for (double& x : s.diffuse) x *= c;
    for (double& x : s.by_diffuse) x *= c;
}
inline void add_next_event(EvalSample& out, std::int64_t order, int diffuse, double w, const Phase& p) {
    const int b = order_bin(order);
    (diffuse > 0 ? out.diffuse : out.specular)[b] += w * p.specular;
    out.diffuse[b] += w * p.diffuse;
    out.by_diffuse[diffuse_bin(diffuse)] += w * p.specular;
    out.by_diffuse[diffuse_bin(diffuse + 1)] += w * p.diffuse;
}

/// The chance to escape toward wo from height h, for next-event estimation. From this side, wo up (local) is reached
/// by reflection and escapes this side; wo down only through the surface, escaping on the other side (where it and the
/// height are negated); one-sided phases are 0 there. At the first hit of expected_first, its closed-form average
/// over the hit's height.
template <class M, class Microsurface>
double next_event_escape(const Microsurface& ms, bool first_expected, const Vec3& w, const Vec3& wo_local, double h) {
    if (wo_local.z() > 0.0) return first_expected ? expected_first_escape(ms, w, wo_local, h) : ms.escape(wo_local, h);
    if constexpr (TwoSided<M>) return ms.escape(-wo_local, ms.other_side(h));
    else return 0.0;
}
}  // namespace detail

}  // namespace smithlab::walk
