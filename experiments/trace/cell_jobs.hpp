// The path tracer's cells as block jobs (cluster/block_jobs.hpp), for `trace` and the report's [walk]: cell j's walks
// in blocks of its request's block size (walk::trace_block) on the microsurface of its NDF with the facets of its
// material, partials merged in block order (walk::merge_partial): the bits of walk::trace_cell for any number of
// ranks and threads. A partial travels between ranks as its tallies' doubles and integers.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "cluster/block_jobs.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/walk/trace.hpp"

namespace smithlab::trace {

struct CellJob {
    AnyNdf ndf;
    walk::Material material;
    walk::CellRequest request;  // its wi, cell (the random stream), walks, block, limits and directional bins
    std::string name;           // for messages: "cell 12 (ggx(alpha=0.3), mirror, theta_i 45)"
    bool needed = true;         // rank 0: false for a cell an earlier run finished
};

class CellJobs {
public:
    using Partial = walk::CellPartial;
    using Finish = std::function<void(std::size_t cell, walk::CellPartial&& total)>;

    // Consecutive cells of one NDF spec share a microsurface.
    CellJobs(std::vector<CellJob> cells, const walk::MicrosurfaceOptions& opts, Finish finish)
        : cells_(std::move(cells)), opts_(opts), finish_(std::move(finish)) {
        for (std::size_t j = 0; j < cells_.size(); ++j)
            kinds_.push_back(j > 0 && cells_[j].ndf.spec() == cells_[j - 1].ndf.spec() ? kinds_.back() : j);
    }

    std::size_t jobs() const { return cells_.size(); }
    std::uint64_t blocks(std::size_t j) const {
        return cells_[j].needed ? walk::block_count(cells_[j].request.walks, cells_[j].request.block) : 0;
    }
    Partial empty(std::size_t j) const { return walk::empty_partial(cells_[j].request); }
    void merge(Partial& total, const Partial& p) const { walk::merge_partial(total, p); }
    std::size_t kind(std::size_t j) const { return kinds_[j]; }
    std::string name(std::size_t j) const { return cells_[j].name; }
    void finish(std::size_t j, Partial&& total) { finish_(j, std::move(total)); }

    // Traces block b of any cell of j's NDF, on one microsurface built here (its NDF's concrete type: no virtual
    // call in the walk, one per block) and shared by the threads that call it.
    cluster::Runner<Partial> runner(std::size_t j) const {
        return [surface = make_surface(cells_[j].ndf, opts_), this](std::size_t c, std::uint64_t b) {
            return surface->trace_block(cells_[c].material, cells_[c].request, b);
        };
    }

    void put(std::vector<char>& out, const Partial& p) const;
    Partial get(cluster::mpi::Reader& in, std::size_t j) const;

private:
    std::vector<CellJob> cells_;
    walk::MicrosurfaceOptions opts_;
    Finish finish_;
    std::vector<std::size_t> kinds_;
};

}  // namespace smithlab::trace
