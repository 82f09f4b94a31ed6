/// @file
/// smithlab/gtr/registry.hpp -- registering GTR, and the registry of every built-in NDF.
#pragma once

#include "smithlab/gtr/gtr.hpp"
#include "smithlab/ndf_types.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/variants.hpp"

namespace smithlab {

/// gtr(alpha, gamma).
void register_gtr_ndfs(NdfRegistry& registry);

/// The types every built-in NDF factory returns: a registered material lists them to walk each as its own type
/// (material_registry.hpp), e.g. registry.materials().add<TintedMirror>(builtin_ndf_types{}).
using builtin_ndf_types = decltype(core_ndf_types{} + NdfTypes<Gtr>{});

/// ggx, beckmann, blinn, gtr: what the CLI and the tests start from.
NdfRegistry builtin_registry();

/// dimov-spline and the interp-* variants across gamma (interpolants.hpp).
void register_gtr_variants(VariantRegistry& registry);

/// Every built-in Lambda variant: the core ones and the GTR ones.
VariantRegistry builtin_variants();

}  // namespace smithlab
