/// @file
/// smithlab/walk/trace.hpp -- one cell: many walks from one incident direction on one microsurface and material,
/// tallied (tally.hpp) over threads in fixed blocks (parallel.hpp). Walk k of a cell draws from WalkRng(seed, cell, k).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>

#include "smithlab/util/parallel.hpp"
#include "smithlab/walk/tally.hpp"
#include "smithlab/walk/walk.hpp"

namespace smithlab::walk {

/// A cell of the sample estimator: one incident direction, its walks and their random streams, the tallies asked for.
struct CellRequest {
    Vec3 wi;  ///< toward the light, wi.z > 0
    /// The seed and the cell's index: walk k draws from WalkRng(seed, cell, k).
    /// @{
    std::uint64_t seed = 1, cell = 0;
    /// @}
    /// The walks traced.
    std::int64_t walks = 100'000;
    /// Where each walk stops short of escaping.
    WalkLimits limits{};
    BrdfBins brdf;              ///< empty: no directional tally is allocated
    unsigned threads = 0;       ///< 0: all cores
    std::int64_t block = 4096;  ///< walks per block (part of the result's definition: the merge order)
};

/// A traced cell: its albedo tallies and, when asked for, its directional tallies.
struct CellResult {
    /// The albedo tallies.
    AlbedoTally albedo;
    /// The directional tallies, when the request has bins.
    std::optional<BrdfTally> brdf;
};

/// The blocks' boundaries: block b holds walks [b * block, min(walks, (b + 1) * block)).
inline std::uint64_t block_count(std::int64_t walks, std::int64_t block) {
    return static_cast<std::uint64_t>((walks + block - 1) / block);
}

/// What one block of a cell's walks leaves, and the cell's total: the partials merged in block order.
struct CellPartial {
    /// The albedo tallies.
    AlbedoTally albedo;
    /// The directional tallies, when the request has bins.
    std::optional<BrdfTally> brdf;
};

/// The total before any block: zero, with the directional tally allocated when the request asks for one.
inline CellPartial empty_partial(const CellRequest& r) {
    CellPartial p;
    if (!r.brdf.empty()) p.brdf.emplace(r.brdf);
    return p;
}

/// Adds the partial p to total (both with or both without directional tallies).
inline void merge_partial(CellPartial& total, const CellPartial& p) {
    total.albedo.merge(p.albedo);
    if (total.brdf) total.brdf->merge(*p.brdf);
}

/// Block b of the cell: walks [b * block, min(walks, (b + 1) * block)) in order, a pure function of (seed, cell, b).
/// trace_cell runs it over threads; a distributed run (experiments/, under MPI) runs it on other processes and merges
/// the partials in the same order: the same bits either way.
template <class Microsurface, class M>
CellPartial trace_block(const Microsurface& ms, const M& material, const CellRequest& r, std::uint64_t b) {
    CellPartial p = empty_partial(r);
    const std::int64_t first = static_cast<std::int64_t>(b) * r.block, last = std::min(r.walks, first + r.block);
    for (std::int64_t k = first; k < last; ++k) {
        WalkRng g(r.seed, r.cell, static_cast<std::uint64_t>(k));
        const WalkSample s = sample_walk(ms, material, r.wi, g, r.limits);
        p.albedo.add(s);
        if (p.brdf) p.brdf->add(s);
    }
    return p;
}

/// progress(fraction done) is called from a worker after each merged block (outside any walk).
template <class Microsurface, class M>
CellResult trace_cell(const Microsurface& ms, const M& material, const CellRequest& r,
                      const std::function<void(double)>& progress = {}) {
    const std::uint64_t blocks = block_count(r.walks, r.block);
    CellPartial total = util::reduce_blocks(
        blocks, r.threads, empty_partial(r), [&](std::uint64_t b) { return trace_block(ms, material, r, b); },
        merge_partial,
        [&](std::uint64_t merged) {
            if (progress) progress(static_cast<double>(merged) / static_cast<double>(blocks));
        });
    return {std::move(total.albedo), std::move(total.brdf)};
}

/// A direction pair of the eval estimator: its walks and random streams, the estimator, and the threads and blocks it
/// runs in.
struct EvalRequest {
    /// The incident direction (toward the light) and the outgoing one.
    /// @{
    Vec3 wi, wo;  ///< wi.z > 0; wo anywhere (f |cos theta_o| = 0 below for the materials here)
    /// @}
    /// The seed and the cell's index: walk k draws from WalkRng(seed, cell, k).
    /// @{
    std::uint64_t seed = 1, cell = 0;
    /// @}
    /// The walks traced.
    std::int64_t walks = 100'000;
    /// Where each walk stops short of escaping.
    WalkLimits limits{};
    /// The threads (0: all cores).
    unsigned threads = 0;
    /// Walks per block (the merge order: part of the result's definition).
    std::int64_t block = 4096;
    EvalEstimator estimator = EvalEstimator::next_event;  ///< walk.hpp; the brdf command's is next_event
    /// If set, called before each block, on the thread that runs it (a front end's check for an interruption, once
    /// per block and never inside a walk); what it throws ends the cell and is rethrown by eval_cell.
    std::function<void()> before_block = {};
};

/// The eval estimator's tallies of f(wi, wo) |cos theta_o| over r.walks walks from r.wi toward r.wo, in blocks merged
/// in block order over r.threads threads: the same bits for any number of threads.
template <class Microsurface, class M>
EvalTally eval_cell(const Microsurface& ms, const M& material, const EvalRequest& r) {
    return util::reduce_blocks(
        block_count(r.walks, r.block), r.threads, EvalTally{},
        [&](std::uint64_t b) {
            if (r.before_block) r.before_block();
            EvalTally p;
            const std::int64_t first = static_cast<std::int64_t>(b) * r.block,
                               last = std::min(r.walks, first + r.block);
            for (std::int64_t k = first; k < last; ++k) {
                WalkRng g(r.seed, r.cell, static_cast<std::uint64_t>(k));
                p.add(eval_walk(ms, material, r.wi, r.wo, g, r.limits, r.estimator));
            }
            return p;
        },
        [](EvalTally& t, const EvalTally& p) { t.merge(p); }, [](std::uint64_t) {});
}

}  // namespace smithlab::walk
