#include "smithlab/abc.hpp"

#include "smithlab/registry.hpp"

namespace smithlab {

void register_abc(NdfRegistry& r) {
    r.add(
        {.name = "abc",
         .parameters = {"b", "c"},
         .description = "ABC (Low et al. 2012), D = A / (1 + b (1 - cos))^c, b in [1e-8, 1e16], c in (0, 1e4]: a sharp "
                        "peak on a wide base, fitted to measured BRDFs; Lambda by quadrature",
         .examples = {"abc(b=1e-8, c=1)", "abc(b=20, c=1.5)", "abc(b=400, c=3)", "abc(b=1e8, c=0.3)",
                      "abc(b=2e4, c=50)"},
         .roughness =
             NdfInfo::Roughness{"b",
                                [](double alpha, const NdfParams& p) { return abc_b_from_alpha(alpha, p.at("c")); }}},
        [](const NdfParams& p) { return abc(p.at("b"), p.at("c")); });
}

}  // namespace smithlab
