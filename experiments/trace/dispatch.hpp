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
#include "walk_options.hpp"  // parse_walk_options

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
    if (family == "student") return f(walk::Microsurface(student(ndf.param("alpha"), ndf.param("gamma")), opts));
    return f(walk::Microsurface(ndf, opts));
}

// f(microsurface, facets) for the pair.
template <class F>
auto with_walk_types(const AnyNdf& ndf, const walk::Material& material, const walk::MicrosurfaceOptions& opts, F&& f) {
    return with_microsurface(ndf, opts, [&](const auto& ms) {
        return std::visit([&](const auto& m) { return f(ms, m); }, material);
    });
}

}  // namespace smithlab::trace
