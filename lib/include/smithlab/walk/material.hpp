/// @file
/// smithlab/walk/material.hpp -- a facet material as a value: one of the built-in materials, or a registered one
/// whose walks were compiled where it was registered (material_kernels.hpp), with its canonical spec and what it does.
///
/// A command holds its materials as Material; the walk takes the concrete type. AnySurface (surface.hpp) visits the
/// built-in alternatives once per block of walks and runs walk/trace.hpp's templates on them directly; a registered
/// material runs its own compiled walks (one virtual call per block, none per bounce).
#pragma once

#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "smithlab/geometry.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/walk/conductor.hpp"
#include "smithlab/walk/dielectric.hpp"
#include "smithlab/walk/fresnel_diffuse.hpp"
#include "smithlab/walk/lambert.hpp"
#include "smithlab/walk/mirror.hpp"

namespace smithlab {
class MaterialKernels;  // surface.hpp
}

namespace smithlab::walk {

/// A material of a type outside the built-in list: its walks, compiled for its concrete type (material_kernels.hpp).
struct RegisteredMaterial {
    std::shared_ptr<const MaterialKernels> kernels;  ///< the material's walks on any surface (never null)
};

/// Whether M is one of the materials every NDF's surface is compiled against (surface.hpp).
template <class M>
inline constexpr bool builtin_material = std::is_same_v<M, Mirror> || std::is_same_v<M, Conductor> ||
    std::is_same_v<M, Lambert> || std::is_same_v<M, FresnelDiffuse> || std::is_same_v<M, Dielectric>;

/// A material's spec as text: "conductor(eta=0.2, k=3)", the bare name where it has no parameters ("mirror").
inline std::string material_spec_text(const NdfSpec& spec) {
    return spec.params.empty() && spec.texts.empty() ? spec.name : format_spec(spec);
}

/// A facet material as a value, with its canonical spec and whether it is diffuse or transmits: a built-in type or
/// a RegisteredMaterial.
class Material {
public:
    /// The material itself: one of the built-in types, or a registered material's kernels.
    using Kind = std::variant<Mirror, Conductor, Lambert, FresnelDiffuse, Dielectric, RegisteredMaterial>;

    /// A built-in material.
    template <class M>
    requires builtin_material<M> Material(M m)
        : spec_(material_spec_text(m.spec())),
          has_diffuse_(material_has_diffuse(m)),
          transmits_(TwoSided<M>),
          kind_(std::move(m)) {}
    /// A registered material: its kernels, its canonical spec, and what it does (material_kernels.hpp fills these in
    /// from its type).
    Material(RegisteredMaterial registered, std::string spec, bool has_diffuse, bool transmits)
        : spec_(std::move(spec)), has_diffuse_(has_diffuse), transmits_(transmits), kind_(std::move(registered)) {}

    /// "conductor(eta=0.2, k=3)": every parameter, in its declared order.
    const std::string& spec() const { return spec_; }
    /// Whether any event of the material is diffuse (the tallies of the diffuse component exist only then).
    bool has_diffuse() const { return has_diffuse_; }
    /// Whether light goes through it (the transmission tallies exist only then): a two-sided material (facets.hpp).
    bool transmits() const { return transmits_; }
    /// Whether the material's BSDF holds a Dirac delta at (wi, wo), where it has no finite density for the eval
    /// estimator to return (an index-matched dielectric at wo = -wi).
    bool dirac_at(const Vec3& wi, const Vec3& wo) const;

    /// The built-in material of type M, or nullptr.
    template <class M>
    const M* get_if() const {
        return std::get_if<M>(&kind_);
    }
    const Kind& kind() const { return kind_; }  ///< the material itself, for std::visit

private:
    std::string spec_;
    bool has_diffuse_, transmits_;
    Kind kind_;
};

/// `builtin(m)` on the concrete type of a built-in material, `registered(kernels)` on a registered material's
/// kernels: the one dispatch over Material::kind() (once per block of walks, never per bounce). Both return the same
/// type.
template <class Builtin, class Registered>
auto visit(const Material& material, Builtin&& builtin, Registered&& registered) {
    return std::visit(
        [&](const auto& m) {
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, RegisteredMaterial>) return registered(*m.kernels);
            else return builtin(m);
        },
        material.kind());
}

}  // namespace smithlab::walk
