/// @file
/// smithlab/surface.hpp -- the Smith microsurface of one NDF with the NDF's type erased once: what a command runs on a
/// cell of walks, a block (or a point) at a time.
///
/// A command holds NDFs as AnyNdf (registry.hpp); a walk needs the concrete type, so that D, Lambda and the visible
/// normals are direct calls (walk.hpp). The registry records, for the type its factory returns, how to build
/// SurfaceOf<N> (NdfKernels); make_surface builds one per cell, tables included, and each of its calls is one virtual
/// call for a whole block of walks (4096 by default) or a point: none per bounce. Every operation visits the facet
/// material once (walk/material.hpp): a built-in one runs the templates of walk/trace.hpp and fit/dataset.hpp on
/// Microsurface<N> here; a registered one runs its own instantiations of them (MaterialKernels, compiled where it was
/// registered: material_kernels.hpp) on this surface's concrete microsurface where its registration listed N, else on
/// the NDF erased (Microsurface<AnyNdf>, built on first use).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <typeinfo>
#include <variant>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/walk/material.hpp"
#include "smithlab/walk/microsurface.hpp"
#include "smithlab/walk/trace.hpp"

namespace smithlab {

/// The Smith microsurface of one NDF, its type erased: the walks a command runs on it, one virtual call per block of
/// walks or per point, for any facet material.
class AnySurface {
public:
    virtual ~AnySurface() = default;
    /// Block b of a cell (walk::trace_block): the sample estimator's tallies.
    virtual walk::CellPartial trace_block(const walk::Material& material, const walk::CellRequest& r,
                                          std::uint64_t b) const = 0;
    /// One direction pair by the eval estimator over r.threads (walk::eval_cell).
    virtual walk::EvalTally eval_cell(const walk::Material& material, const walk::EvalRequest& r) const = 0;
    /// The fitter's points, one thread each (fit::trace_eval_point by `estimator`, fit::trace_albedo_point).
    ///@{
    virtual fit::SplitMoments eval_point(const walk::Material& material, const Vec3& wi, const Vec3& wo,
                                         std::uint64_t seed, std::uint64_t stream, std::int64_t walks,
                                         walk::EvalEstimator estimator) const = 0;
    virtual fit::SplitMoments albedo_point(const walk::Material& material, const Vec3& wi, std::uint64_t seed,
                                           std::uint64_t stream, std::int64_t walks) const = 0;
    ///@}

    /// For a registered material's kernels: the NDF's concrete type and its walk::Microsurface of that type, and the
    /// same microsurface with the NDF erased (built on first use; its tables may refuse the NDF, as input_error).
    ///@{
    virtual const std::type_info& ndf_type() const = 0;
    virtual const void* microsurface() const = 0;
    virtual const walk::Microsurface<AnyNdf>& erased_microsurface() const = 0;
    ///@}
};

/// A registered material's walks (walk/material.hpp, RegisteredMaterial): the operations of AnySurface for one
/// concrete material type, on a surface it is given (material_kernels.hpp, MaterialKernelsOf).
class MaterialKernels {
public:
    virtual ~MaterialKernels() = default;
    /// AnySurface's trace_block, eval_cell, eval_point and albedo_point for this material on the surface `s`, and
    /// whether the material's phase has a Dirac delta at (wi, wo) (walk::material_dirac_at).
    ///@{
    virtual walk::CellPartial trace_block(const AnySurface& s, const walk::CellRequest& r, std::uint64_t b) const = 0;
    virtual walk::EvalTally eval_cell(const AnySurface& s, const walk::EvalRequest& r) const = 0;
    virtual fit::SplitMoments eval_point(const AnySurface& s, const Vec3& wi, const Vec3& wo, std::uint64_t seed,
                                         std::uint64_t stream, std::int64_t walks,
                                         walk::EvalEstimator estimator) const = 0;
    virtual fit::SplitMoments albedo_point(const AnySurface& s, const Vec3& wi, std::uint64_t seed,
                                           std::uint64_t stream, std::int64_t walks) const = 0;
    virtual bool dirac_at(const Vec3& wi, const Vec3& wo) const = 0;
    ///@}
};

/// The surface of the concrete NDF type N: walk::Microsurface`<`N`>`, so that D, Lambda and the visible normals are
/// direct calls in the walks.
template <Ndf N>
class SurfaceOf final : public AnySurface {
public:
    /// `self`: the same NDF as an AnyNdf, for the erased microsurface.
    SurfaceOf(const N& ndf, const walk::MicrosurfaceOptions& opts, AnyNdf self)
        : ms_(ndf, opts), self_(std::move(self)) {}

