// Where the path tracer's types are erased, once per cell: the NDF picks the concrete microsurface type, the
// material its facet type, and the cell's walks run on those (no virtual call per bounce).
#pragma once

#include <string>
#include <variant>

#include "smithlab/any_ndf.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"

namespace smithlab::trace {

// f(concrete microsurface) for the NDF: the built-in families by their own types, anything else registered
// through AnyNdf (its D and Lambda then cost a virtual call each).
template <class F>
auto with_microsurface(const AnyNdf& ndf, const walk::MicrosurfaceOptions& opts, F&& f) {
    const std::string& family = ndf.family();
    if (family == "ggx") return f(walk::Microsurface(ggx(ndf.param("alpha")), opts));
    if (family == "beckmann") return f(walk::Microsurface(beckmann(ndf.param("alpha")), opts));
    if (family == "blinn") return f(walk::Microsurface(blinn(ndf.param("n")), opts));
    if (family == "gtr") return f(walk::Microsurface(gtr(ndf.param("alpha"), ndf.param("gamma")), opts));
    return f(walk::Microsurface(ndf, opts));
}

// f(microsurface, facets) for the pair.
template <class F>
auto with_walk_types(const AnyNdf& ndf, const walk::Material& material, const walk::MicrosurfaceOptions& opts, F&& f) {
    return with_microsurface(ndf, opts, [&](const auto& ms) {
        return std::visit([&](const auto& m) { return f(ms, m); }, material);
    });
}

// The walk's options as the flags and scene files name them: the downward Lambda, "smith" (-1 - Lambda) or
// "hammon" (-Lambda); the hit normal, "visible" (visible normals of -T) or "hammon" (Hammon's D cos facing T).
inline walk::MicrosurfaceOptions parse_walk_options(const std::string& downward, const std::string& hit_normal,
                                                    const std::string& where) {
    walk::MicrosurfaceOptions o;
    if (downward == "hammon") o.downward = Downward::hammon_symmetric;
    else if (downward != "smith") throw input_error(where + "downward must be smith or hammon, got '" + downward + "'");
    if (hit_normal == "hammon") o.hit_normal = walk::HitNormal::hammon_dcos;
    else if (hit_normal != "visible")
        throw input_error(where + "hit-normal must be visible or hammon, got '" + hit_normal + "'");
    return o;
}

}  // namespace smithlab::trace
