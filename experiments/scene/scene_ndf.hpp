// The [[ndf]] tables of every scene format (report, trace, fit), read by one reader: a registered family and an axis
// for any parameter it declares, e.g.
//     [[ndf]]
//     family = "student"
//     gamma = [1.65, 2, 4]                  # a list, or {log = [lo, hi], n = N}, or {lin = [lo, hi], n = N}
//     alpha = {log = [0.01, 1], n = 5}      # optional where the scene has its own alpha axis
// The entry's points are the cross product of its axes, the family's first declared parameter outermost. A family
// swept over the scene's alpha axis (where the entry gives no axis for alpha, nor for the parameter the family's
// roughness sets: Blinn-Phong's n) gets alpha through the registry's roughness mapping (registry.hpp, make_at_alpha).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/strict_table.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::scene {

using ParamPoint = std::vector<std::pair<std::string, double>>;

struct NdfEntry {
    std::string family;
    std::vector<std::pair<std::string, std::vector<double>>> axes;  // in the family's declared order
    std::vector<std::pair<std::string, std::string>> texts;         // its text parameters (a file's path)
    bool roughness_given = false;  // its own axes make its NDFs: an axis for alpha or for the parameter the family's
                                   // roughness sets, or a family alpha cannot reach (takes_alpha false)
    bool takes_alpha = true;       // the family has a parameter alpha or a roughness mapping
    std::string where;             // "FILE:LINE: ndf.family", for refusals of its points

    // The cross product of the axes (one empty point when there are none), the first axis outermost.
    std::vector<ParamPoint> points() const;
    // The number of NDFs the entry makes over an alpha axis of n points.
    std::size_t count(std::size_t alphas) const;
};

// The keys an [[ndf]] table may hold: family, every parameter (numeric or text) any registered family declares, and
// `extra`.
std::vector<std::string> ndf_table_keys(const NdfRegistry& registry, const std::vector<std::string>& extra = {});

// One [[ndf]] table (opened with ndf_table_keys): its family, which must be registered, an axis per numeric parameter
// key and a string per text parameter, each a parameter of that family (else refused, naming the family's
// parameters). A path in a text parameter is as on the command line (relative to the working directory). Keys in
// `extra` are left to the caller. Does not call t.done().
NdfEntry read_ndf_entry(StrictTable& t, const NdfRegistry& registry);

// The NDF at one point of the entry, at roughness `alpha` unless the entry gives its own: the registry's refusals
// (a value outside the family's domain, a family that cannot take alpha) prefixed with the entry's FILE:LINE.
AnyNdf make_entry_ndf(const NdfEntry& entry, const NdfRegistry& registry, const ParamPoint& point,
                      std::optional<double> alpha);

}  // namespace smithlab::scene
