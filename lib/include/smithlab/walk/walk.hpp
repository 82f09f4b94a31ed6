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

#include "smithlab/named.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"
#include "smithlab/walk/position_free.hpp"
#include "smithlab/walk/steps.hpp"

namespace smithlab::walk {

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
///   position_free   no heights: the depth of every hit integrated out in closed form given the directions
///                   (position_free.hpp), under Smith's downward convention, from the end reciprocal picks;
///                   elsewhere (or on a microsurface that is not DepthWalkable) expected_first.
enum class EvalEstimator { next_event, expected_first, reciprocal, position_free };
/// The estimators by name, as front ends spell them (named.hpp).
inline constexpr std::array<Named<EvalEstimator>, 4> eval_estimator_names = {{
    {EvalEstimator::next_event, "next_event", "the escape chance at the height reached"},
    {EvalEstimator::expected_first, "expected_first", "the first hit's height averaged in closed form"},
    {EvalEstimator::reciprocal, "reciprocal", "expected_first, traced from the more grazing direction"},
    {EvalEstimator::position_free, "position_free", "every hit's depth integrated out; reciprocal's direction"},
}};
/// The estimator's name as front ends spell it: "next_event", "expected_first", "reciprocal", "position_free".
inline const char* name(EvalEstimator e) { return eval_estimator_names[static_cast<int>(e)].name.data(); }
inline constexpr double reciprocal_cos = 0.64278760968653933;  ///< cos 50 degrees

namespace detail {
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
    const bool smith = ms.options().downward == Downward::smith;
    if (estimator == EvalEstimator::reciprocal || estimator == EvalEstimator::position_free) {
        bool position_free = estimator == EvalEstimator::position_free && smith;
        if constexpr (!DepthWalkable<Microsurface>) position_free = false;  // a stand-in microsurface (tests)
        // From a to b: position-free, or expected_first.
        const auto from = [&](const Vec3& a, const Vec3& b) {
            if constexpr (DepthWalkable<Microsurface>) {
                if (position_free) return detail::eval_walk_position_free(ms, material, a, b, g, limits);
            }
            return detail::eval_walk_by(ms, material, a, b, g, limits, EvalEstimator::expected_first);
        };
        if constexpr (Reciprocal<M>) {
            if (wo.z() > 0.0 && wo.z() < wi.z() && wo.z() < reciprocal_cos && smith) {
                EvalSample s = from(wo, wi);
                detail::scale(s, wo.z() / wi.z());
                return s;
            }
        }
        return from(wi, wo);
    }
    return detail::eval_walk_by(ms, material, wi, wo, g, limits, estimator);
}

}  // namespace smithlab::walk
