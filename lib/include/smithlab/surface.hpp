/// @file
/// smithlab/surface.hpp -- the Smith microsurface of one NDF with the NDF's type erased once: what a command runs on a
/// cell of walks, a block (or a point) at a time.
///
/// A command holds NDFs as AnyNdf (registry.hpp); a walk needs the concrete type, so that D, Lambda and the visible
/// normals are direct calls (walk.hpp). The registry records, for the type its factory returns, how to build
/// SurfaceOf<N> (NdfKernels); make_surface builds one per cell, tables included, and each of its calls is one virtual
/// call for a whole block of walks (4096 by default) or a point: none per bounce. Every operation visits the facet
/// material once (facets.hpp's closed std::variant) and runs the templates of walk/trace.hpp and fit/dataset.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <variant>

#include "smithlab/any_ndf.hpp"
#include "smithlab/fit/dataset.hpp"
#include "smithlab/walk/facets.hpp"
#include "smithlab/walk/microsurface.hpp"
#include "smithlab/walk/trace.hpp"

namespace smithlab {

/// The Smith microsurface of one NDF, its type erased: each call runs a block of walks, a direction pair or a fitter's
/// point on the concrete type.
class AnySurface {
public:
    virtual ~AnySurface() = default;
    /// Block b of a cell (walk::trace_block): the sample estimator's tallies.
    virtual walk::CellPartial trace_block(const walk::Material& material, const walk::CellRequest& r,
                                          std::uint64_t b) const = 0;
    /// One direction pair by the eval estimator over r.threads (walk::eval_cell).
    virtual walk::EvalTally eval_cell(const walk::Material& material, const walk::EvalRequest& r) const = 0;
    /// The fitter's points, one thread each (fit::trace_eval_point, fit::trace_albedo_point).
    /// @{
    virtual fit::SplitMoments eval_point(const walk::Material& material, const Vec3& wi, const Vec3& wo,
                                         std::uint64_t seed, std::uint64_t stream, std::int64_t walks) const = 0;
    virtual fit::SplitMoments albedo_point(const walk::Material& material, const Vec3& wi, std::uint64_t seed,
                                           std::uint64_t stream, std::int64_t walks) const = 0;
    /// @}
};

/// The microsurface of the concrete NDF type N, built once (its tables included); every call visits the material once.
template <Ndf N>
class SurfaceOf final : public AnySurface {
public:
    /// Builds walk::Microsurface<N> of `ndf` with the given conventions.
    SurfaceOf(const N& ndf, const walk::MicrosurfaceOptions& opts) : ms_(ndf, opts) {}

    walk::CellPartial trace_block(const walk::Material& material, const walk::CellRequest& r,
                                  std::uint64_t b) const override {
        return std::visit([&](const auto& m) { return walk::trace_block(ms_, m, r, b); }, material);
    }
    walk::EvalTally eval_cell(const walk::Material& material, const walk::EvalRequest& r) const override {
        return std::visit([&](const auto& m) { return walk::eval_cell(ms_, m, r); }, material);
    }
    fit::SplitMoments eval_point(const walk::Material& material, const Vec3& wi, const Vec3& wo, std::uint64_t seed,
                                 std::uint64_t stream, std::int64_t walks) const override {
        return std::visit([&](const auto& m) { return fit::trace_eval_point(ms_, m, wi, wo, seed, stream, walks); },
                          material);
    }
    fit::SplitMoments albedo_point(const walk::Material& material, const Vec3& wi, std::uint64_t seed,
                                   std::uint64_t stream, std::int64_t walks) const override {
        return std::visit([&](const auto& m) { return fit::trace_albedo_point(ms_, m, wi, seed, stream, walks); },
                          material);
    }

private:
    walk::Microsurface<N> ms_;
};

/// What the registry attaches to the NDFs it makes (AnyNdf::kernels): the surface of the concrete type N.
class NdfKernels {
public:
    virtual ~NdfKernels() = default;
    /// A new microsurface of the NDF (its tables built) for the given conventions.
    virtual std::shared_ptr<const AnySurface> surface(const walk::MicrosurfaceOptions& opts) const = 0;
};

/// The kernels of the concrete NDF type N: surfaces of SurfaceOf<N>.
template <Ndf N>
class KernelsOf final : public NdfKernels {
public:
    /// Holds `ndf`, of which every surface is made.
    explicit KernelsOf(N ndf) : ndf_(std::move(ndf)) {}
    std::shared_ptr<const AnySurface> surface(const walk::MicrosurfaceOptions& opts) const override {
        return std::make_shared<const SurfaceOf<N>>(ndf_, opts);
    }

private:
    N ndf_;
};

/// The microsurface of `ndf` (its tables built here: they may refuse the NDF, as input_error): through the kernels
/// its registration attached, else (an AnyNdf made outside a registry) on AnyNdf itself, a virtual D and Lambda each.
std::shared_ptr<const AnySurface> make_surface(const AnyNdf& ndf, const walk::MicrosurfaceOptions& opts = {});

}  // namespace smithlab
