// smithlab/gtr/registry.hpp -- registering GTR, and the registry of every built-in NDF.
#pragma once

#include "smithlab/registry.hpp"

namespace smithlab {

// gtr(alpha, gamma).
void register_gtr_ndfs(NdfRegistry& registry);

// ggx, beckmann, blinn, gtr: what the CLI and the tests start from.
NdfRegistry builtin_registry();

}  // namespace smithlab
