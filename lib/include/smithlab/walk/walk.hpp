/// @file
/// smithlab/walk/walk.hpp -- the random walk on the Smith microsurface, and its two estimators (Heitz, Hanika, d'Eon,
/// Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the Smith Model", sec. 4-5, alg. 1-3; Hammon 2017,
/// appendix, "Solution - Path Tracing"):
///   sample_walk(wi)    one walk from wi: the direction it leaves in, the weight it carries, its scattering order;
///                      the weighted density of the exit direction is f(wi, wo) |cos theta_o|.
///   eval_walk(wi, wo)  one walk from wi with next-event estimation toward wo at every hit: an unbiased estimate of
///                      f(wi, wo) |cos theta_o|, split by scattering order and component, by one of two estimators
///                      (EvalEstimator).
/// Templated on the concrete NDF (through Microsurface), the height law, the facet material and the generator: no
/// virtual call, std::function, allocation, exception or string inside. wi and wo point away from the surface.
///
/// Both sides (Heitz et al. 2016, sec. 6.2): a ray that a two-sided material (facets.hpp, the dielectric) lets through
/// travels on below the microsurface, where the walk works in the negated frame -- every direction and height of the
/// side below negated, in which the microsurface looks exactly as from above (its normals keep their law D, the
/// heights' law is symmetric) -- so the same height steps, escape test and visible normals serve both sides; only the
/// material is told the side (its relative index). Light may come from below (wi.z < 0) for a two-sided material;
/// for the others wi.z > 0.
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

/// One walk of sample_walk: where it left, what it carries, and how it ended.
struct WalkSample {
    Vec3 wo;             ///< the exit direction, when escaped
    double weight;       ///< what it carries out (0 when absorbed, truncated or capped)
    int order;           ///< hits before it left
    int diffuse_events;  ///< diffuse events on the way
    bool escaped;        ///< it left the surface (else absorbed, truncated at max_order, or capped)
    bool capped;         ///< it ended at max_events hits, or where no visible normal could be drawn
    bool diffuse() const { return diffuse_events > 0; }  ///< whether any event on the way was diffuse
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
}  // namespace detail

/// One walk from wi on `ms` with `material` (Heitz et al. 2016, alg. 1-2): the weighted density of the exit direction
/// is f(wi, wo) `|`cos theta_o`|`; wi.z `<` 0 (light from below) only for a two-sided material.
template <class Microsurface, class M, class G>
WalkSample sample_walk(const Microsurface& ms, const M& material, const Vec3& wi, G& g, const WalkLimits& limits = {}) {
    bool above = !TwoSided<M> || wi.z() > 0.0;
    Vec3 w = above ? -wi : wi;  // the travel direction in the frame of the ray's side
    double h = INFINITY, weight = 1.0;
    int diffuse = 0;
    for (std::int64_t order = 0;; ++order) {
        const Vec3 world = above ? w : -w;
        if (!ms.next_height(w, h, 1.0 - uniform01(g)))
            return {world, weight, static_cast<int>(order), diffuse, true, false};
        if (order + 1 > limits.max_events) return {world, 0.0, static_cast<int>(order), diffuse, false, true};
        if (limits.max_order > 0 && order + 1 > limits.max_order)
            return {world, 0.0, static_cast<int>(order), diffuse, false, false};
        const Vec3 v = -w;
        const Vec3 m = ms.hit_normal(v, g);
        if (std::isnan(m.z())) return {world, 0.0, static_cast<int>(order), diffuse, false, true};  // none drawn
        const Scatter s = detail::scatter(material, v, m, g, above);
        weight *= s.weight;
        diffuse += s.diffuse;
        if (weight == 0.0) return {world, 0.0, static_cast<int>(order + 1), diffuse, false, false};
        w = s.wo;
        if (s.transmitted) {
            w = -w;
            h = ms.other_side(h);
            above = !above;
        }
    }
}

