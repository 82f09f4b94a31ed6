// The walk's options by name, as trace's flags (--downward, --hit-normal) and scene files ([walks] downward,
// hit_normal) give them: one table per choice (smithlab/named.hpp), read by the parser, the scene reader and the help.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "smithlab/errors.hpp"
#include "smithlab/named.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/walk/microsurface.hpp"

namespace smithlab::scene {

// The hit normals by name (walk::HitNormal, microsurface.hpp). The downward Lambda's are smith.hpp's downward_names.
inline constexpr std::array<Named<walk::HitNormal>, 2> hit_normal_names = {{
    {walk::HitNormal::visible, "visible", "visible normals of -T"},
    {walk::HitNormal::hammon_dcos, "hammon", "D cos restricted to T.m < 0"},
}};

// The names of a table, quoted: "smith" or "hammon".
template <class E, std::size_t N>
std::string quoted_names(const std::array<Named<E>, N>& table) {
    std::string out = "\"";
    out += join_names(table, "\", \"", "\" or \"");
    out += '"';
    return out;
}

// The walk's options from their names: the downward Lambda (downward_names: smith, -1 - Lambda; hammon, -Lambda) and
// the hit normal (hit_normal_names); input_error "WHERE" + "downward must be smith or hammon, got '...'" otherwise.
inline walk::MicrosurfaceOptions parse_walk_options(const std::string& downward, const std::string& hit_normal,
                                                    const std::string& where) {
    walk::MicrosurfaceOptions o;
    const Named<Downward>* d = find_named(downward_names, downward);
    if (!d)
        throw input_error(where + "downward must be " + join_names(downward_names, ", ", " or ") + ", got '" +
                          downward + "'");
    o.downward = d->value;
    const Named<walk::HitNormal>* h = find_named(hit_normal_names, hit_normal);
    if (!h)
        throw input_error(where + "hit-normal must be " + join_names(hit_normal_names, ", ", " or ") + ", got '" +
                          hit_normal + "'");
    o.hit_normal = h->value;
    return o;
}

}  // namespace smithlab::scene
