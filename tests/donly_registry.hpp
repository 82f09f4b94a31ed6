// The built-in NDFs and GGX as D alone ("donly_ggx"): no slope form, no sampler, no Lambda; everything is derived
// (tabulated) for it. The tests of the samplers and the walk's routes run both.
#pragma once

#include <smithlab/gtr.hpp>

inline smithlab::NdfRegistry registry_with_donly() {
    smithlab::NdfRegistry r = smithlab::builtin_registry();
    r.add({"donly_ggx", {"alpha"}, "GGX as D alone", {"donly_ggx(alpha=0.3)"}},
          [](const smithlab::NdfParams& p) { return smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(p.at("alpha"))}; });
    return r;
}
