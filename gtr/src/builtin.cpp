#include "smithlab/gtr/gtr.hpp"
#include "smithlab/gtr/registry.hpp"

namespace smithlab {

void register_gtr_ndfs(NdfRegistry& r) {
    r.add({"gtr",
           {"alpha", "gamma"},
           "Generalized Trowbridge-Reitz (Burley 2012), any real gamma >= 0; closed-form Lambda at gamma = 0..4",
           {"gtr(alpha=1e-4, gamma=0.5)", "gtr(alpha=0.3, gamma=1)", "gtr(alpha=0.3, gamma=1.000000001)",
            "gtr(alpha=0.999999, gamma=1)", "gtr(alpha=1, gamma=3)", "gtr(alpha=0.2, gamma=0)",
            "gtr(alpha=0.5, gamma=2.5)", "gtr(alpha=0.05, gamma=4)", "gtr(alpha=0.05, gamma=10)"}},
          [](const NdfParams& p) { return gtr(p.at("alpha"), p.at("gamma")); });
}

NdfRegistry builtin_registry() {
    NdfRegistry r;
    register_core_ndfs(r);
    register_gtr_ndfs(r);
    return r;
}

}  // namespace smithlab
