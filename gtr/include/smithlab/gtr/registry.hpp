/// @file
/// smithlab/gtr/registry.hpp -- registering GTR, and the registry of every built-in NDF.
#pragma once

#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab {

/// gtr(alpha, gamma).
void register_gtr_ndfs(NdfRegistry& registry);

/// ggx, beckmann, blinn, gtr: what the CLI and the tests start from.
NdfRegistry builtin_registry();

/// dimov-spline and the interp-* variants across gamma (interpolants.hpp).
void register_gtr_variants(VariantRegistry& registry);

/// Every built-in Lambda variant: the core ones and the GTR ones.
VariantRegistry builtin_variants();

}  // namespace smithlab
