// smithlab/walk/walk.hpp -- the random walk on the Smith microsurface, and its two estimators (Heitz, Hanika, d'Eon,
// Dachsbacher 2016, "Multiple-Scattering Microfacet BSDFs with the Smith Model", sec. 4-5, alg. 1-3; Hammon 2017,
// appendix, "Solution - Path Tracing"):
//   sample_walk(wi)    one walk from wi: the direction it leaves in, the weight it carries, its scattering order;
//                      the weighted density of the exit direction is f(wi, wo) |cos theta_o|.
//   eval_walk(wi, wo)  one walk from wi with next-event estimation toward wo at every hit: an unbiased estimate of
//                      f(wi, wo) |cos theta_o|, split by scattering order and component.
// Templated on the concrete NDF (through Microsurface), the height law, the facet material and the generator: no
// virtual call, std::function, allocation, exception or string inside. wi and wo point away from the surface.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"

namespace smithlab::walk {

// Tallies by scattering order: 1, 2, 3, 4+.
inline constexpr int order_bins = 4;
inline int order_bin(std::int64_t order) { return static_cast<int>(std::min<std::int64_t>(order, order_bins)) - 1; }

struct WalkLimits {
    int max_order = 0;               // > 0: the walk ends after this many hits (the orders beyond are not asked for)
    std::int64_t max_events = 1'000'000;  // a walk still inside after this many hits ends as `capped` (never a hang)
};

struct WalkSample {
    Vec3 wo;           // the exit direction, when escaped
    double weight;     // what it carries out (0 when absorbed, truncated or capped)
    int order;         // hits before it left
    bool diffuse;      // any diffuse event on the way
    bool escaped;
    bool capped;
};

template <class Microsurface, class M, class G>
WalkSample sample_walk(const Microsurface& ms, const M& material, const Vec3& wi, G& g, const WalkLimits& limits = {}) {
    Vec3 w = -wi;
    double h = INFINITY, weight = 1.0;
    bool diffuse = false;
    for (std::int64_t order = 0;; ++order) {
        if (!ms.next_height(w, h, 1.0 - uniform01(g))) return {w, weight, static_cast<int>(order), diffuse, true, false};
        if (order + 1 > limits.max_events) return {w, 0.0, static_cast<int>(order), diffuse, false, true};
        if (limits.max_order > 0 && order + 1 > limits.max_order) return {w, 0.0, static_cast<int>(order), diffuse, false, false};
        const Vec3 v = -w;
        const Scatter s = material.sample(v, ms.visible_normal(v, g), g);
        weight *= s.weight;
        diffuse = diffuse || s.diffuse;
        if (weight == 0.0) return {w, 0.0, static_cast<int>(order + 1), diffuse, false, false};
        w = s.wo;
    }
}

struct EvalSample {
    std::array<double, order_bins> specular{}, diffuse{};  // f |cos theta_o| by order bin and component
    std::int64_t events = 0;
    bool capped = false;
};

template <class Microsurface, class M, class G>
EvalSample eval_walk(const Microsurface& ms, const M& material, const Vec3& wi, const Vec3& wo, G& g,
                     const WalkLimits& limits = {}) {
    EvalSample out;
    Vec3 w = -wi;
    double h = INFINITY, weight = 1.0;
    bool diffuse = false;
    for (std::int64_t order = 1;; ++order) {
        if (!ms.next_height(w, h, 1.0 - uniform01(g))) break;
        if (limits.max_order > 0 && order > limits.max_order) break;
        if (order > limits.max_events) {
            out.capped = true;
            break;
        }
        ++out.events;
        const Vec3 v = -w;
        // Next-event estimation: the phase function toward wo times the chance to escape along it from here.
        const double e = ms.escape(wo, h);
        if (e > 0.0) {
            const Phase p = material.phase(ms, v, wo, g);
            const int b = order_bin(order);
            (diffuse ? out.diffuse : out.specular)[b] += weight * e * p.specular;
            out.diffuse[b] += weight * e * p.diffuse;
        }
        const Scatter s = material.sample(v, ms.visible_normal(v, g), g);
        weight *= s.weight;
        diffuse = diffuse || s.diffuse;
        if (weight == 0.0) break;
        w = s.wo;
    }
    return out;
}

}  // namespace smithlab::walk
