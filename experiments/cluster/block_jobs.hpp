// cluster/block_jobs.hpp -- jobs made of numbered blocks, traced on the threads of every MPI rank and merged on rank 0
// in block order: the same bits as one process on any number of threads, for any number of ranks.
//
// A plan says what the jobs are; every rank builds the same plan from the same input:
//   using Partial;                                     what a block leaves (a tally); a job's total is one too
//   std::size_t jobs() const;
//   std::uint64_t blocks(std::size_t j) const;          rank 0: job j's blocks, 0 for one that needs none (reused)
//   Partial empty(std::size_t j) const;                 rank 0: the total before any block
//   void merge(Partial& total, const Partial& p) const;
//   std::size_t kind(std::size_t j) const;              jobs of one kind share a runner (one microsurface)
//   Runner<Partial> runner(std::size_t j) const;        (job, block) -> Partial, for every job of j's kind
//   void put(std::vector<char>& out, const Partial&) const;   the bytes another rank sends of a partial
//   Partial get(mpi::Reader& in, std::size_t j) const;
//   void finish(std::size_t j, Partial&& total);        rank 0: job j's total, all its blocks merged (any order)
//   std::string name(std::size_t j) const;              for messages: "cell 12 (ggx(alpha=0.3), mirror, theta_i 45)"
//
// Rank 0's threads trace blocks one at a time; its main thread serves the other ranks. Another rank asks for a chunk
// (blocks of one job, a whole number per thread, about 20 ms of its work), traces it on its threads, and sends the
// partials back with its next request (two requests out per rank, so the next chunk is there when one is done).
// Blocks go out in (job, block) order as threads and ranks free up, so cells that differ in cost by orders of
// magnitude balance themselves, and rank 0 merges each job's partials in block order whoever traced them. Without
// MPI, or on one rank, this is the threads of one process.
//
// When mpirun ends the job because a rank died, it sends rank 0 SIGTERM: rank 0 prints which rank held which job
// (output::SignalNote) before it ends; mpirun's own message names the rank that died. A block that throws on
// another rank ends the job (main's handler: MPI_Abort) after that rank names the job it was tracing.
//
// The pieces: protocol.hpp (the messages, the chunk size), runner_cache.hpp (one runner per kind of job and rank),
// worker_rank.hpp (a rank other than 0), job_board.hpp (rank 0's hand-out and in-order merge, and its threads' loop),
// dispatcher.hpp (rank 0's main thread serving the other ranks), ledger.hpp (what each rank holds, for the signal
// note).
#pragma once

#include <algorithm>
#include <cstdint>
#include <thread>
#include <type_traits>
#include <vector>

#include "cluster/dispatcher.hpp"
#include "cluster/job_board.hpp"
#include "cluster/ledger.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/protocol.hpp"
#include "cluster/runner_cache.hpp"
#include "cluster/traffic.hpp"
#include "cluster/worker_rank.hpp"
#include "output/signal_cleanup.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::cluster {

// Runs every job of the plan on all ranks (each with `threads` threads, 0: all cores). On rank 0, finish(j, total)
// for each job with blocks, and progress(blocks merged, blocks in all) after each merge; the other ranks return when
// rank 0 has handed out everything. Rethrows the first exception of a block or of finish.
template <class Plan, class Progress>
Traffic run_jobs(Plan& plan, unsigned threads, Progress&& progress) {
    if (mpi::rank() != 0) {
        detail::serve(plan, threads);
        return {};
    }
    detail::JobBoard<Plan, std::remove_reference_t<Progress>> board(plan, progress);
    detail::RunnerCache<Plan> cache(plan);
    auto trace_here = [&] { detail::trace_blocks_here(board, cache); };
    if (mpi::size() == 1) {
        // One process: as many threads as there are blocks, at most `threads`, this one among them.
        const std::uint64_t n =
            std::min<std::uint64_t>(util::thread_count(threads), std::max<std::uint64_t>(board.blocks_in_all(), 1));
        std::vector<std::jthread> pool;
        for (std::uint64_t t = 1; t < n; ++t) pool.emplace_back(trace_here);
        trace_here();
    } else {
        // Rank 0 of several: `threads` threads trace while this one serves the other ranks.
        detail::Ledger ledger(mpi::size());
        const output::SignalNote note([&] { return ledger.note(plan); });
        std::vector<std::jthread> pool;
        for (std::uint64_t t = 0; t < util::thread_count(threads); ++t) pool.emplace_back(trace_here);
        detail::serve_ranks(board, ledger);
    }
    return board.result();
}

}  // namespace smithlab::cluster
