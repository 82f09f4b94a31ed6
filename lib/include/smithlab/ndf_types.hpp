/// @file
/// smithlab/ndf_types.hpp -- lists of concrete NDF types, for code compiled against each of them: a registered facet
/// material's walks (material_kernels.hpp).
#pragma once

namespace smithlab {

/// A compile-time list of concrete NDF types (no members): a material's walks are instantiated for each.
template <class... Ns>
struct NdfTypes {};

struct Ggx;
struct Beckmann;
struct BlinnPhong;
struct StudentT;
struct Abc;
class TabulatedNdf;

/// The types register_core_ndfs's factories return (registry.hpp); smithlab/gtr/registry.hpp's builtin_ndf_types adds
/// the GTR family's.
using core_ndf_types = NdfTypes<Ggx, Beckmann, BlinnPhong, StudentT, Abc, TabulatedNdf>;

/// The concatenation of two lists, A's types first: core_ndf_types + NdfTypes`<`MyNdf`>`{}.
template <class... A, class... B>
constexpr NdfTypes<A..., B...> operator+(NdfTypes<A...>, NdfTypes<B...>) {
    return {};
}

}  // namespace smithlab
