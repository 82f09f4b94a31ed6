// An NDF family swept over alpha, as the fit's and the tables' [[ndf]] entries give it (scene_ndf.hpp): a registered
// family at fixed values of its other parameters, one per point of the entry's axes, made at each alpha of the
// scene's own axis (registry.hpp, make_at_alpha).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "scene/scene_ndf.hpp"
#include "scene/strict_table.hpp"
#include "smithlab/any_ndf.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::scene {

struct AlphaFamily {
    NdfEntry entry;     // the [[ndf]] it comes from
    ParamPoint params;  // its parameters but the roughness: one family per point of the entry's axes
    const std::string& family() const { return entry.family; }
};

// The family as text: "ggx", "gtr(gamma=1.5)", "tabulated(file=ndf.csv)" (its parameters but alpha).
std::string family_label(const AlphaFamily& f);

// The NDF of a family at one alpha (alpha itself, or the parameter its registered roughness sets from alpha).
AnyNdf make_ndf(const NdfRegistry& registry, const AlphaFamily& family, double alpha);

// The scene's [[ndf]] tables, each expanded over its axes, in order. An entry whose family takes no alpha, or that
// gives its own roughness, is refused naming it, the message ending in `sweep` ("the fit sweeps alpha over
// training.alpha"); check(entry, n), when given, may refuse the entry that brings the families to n (a scene too
// large); no [[ndf]] at all is refused naming "ndf".
std::vector<AlphaFamily> read_alpha_families(StrictTable& doc, const NdfRegistry& registry, const std::string& sweep,
                                             const std::function<void(const StrictTable&, double)>& check = {});

}  // namespace smithlab::scene