/// The eval estimators. Both add, at every hit, the walk's weight times the chance to escape toward wo from there times
/// the phase function toward wo (a one-sample estimate over a visible normal where the facet is diffuse):
///   next_event      the escape chance at the height the walk reached, the phase's visible normal drawn for it alone
///                   (Heitz et al. 2016, alg. 3);
///   expected_first  at the first hit, the escape chance averaged over that hit's height in closed form: a ray from
///                   above along -wi first meets the surface where C1 = S^(1/a), a = -Lambda(-wi) (microsurface.hpp,
///                   the downward convention), so C1 has the density a C1^(a - 1) and E[C1^Lambda(wo)] =
///                   a / (a + Lambda(wo)) -- with Smith's convention (1 + Lambda(wi)) / (1 + Lambda(wi) + Lambda(wo)),
///                   the height-correlated G2 over G1(wi) (Heitz 2014, "Understanding the Masking-Shadowing Function
///                   in Microfacet-Based BRDFs"); and at every hit the phase's diffuse part estimated at the hit normal
///                   itself, a visible normal of the same direction (no second draw). Each term keeps its expectation
///                   (the height's average is a conditional expectation; the shared normal has the law the phase
///                   integrates over), so the sum stays unbiased; only the terms' correlation changes. Toward wo on the
///                   other side of a two-sided material the first hit's escape chance stays sampled.
///   reciprocal      expected_first, traced from wo toward wi where wo is the more grazing of the two and beyond
///                   50 degrees (cos theta_o < reciprocal_cos): for a reciprocal material (facets.hpp, Reciprocal)
///                   under Smith's downward convention f(wi, wo) = f(wo, wi), so f(wi, wo) |cos theta_o| =
///                   f(wo, wi) |cos theta_i| x cos theta_o / cos theta_i, order by order and diffuse event by diffuse
///                   event (a path reversed keeps both). The escape chance and the diffuse phase toward a direction
///                   near the horizon are what vary most from walk to walk. Toward a direction near the normal every
///                   hit escapes alike, so long walks weigh more: bench_fit has GTR gamma 1 at (0, 40, 0) 1.4x slower
///                   to a given error traced from 40 degrees, hence the threshold. Elsewhere (wo below, not grazing
///                   enough, another material or convention) it is expected_first.
/// reciprocal is the fitter's: its equal-error time (ns a walk x variance) is the lowest at every point bench_fit
/// measures.
enum class EvalEstimator { next_event, expected_first, reciprocal };
/// The estimator's name as front ends spell it: "next_event", "expected_first", "reciprocal".
inline const char* name(EvalEstimator e) {
    return e == EvalEstimator::next_event    ? "next_event"
        : e == EvalEstimator::expected_first ? "expected_first"
                                             : "reciprocal";
}
inline constexpr double reciprocal_cos = 0.64278760968653933;  ///< cos 50 degrees

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
}  // namespace detail

namespace detail {

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

/// eval_walk by next_event or expected_first (shared).
template <class Microsurface, class M, class G>
EvalSample eval_walk_by(const Microsurface& ms, const M& material, const Vec3& wi, const Vec3& wo, G& g,
                        const WalkLimits& limits, EvalEstimator estimator) {
    EvalSample out;
    // The phase functions are densities over visible normals: a microsurface whose hits draw another law
    // (require_eval_normals, which the caller runs before any walk) gives no estimate, every walk capped.
    if (ms.options().hit_normal != HitNormal::visible) {
        out.capped = true;
        return out;
    }
    bool above = !TwoSided<M> || wi.z() > 0.0;
    Vec3 w = above ? -wi : wi;
    double h = INFINITY, weight = 1.0;
    int diffuse = 0;  // diffuse events so far
    for (std::int64_t order = 1;; ++order) {
        if (!ms.next_height(w, h, 1.0 - uniform01(g))) break;
        if (limits.max_order > 0 && order > limits.max_order) break;
        if (order > limits.max_events) {
            out.capped = true;
            break;
        }
        ++out.events;
        const Vec3 v = -w;
        const bool shared = estimator == EvalEstimator::expected_first;
        // expected_first: the hit normal first, the phase estimated at it.
        const Vec3 m_shared = shared ? ms.hit_normal(v, g) : Vec3();
        if (shared && std::isnan(m_shared.z())) {
            out.capped = true;
            break;
        }
        // Next-event estimation: the phase function toward wo times the chance to escape along it from here.
        const Vec3 wo_local = above ? wo : -wo;
        if (const double e = next_event_escape<M>(ms, shared && order == 1, w, wo_local, h); e > 0.0) {
            const Phase p = shared ? phase(DrawnNormal<Microsurface>{ms, m_shared}, material, v, wo_local, g, above)
                                   : phase(ms, material, v, wo_local, g, above);
            add_next_event(out, order, diffuse, weight * e, p);
        }
        const Vec3 m = shared ? m_shared : ms.hit_normal(v, g);
        if (std::isnan(m.z())) {
            out.capped = true;
            break;
        }
        const Scatter s = scatter(material, v, m, g, above);
        weight *= s.weight;
        diffuse += s.diffuse;
        if (weight == 0.0) break;
        w = s.wo;
        if (s.transmitted) {
            w = -w;
            h = ms.other_side(h);
            above = !above;
        }
    }
    return out;
}

}  // namespace detail

/// One walk from wi with next-event estimation toward wo at every hit (Heitz et al. 2016, alg. 3; `estimator`: which
/// of the EvalEstimator variants): an unbiased estimate of f(wi, wo) `|`cos theta_o`|`.
template <class Microsurface, class M, class G>
EvalSample eval_walk(const Microsurface& ms, const M& material, const Vec3& wi, const Vec3& wo, G& g,
                     const WalkLimits& limits = {}, EvalEstimator estimator = EvalEstimator::next_event) {
    if (estimator == EvalEstimator::reciprocal) {
        if constexpr (Reciprocal<M>) {
            if (wo.z() > 0.0 && wo.z() < wi.z() && wo.z() < reciprocal_cos &&
                ms.options().downward == Downward::smith) {
                EvalSample s = detail::eval_walk_by(ms, material, wo, wi, g, limits, EvalEstimator::expected_first);
                detail::scale(s, wo.z() / wi.z());
                return s;
            }
        }
        estimator = EvalEstimator::expected_first;
    }
    return detail::eval_walk_by(ms, material, wi, wo, g, limits, estimator);
}

}  // namespace smithlab::walk