    /// AnySurface's operations: a built-in material's walks on walk::Microsurface`<`N`>`, a registered one's through
    /// its kernels.
    ///@{
    walk::CellPartial trace_block(const walk::Material& material, const walk::CellRequest& r,
                                  std::uint64_t b) const override {
        return walk::visit(
            material, [&](const auto& m) { return walk::trace_block(ms_, m, r, b); },
            [&](const MaterialKernels& k) { return k.trace_block(*this, r, b); });
    }
    walk::EvalTally eval_cell(const walk::Material& material, const walk::EvalRequest& r) const override {
        return walk::visit(
            material, [&](const auto& m) { return walk::eval_cell(ms_, m, r); },
            [&](const MaterialKernels& k) { return k.eval_cell(*this, r); });
    }
    fit::SplitMoments eval_point(const walk::Material& material, const Vec3& wi, const Vec3& wo, std::uint64_t seed,
                                 std::uint64_t stream, std::int64_t walks, walk::EvalEstimator e) const override {
        return walk::visit(
            material, [&](const auto& m) { return fit::trace_eval_point(ms_, m, wi, wo, seed, stream, walks, e); },
            [&](const MaterialKernels& k) { return k.eval_point(*this, wi, wo, seed, stream, walks, e); });
    }
    fit::SplitMoments albedo_point(const walk::Material& material, const Vec3& wi, std::uint64_t seed,
                                   std::uint64_t stream, std::int64_t walks) const override {
        return walk::visit(
            material, [&](const auto& m) { return fit::trace_albedo_point(ms_, m, wi, seed, stream, walks); },
            [&](const MaterialKernels& k) { return k.albedo_point(*this, wi, seed, stream, walks); });
    }
    ///@}

    /// typeid(N), the walk::Microsurface`<`N`>` itself, and the same NDF erased (built once, on first use).
    ///@{
    const std::type_info& ndf_type() const override { return typeid(N); }
    const void* microsurface() const override { return &ms_; }
    const walk::Microsurface<AnyNdf>& erased_microsurface() const override {
        if constexpr (std::is_same_v<N, AnyNdf>) {
            return ms_;
        } else {
            std::call_once(erased_once_, [this] {
                erased_ = std::make_unique<const walk::Microsurface<AnyNdf>>(self_, ms_.options());
            });
            return *erased_;
        }
    }
    ///@}

private:
    walk::Microsurface<N> ms_;
    AnyNdf self_;
    mutable std::once_flag erased_once_;
    mutable std::unique_ptr<const walk::Microsurface<AnyNdf>> erased_;
};

/// What the registry attaches to the NDFs it makes (AnyNdf::kernels): the surface of the concrete type N.
class NdfKernels {
public:
    virtual ~NdfKernels() = default;
    /// `self`: the AnyNdf these kernels are attached to.
    virtual std::shared_ptr<const AnySurface> surface(const AnyNdf& self,
                                                      const walk::MicrosurfaceOptions& opts) const = 0;
};

/// The NdfKernels of the concrete NDF type N: a copy of the NDF, from which it builds SurfaceOf`<`N`>`.
template <Ndf N>
class KernelsOf final : public NdfKernels {
public:
    /// Holds a copy of `ndf`, the concrete type of the AnyNdf these kernels attach to.
    explicit KernelsOf(N ndf) : ndf_(std::move(ndf)) {}
    std::shared_ptr<const AnySurface> surface(const AnyNdf& self,
                                              const walk::MicrosurfaceOptions& opts) const override {
        return std::make_shared<const SurfaceOf<N>>(ndf_, opts, self);
    }

private:
    N ndf_;
};

/// The microsurface of `ndf` (its tables built here: they may refuse the NDF, as input_error): through the kernels
/// its registration attached, else (an AnyNdf made outside a registry) on AnyNdf itself, a virtual D and Lambda each.
std::shared_ptr<const AnySurface> make_surface(const AnyNdf& ndf, const walk::MicrosurfaceOptions& opts = {});

}  // namespace smithlab
