/// @file
/// smithlab/walk/position_free.hpp -- the position-free eval estimator: a walk over directions only, the depth of each
/// hit integrated out in closed form (depth_law.hpp), for any NDF (only its Lambda and visible normals are read).
///
/// The walk draws what the height walk draws at a hit -- a visible normal of the direction it travels, the material's
/// scattering there -- and no height: the law of the hit's depth given the directions so far (DepthLaw, a sum of
/// exponentials) is carried instead. Its next-event term at hit k toward wo is the path's weight, times the phase
/// toward wo (estimated at the hit normal itself, as expected_first does), times the chance of being at hit k and
/// escaping toward wo from there, int p_k(t) e^{-Lambda(wo) t} dt (depth_law.hpp, eq. 5; eq. 6 toward the other side
/// of a two-sided material). Averaged over the directions, which the height walk draws from the same laws and
/// independently of the heights (the Smith microsurface's normals are independent of height), that is the height walk's
/// expectation term by term: the estimate is unbiased, order by order (Bitterli and d'Eon 2022, "A Position-Free Path
/// Integral for Homogeneous Slabs and Multiple Scattering on Smith Microfacets", CGF 41(4), sec. 5-6; Wang, Jin and Yan
/// 2022, "Position-free Multiple-bounce Computations for Smith Microfacet BSDFs", ACM TOG 41(4), sec. 4).
///
/// The walk has no escape of its own: it goes on while the chance to reach the next hit times its weight, q, is at
/// least `roulette`; below, a Russian roulette keeps it with probability q / roulette and multiplies the law by
/// roulette / q (unbiased). Where the law cannot be carried on -- a transmission into the other side (C1 becomes
/// 1 - C1 there, which a sum of exponentials in t does not follow), a downward step that DepthLaw::down refuses -- the
/// walk draws the hit's depth from the law, multiplies its weight by the law's mass, and goes on as the height walk
/// (walk.hpp's eval_walk_by). So every material runs it, with the dielectric position-free until it first transmits.
/// Smith's downward convention only (depth_law.hpp's steps are its; walk.hpp falls back to expected_first otherwise).
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>

#include "smithlab/walk/depth_law.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"
#include "smithlab/walk/steps.hpp"

namespace smithlab::walk {

/// The chance to reach the next hit times the weight below which the position-free walk plays Russian roulette.
inline constexpr double position_free_roulette = 0.4;

/// A microsurface the position-free walk runs on: Lambda of a direction and the height at a depth, besides what every
/// walk reads (walk::Microsurface has them).
template <class Microsurface>
concept DepthWalkable = requires(const Microsurface& ms, const Vec3& w) {
    { ms.Lambda(w) } -> std::convertible_to<double>;
    { ms.height_at_depth(0.0) } -> std::convertible_to<double>;
};

namespace detail {

/// The position-free walk's next-event escape chance at a hit whose depth is the law `law`, toward wo_local (up: this
/// side; down: the other side of a two-sided material), of Lambda L_o.
template <class M>
double escape_by_law(const DepthLaw& law, const Vec3& wo_local, double L_o) {
    if (wo_local.z() > 0.0) return law.escape(L_o);
    if constexpr (TwoSided<M>) return law.escape_other_side(L_o);
    else return 0.0;
}

/// The law's step along w, up or down (depth_law.hpp, eqs. 2-3); false where DepthLaw::down refuses it.
template <class Microsurface>
bool step_law(const Microsurface& ms, DepthLaw& law, const Vec3& w) {
    if (!(w.z() > 0.0)) return law.down(-ms.Lambda(w));
    law.up(ms.Lambda(w));
    return true;
}

/// eval_walk by the position-free estimator (the file comment). Smith's downward convention, visible hit normals.
template <class Microsurface, class M, class G>
EvalSample eval_walk_position_free(const Microsurface& ms, const M& material, const Vec3& wi, const Vec3& wo, G& g,
                                   const WalkLimits& limits, double roulette = position_free_roulette) {
    EvalSample out;
    if (ms.options().hit_normal != HitNormal::visible) {
        out.capped = true;
        return out;
    }
    bool above = !TwoSided<M> || wi.z() > 0.0;
    Vec3 w = above ? -wi : wi;
    const double L_o = ms.Lambda(wo.z() > 0.0 ? wo : Vec3(-wo));  // Lambda(|mu_o|), on either side
    DepthLaw law(-ms.Lambda(w));
    bool by_law = true;  // the depth is `law`; else the height walk's h
    double h = INFINITY, weight = 1.0;
    int diffuse = 0;
    // The height walk from here on: the hit's depth drawn from the law, its chance carried in the weight.
    auto leave_law = [&] {
        weight *= law.mass();
        h = ms.height_at_depth(law.sample(g));
        by_law = false;
    };
    for (std::int64_t order = 1;; ++order) {
        if (!by_law && !ms.next_height(w, h, 1.0 - uniform01(g))) break;
        if (limits.max_order > 0 && order > limits.max_order) break;
        if (order > limits.max_events) {
            out.capped = true;
            break;
        }
        ++out.events;
        const Vec3 v = -w, wo_local = above ? wo : -wo;
        const Vec3 m = ms.hit_normal(v, g);
        if (std::isnan(m.z())) {
            out.capped = true;
            break;
        }
        const double e =
            by_law ? escape_by_law<M>(law, wo_local, L_o) : next_event_escape<M>(ms, false, w, wo_local, h);
        if (e > 0.0) {
            add_next_event(out, order, diffuse, weight * e,
                           phase(DrawnNormal<Microsurface>{ms, m}, material, v, wo_local, g, above));
        }
        const Scatter s = scatter(material, v, m, g, above);
        weight *= s.weight;
        diffuse += s.diffuse;
        if (weight == 0.0) break;
        w = s.wo;
        if (s.transmitted) {
            if (by_law) leave_law();
            w = -w;
            h = ms.other_side(h);
            above = !above;
        }
        if (!by_law) continue;
        if (!step_law(ms, law, w)) leave_law();
        if (!by_law) continue;
        if (const double q = weight * law.mass(); q < roulette) {
            if (!(uniform01(g) * roulette < q)) break;
            law.scale(roulette / q);
        }
    }
    return out;
}

}  // namespace detail

}  // namespace smithlab::walk
