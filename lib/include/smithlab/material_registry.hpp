/// @file
/// smithlab/material_registry.hpp -- the facet materials by name: what turns a spec such as "conductor(eta=0.2, k=3)"
/// into a walk::Material, and what front ends list (`smithlab list`, `--help`, Python's materials()).
///
/// A material is a type with the members facets.hpp describes, its registration (`static MaterialInfo info()`,
/// `static M make(const MaterialParams&)`) and its spec (`NdfSpec spec() const`); registering it is one line,
///     registry.materials().add<TintedMirror>();
/// and every command then reads it by name. Its walks are compiled there for each NDF type of the list given
/// (default: core_ndf_types; smithlab/gtr/registry.hpp's builtin_ndf_types adds GTR's), and for any other NDF on the
/// NDF erased (material_kernels.hpp).
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "smithlab/material_kernels.hpp"
#include "smithlab/ndf_types.hpp"
#include "smithlab/walk/material.hpp"
#include "smithlab/walk/material_info.hpp"

namespace smithlab {

/// The facet materials by name: each one's MaterialInfo (parameters, ranges, description) and the factory that
/// makes it from a spec's parameters, in registration order.
class MaterialRegistry {
public:
    /// Makes a material from its parsed, range-checked parameters.
    using Factory = std::function<walk::Material(const walk::MaterialParams&)>;

    /// The built-in materials: mirror, conductor, lambert, fresnel-diffuse, dielectric.
    MaterialRegistry();

    /// Register the material type M (M::info(), M::make), its walks compiled here for the NDF types of Ndfs.
    template <class M, class Ndfs = core_ndf_types>
    void add(Ndfs ndfs = {}) {
        walk::MaterialInfo info = M::info();
        info.transmits = walk::TwoSided<M>;
        add_erased(std::move(info), [ndfs](const walk::MaterialParams& p) { return make_material(M::make(p), ndfs); });
    }

    /// The material a spec names; input_error naming an unknown material (with the known ones), an unknown or
    /// missing parameter, or a value out of its range.
    walk::Material make(std::string_view spec) const;
    /// The material named `name`, or nullptr.
    const walk::MaterialInfo* find(std::string_view name) const;
    std::vector<const walk::MaterialInfo*> list() const;  ///< in registration order

private:
    void add_erased(walk::MaterialInfo info, Factory make);
    std::vector<std::pair<walk::MaterialInfo, Factory>> entries_;
};

}  // namespace smithlab
