// cluster/dispatcher.hpp -- rank 0's main thread in a run on several ranks (block_jobs.hpp): answers each other
// rank's message (its partials, protocol.hpp) with its next chunk from the job board, while rank 0's own threads trace.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cluster/ledger.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/protocol.hpp"
#include "cluster/traffic.hpp"

namespace smithlab::cluster::detail {

// Rank m.from's message: its partials go to the board, its next chunk (sized by `rounds`, that rank's rounds per
// chunk, updated from the pace of the chunk it sent back) into `reply` and the ledger. Returns that chunk.
template <class Board>
Chunk answer(Board& board, Ledger& ledger, std::uint64_t& rounds, const mpi::Message& m, std::vector<char>& reply) {
    const std::string from = " from rank " + std::to_string(m.from);
    if (m.tag != tag_result) throw std::runtime_error("cluster: an unexpected message" + from);
    mpi::Reader in(m.bytes);
    const ResultHead head = read_head(in);
    if (head.count > 0 && head.job >= board.jobs()) throw std::runtime_error("cluster: a job out of range" + from);
    std::vector<typename Board::Partial> parts;
    for (std::int64_t k = 0; k < head.count; ++k) parts.push_back(board.plan().get(in, head.job));
    if (!in.done()) throw std::runtime_error("cluster: a longer message than its contents" + from);
    const auto threads_there = static_cast<std::uint64_t>(std::max<std::int64_t>(head.capacity, 1));
    if (head.count > 0)
        rounds = rounds_for(head.seconds, (static_cast<std::uint64_t>(head.count) + threads_there - 1) / threads_there);
    const Chunk c = board.traced_elsewhere(head.job, head.first, std::move(parts), rounds * threads_there);
    put_chunk(reply, c);
    ledger.update(m.from, head.returned(), c);
    return c;
}

// Serves the other ranks until each has had an empty chunk on each of its `depth` chains of requests, or the run
// failed. Polls, sleeping between probes: 20 us after a message, doubling to 1 ms while none comes (the other ranks
// hold their next chunk already, so an answer 1 ms late costs them nothing, and rank 0's own threads keep the cores).
// An error here fails the board (its result() rethrows it).
template <class Board>
void serve_ranks(Board& board, Ledger& ledger) {
    std::vector<std::uint64_t> rounds(static_cast<std::size_t>(mpi::size()), 1);  // per rank, its next chunk's
    Traffic& traffic = board.traffic();
    try {
        std::chrono::microseconds nap{20};
        for (int active = depth * (mpi::size() - 1); active > 0 && !board.failed();) {
            std::optional<mpi::Message> m = mpi::try_recv_any();
            if (!m) {
                std::this_thread::sleep_for(nap);
                nap = std::min(2 * nap, std::chrono::microseconds(1000));
                continue;
            }
            nap = std::chrono::microseconds(20);
            const auto served_from = std::chrono::steady_clock::now();
            std::vector<char> reply;
            if (answer(board, ledger, rounds[static_cast<std::size_t>(m->from)], *m, reply).count == 0) --active;
            mpi::send(m->from, tag_work, reply);  // before finishing jobs: the rank goes on at once
            traffic.messages += 2;
            traffic.bytes += static_cast<std::int64_t>(m->bytes.size() + reply.size());
            traffic.serving_seconds +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - served_from).count();
            board.finish_completed();
        }
    } catch (...) {
        board.fail();
    }
}

}  // namespace smithlab::cluster::detail
