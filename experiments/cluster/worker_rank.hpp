// cluster/worker_rank.hpp -- a rank other than 0 of a block-jobs run (block_jobs.hpp): asks rank 0 for chunks,
// traces each on its threads, and sends the partials back as its next request (protocol.hpp).
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

#include "cluster/mpi_world.hpp"
#include "cluster/protocol.hpp"
#include "cluster/runner_cache.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::cluster::detail {

// The partials of chunk c's blocks, in block order, traced on `threads` threads. A block that throws is named on
// stderr (this rank's message: rank 0 sees only the job end) and rethrown.
template <class Plan>
std::vector<typename Plan::Partial> trace_chunk(const Plan& plan, RunnerCache<Plan>& cache, const Chunk& c,
                                                unsigned threads) {
    std::vector<typename Plan::Partial> parts(c.count);
    try {
        const auto run = cache.get(c.job);
        util::reduce_blocks(
            c.count, threads, 0,
            [&](std::uint64_t b) {
                parts[b] = (*run)(c.job, c.first + b);
                return 0;
            },
            [](int&, int) {}, [](std::uint64_t) {});
    } catch (const std::exception&) {
        std::fprintf(stderr, "smithlab: rank %d failed while tracing %s, %s\n", mpi::rank(), plan.name(c.job).c_str(),
                     block_range(c).c_str());
        throw;
    }
    return parts;
}

// Keeps `depth` requests out, and answers each chunk rank 0 hands out with its partials (the next request), until
// rank 0 has answered each chain of requests with an empty chunk.
template <class Plan>
void serve(const Plan& plan, unsigned threads) {
    RunnerCache<Plan> cache(plan);
    const auto capacity = static_cast<std::int64_t>(util::thread_count(threads));
    std::vector<char> msg;
    put_head(msg, {capacity, 0});
    for (int k = 0; k < depth; ++k) mpi::send(0, tag_result, msg);
    for (int ended = 0; ended < depth;) {
        const std::vector<char> bytes = mpi::recv(0, tag_work);
        mpi::Reader in(bytes);
        const Chunk c = read_chunk(in);
        if (c.count == 0) {
            ++ended;
            continue;
        }
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<typename Plan::Partial> parts = trace_chunk(plan, cache, c, threads);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        msg.clear();
        put_head(msg, {capacity, static_cast<std::int64_t>(c.count), seconds, c.job, c.first});
        for (const auto& p : parts) plan.put(msg, p);
        mpi::send(0, tag_result, msg);
    }
}

}  // namespace smithlab::cluster::detail
