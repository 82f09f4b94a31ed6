/// @file
/// smithlab/material_kernels.hpp -- the walks of a registered facet material, compiled for its concrete type where it
/// is registered (material_registry.hpp), so that its hot loop has no virtual call per bounce.
///
/// A surface (surface.hpp) hands a registered material its microsurface once per block of walks. MaterialKernelsOf<M,
/// NdfTypes<Ns...>> holds the walk templates instantiated for M on walk::Microsurface<N> for each N listed, and on
/// Microsurface<AnyNdf> (the NDF erased: a virtual D and Lambda each) for an NDF of any other type; it finds which by
/// the surface's NDF type, once per block.
#pragma once

#include <memory>
#include <optional>
#include <typeinfo>
#include <utility>

#include "smithlab/abc.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/ndf_types.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/student_t.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/tabulated.hpp"
#include "smithlab/walk/material.hpp"
#include "smithlab/walk/trace.hpp"

namespace smithlab {

template <class M, class Ndfs>
class MaterialKernelsOf;

/// The walks of material type M, instantiated on walk::Microsurface`<`N`>` for each N of Ns and on
/// Microsurface`<`AnyNdf`>` for any other NDF: the surface's NDF type picks one, once per call.
template <class M, class... Ns>
class MaterialKernelsOf<M, NdfTypes<Ns...>> final : public MaterialKernels {
public:
    /// Holds `material` by value for the walks.
    explicit MaterialKernelsOf(M material) : m_(std::move(material)) {}

    /// The operations of MaterialKernels (surface.hpp), run with this material on `s`'s microsurface.
    ///@{
    walk::CellPartial trace_block(const AnySurface& s, const walk::CellRequest& r, std::uint64_t b) const override {
        return on_microsurface(s, [&](const auto& ms) { return walk::trace_block(ms, m_, r, b); });
    }
    walk::EvalTally eval_cell(const AnySurface& s, const walk::EvalRequest& r) const override {
        return on_microsurface(s, [&](const auto& ms) { return walk::eval_cell(ms, m_, r); });
    }
    fit::SplitMoments eval_point(const AnySurface& s, const Vec3& wi, const Vec3& wo, std::uint64_t seed,
                                 std::uint64_t stream, std::int64_t walks, walk::EvalEstimator e) const override {
        return on_microsurface(
            s, [&](const auto& ms) { return fit::trace_eval_point(ms, m_, wi, wo, seed, stream, walks, e); });
    }
    fit::SplitMoments albedo_point(const AnySurface& s, const Vec3& wi, std::uint64_t seed, std::uint64_t stream,
                                   std::int64_t walks) const override {
        return on_microsurface(
            s, [&](const auto& ms) { return fit::trace_albedo_point(ms, m_, wi, seed, stream, walks); });
    }
    bool dirac_at(const Vec3& wi, const Vec3& wo) const override { return walk::material_dirac_at(m_, wi, wo); }
    ///@}

private:
    /// f on the surface's microsurface of its concrete NDF type where that is listed, else on the erased one.
    template <class F>
    auto on_microsurface(const AnySurface& s, F f) const {
        using R = decltype(f(s.erased_microsurface()));
        std::optional<R> out;
        const std::type_info& type = s.ndf_type();
        ((!out && type == typeid(Ns) &&
          (out.emplace(f(*static_cast<const walk::Microsurface<Ns>*>(s.microsurface()))), true)),
         ...);
        if (out) return std::move(*out);
        return f(s.erased_microsurface());
    }

    M m_;
};

/// A material of type M as a walk::Material: a built-in one as itself, any other with its walks compiled here for
/// the NDF types listed (and for any NDF, erased).
template <class M, class Ndfs = core_ndf_types>
walk::Material make_material(M m, Ndfs = {}) {
    if constexpr (walk::builtin_material<M>) {
        return walk::Material(std::move(m));
    } else {
        std::string spec = walk::material_spec_text(m.spec());
        const bool diffuse = walk::material_has_diffuse(m);
        return walk::Material(
            walk::RegisteredMaterial{std::make_shared<const MaterialKernelsOf<M, Ndfs>>(std::move(m))}, std::move(spec),
            diffuse, walk::TwoSided<M>);
    }
}

}  // namespace smithlab
