// cluster/protocol.hpp -- the messages between rank 0 and the other ranks of a block-jobs run (block_jobs.hpp), and
// how many blocks one chunk holds.
//
// Another rank sends rank 0 (tag_result): its capacity (threads, int64), the count of partials it carries (int64),
// and when it carries any: the seconds they took (double), their job (int64) and first block (uint64), then the
// partials in block order (the plan's put). Its first `depth` messages carry none. Rank 0 answers each (tag_work) with
// a chunk: job (int64), first block (uint64), count (uint64); count 0: no more work on that chain of requests.
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "cluster/mpi_world.hpp"

namespace smithlab::cluster::detail {

constexpr int tag_result = 1, tag_work = 2;

// Requests each other rank keeps out: while it traces one chunk, the answer to its next request is on its way, so it
// never waits for rank 0 between chunks.
constexpr int depth = 2;

// Blocks [first, first + count) of a job; count 0: no more work.
struct Chunk {
    std::size_t job = 0;
    std::uint64_t first = 0, count = 0;
};

// "block 3" or "blocks 3-7", for messages.
inline std::string block_range(const Chunk& c) {
    return c.count == 1 ? "block " + std::to_string(c.first)
                        : "blocks " + std::to_string(c.first) + "-" + std::to_string(c.first + c.count - 1);
}

// A chunk is a whole number of rounds (one block per thread of the rank), as many as fill about `chunk_seconds` at the
// pace of the rank's last chunk, at most max_rounds: rank 0 answers a message per chunk, not per block (a cheap
// cell's block of 4096 walks takes ~0.2 ms, a message ~5 us of rank 0's time), and the run's tail stays short.
constexpr double chunk_seconds = 0.02;
constexpr std::uint64_t max_rounds = 64;

// The rounds of a rank's next chunk, after its last one of `rounds` rounds took `seconds`.
inline std::uint64_t rounds_for(double seconds, std::uint64_t rounds) {
    if (!(seconds > 0.0)) return max_rounds;
    const double pace = seconds / static_cast<double>(rounds);
    return std::clamp<std::uint64_t>(static_cast<std::uint64_t>(chunk_seconds / pace), 1, max_rounds);
}

// The head of a message to rank 0: the fields before its partials.
struct ResultHead {
    std::int64_t capacity = 0, count = 0;
    double seconds = 0.0;
    std::size_t job = 0;
    std::uint64_t first = 0;
    // The chunk whose partials it carries (count 0: none).
    Chunk returned() const { return count > 0 ? Chunk{job, first, static_cast<std::uint64_t>(count)} : Chunk{}; }
};

inline void put_head(std::vector<char>& out, const ResultHead& h) {
    mpi::put(out, h.capacity);
    mpi::put(out, h.count);
    if (h.count <= 0) return;
    mpi::put(out, h.seconds);
    mpi::put(out, static_cast<std::int64_t>(h.job));
    mpi::put(out, h.first);
}

inline ResultHead read_head(mpi::Reader& in) {
    ResultHead h;
    h.capacity = in.get<std::int64_t>();
    h.count = in.get<std::int64_t>();
    if (h.count <= 0) return h;
    h.seconds = in.get<double>();
    h.job = static_cast<std::size_t>(in.get<std::int64_t>());
    h.first = in.get<std::uint64_t>();
    return h;
}

inline void put_chunk(std::vector<char>& out, const Chunk& c) {
    mpi::put(out, static_cast<std::int64_t>(c.job));
    mpi::put(out, c.first);
    mpi::put(out, c.count);
}

inline Chunk read_chunk(mpi::Reader& in) {
    Chunk c;
    c.job = static_cast<std::size_t>(in.get<std::int64_t>());
    c.first = in.get<std::uint64_t>();
    c.count = in.get<std::uint64_t>();
    return c;
}

}  // namespace smithlab::cluster::detail
