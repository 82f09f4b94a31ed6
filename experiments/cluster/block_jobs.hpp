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
//   void finish(std::size_t j, Partial&& total);        rank 0: job j's total, all its blocks merged (jobs in any order)
//   std::string name(std::size_t j) const;              "cell 12 (ggx(alpha=0.3), mirror, theta_i 45)", for messages
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
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "cluster/mpi_world.hpp"
#include "output/signal_cleanup.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::cluster {

template <class Partial>
using Runner = std::function<Partial(std::size_t job, std::uint64_t block)>;

// What rank 0 saw: its messages and bytes both ways, the blocks traced here and by the other ranks, the time its
// main thread spent serving messages (reading, merging, answering: the dispatcher's cost), and the time finishing
// jobs took (the plan's finish: writing cell files and caches), on whichever of its threads.
struct Traffic {
    std::int64_t messages = 0, bytes = 0;
    std::uint64_t blocks_here = 0, blocks_elsewhere = 0;
    double serving_seconds = 0.0, finishing_seconds = 0.0;
};

namespace detail {

constexpr int tag_result = 1, tag_work = 2;

// Blocks [first, first + count) of a job; count 0: no more work.
struct Chunk {
    std::size_t job = 0;
    std::uint64_t first = 0, count = 0;
};

// The runner of the kind last asked for, built on first use: one microsurface per kind and rank, shared by the
// rank's threads (each holds its own reference while it traces, so a change of kind frees nothing in use).
template <class Plan>
class RunnerCache {
public:
    using R = Runner<typename Plan::Partial>;
    explicit RunnerCache(const Plan& plan) : plan_(plan) {}
    std::shared_ptr<const R> get(std::size_t job) {
        const std::lock_guard guard(lock_);
        const std::size_t k = plan_.kind(job);
        if (!runner_ || k != kind_) {
            runner_ = std::make_shared<const R>(plan_.runner(job));
            kind_ = k;
        }
        return runner_;
    }

private:
    const Plan& plan_;
    std::mutex lock_;
    std::size_t kind_ = 0;
    std::shared_ptr<const R> runner_;
};

inline std::string block_range(const Chunk& c) {
    return c.count == 1 ? "block " + std::to_string(c.first)
                        : "blocks " + std::to_string(c.first) + "-" + std::to_string(c.first + c.count - 1);
}

// Requests each other rank keeps out: while it traces one chunk, the answer to its next request is on its way, so it
// never waits for rank 0 between chunks.
constexpr int depth = 2;

// A chunk is a whole number of rounds (one block per thread of the rank), as many as fill about `chunk_seconds` at the
// pace of the rank's last chunk, at most max_rounds: rank 0 answers a message per chunk, not per block (a cheap
// cell's block of 4096 walks takes ~0.2 ms, a message ~5 us of rank 0's time), and the run's tail stays short.
constexpr double chunk_seconds = 0.02;
constexpr std::uint64_t max_rounds = 64;

inline std::uint64_t rounds_for(double seconds, std::uint64_t rounds) {
    if (!(seconds > 0.0)) return max_rounds;
    const double pace = seconds / static_cast<double>(rounds);
    return std::clamp<std::uint64_t>(static_cast<std::uint64_t>(chunk_seconds / pace), 1, max_rounds);
}

// A rank other than 0: asks rank 0 for chunks, traces each on its threads, and sends the partials back as its next
// request, until rank 0 has answered each of its `depth` request chains with an empty chunk.
template <class Plan>
void serve(const Plan& plan, unsigned threads) {
    RunnerCache<Plan> cache(plan);
    const auto capacity = static_cast<std::int64_t>(util::thread_count(threads));
    std::vector<char> msg;
    mpi::put(msg, capacity);
    mpi::put(msg, std::int64_t{0});
    for (int k = 0; k < depth; ++k) mpi::send(0, tag_result, msg);
    for (int ended = 0; ended < depth;) {
        const std::vector<char> bytes = mpi::recv(0, tag_work);
        mpi::Reader in(bytes);
        const Chunk c{static_cast<std::size_t>(in.get<std::int64_t>()), in.get<std::uint64_t>(), in.get<std::uint64_t>()};
        if (c.count == 0) {
            ++ended;
            continue;
        }
        std::vector<typename Plan::Partial> parts(c.count);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            const auto run = cache.get(c.job);
            util::reduce_blocks(
                c.count, threads, 0,
                [&](std::uint64_t b) {
                    parts[b] = (*run)(c.job, c.first + b);
                    return 0;
                },
                [](int&, int) {}, [](std::uint64_t) {});
        } catch (const std::exception& e) {
            std::fprintf(stderr, "smithlab: rank %d failed while tracing %s, %s\n", mpi::rank(), plan.name(c.job).c_str(),
                         block_range(c).c_str());
            throw;
        }
        msg.clear();
        mpi::put(msg, capacity);
        mpi::put(msg, static_cast<std::int64_t>(c.count));
        mpi::put(msg, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        mpi::put(msg, static_cast<std::int64_t>(c.job));
        mpi::put(msg, c.first);
        for (const auto& p : parts) plan.put(msg, p);
        mpi::send(0, tag_result, msg);
    }
}

}  // namespace detail

// Runs every job of the plan on all ranks (each with `threads` threads, 0: all cores). On rank 0, finish(j, total)
// for each job with blocks, and progress(blocks merged, blocks in all) after each merge; the other ranks return when
// rank 0 has handed out everything. Rethrows the first exception of a block or of finish.
template <class Plan, class Progress>
Traffic run_jobs(Plan& plan, unsigned threads, Progress&& progress) {
    using Partial = typename Plan::Partial;
    if (mpi::rank() != 0) {
        detail::serve(plan, threads);
        return {};
    }
    const std::size_t n = plan.jobs();
    std::vector<std::uint64_t> blocks(n);
    std::uint64_t all = 0;
    for (std::size_t j = 0; j < n; ++j) all += blocks[j] = plan.blocks(j);

    std::mutex lock;         // everything below but the plan's finish
    std::mutex finish_lock;  // the plan's finish (writing a cell file): one at a time, not holding up the hand-out
    std::size_t job = 0;
    std::uint64_t next = 0, merged = 0;
    std::map<std::size_t, util::InOrder<Partial>> open;
    Traffic traffic;
    std::exception_ptr error;
    std::atomic<bool> failed{false};
    auto take = [&](std::uint64_t most) {  // under lock
        while (job < n && next == blocks[job]) {
            ++job;
            next = 0;
        }
        if (job == n) return detail::Chunk{n, 0, 0};
        if (next == 0) open.emplace(job, util::InOrder<Partial>(plan.empty(job)));
        const detail::Chunk c{job, next, std::min(most, blocks[job] - next)};
        next += c.count;
        return c;
    };
    // Under lock; a job whose last block this was goes to `done`, for finish() once the lock is released.
    auto deliver = [&](std::size_t j, std::uint64_t b, Partial&& p, std::vector<std::pair<std::size_t, Partial>>& done) {
        const auto it = open.find(j);
        if (it == open.end() || b >= blocks[j]) throw std::runtime_error("cluster: a block that was not handed out came back");
        merged += it->second.add(b, std::move(p), [&](Partial& t, const Partial& q) { plan.merge(t, q); });
        if (it->second.merged() == blocks[j]) {
            done.emplace_back(j, std::move(it->second.total()));
            open.erase(it);
        }
        progress(merged, all);
    };
    auto finish = [&](std::vector<std::pair<std::size_t, Partial>>& done) {  // not under lock
        if (done.empty()) return;
        const std::lock_guard guard(finish_lock);
        const auto t0 = std::chrono::steady_clock::now();
        for (auto& [j, total] : done) plan.finish(j, std::move(total));
        done.clear();
        traffic.finishing_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    auto fail = [&] {
        const std::lock_guard guard(lock);
        if (!error) error = std::current_exception();
        failed = true;
    };

    detail::RunnerCache<Plan> cache(plan);
    auto trace_here = [&] {
        try {
            for (;;) {
                detail::Chunk c;
                {
                    const std::lock_guard guard(lock);
                    if (failed) return;
                    c = take(1);
                }
                if (c.count == 0) return;
                Partial p = (*cache.get(c.job))(c.job, c.first);
                std::vector<std::pair<std::size_t, Partial>> done;
                {
                    const std::lock_guard guard(lock);
                    deliver(c.job, c.first, std::move(p), done);
                    ++traffic.blocks_here;
                }
                finish(done);
            }
        } catch (...) {
            fail();
        }
    };

    if (mpi::size() == 1) {
        std::vector<std::jthread> pool;
        for (std::uint64_t t = 1; t < std::min<std::uint64_t>(util::thread_count(threads), std::max<std::uint64_t>(all, 1)); ++t)
            pool.emplace_back(trace_here);
        trace_here();
    } else {
        // What each rank holds, for the note a signal prints (mpirun's SIGTERM when a rank died).
        std::mutex ledger_lock;
        std::vector<std::vector<detail::Chunk>> held(static_cast<std::size_t>(mpi::size()));
        const output::SignalNote note([&] {
            const std::lock_guard guard(ledger_lock);
            std::string text = "smithlab: stopped by a signal (mpirun sends one when a rank dies, and names it)";
            for (std::size_t r = 1; r < held.size(); ++r)
                for (const detail::Chunk& c : held[r])
                    text += "\n  rank " + std::to_string(r) + " held " + plan.name(c.job) + ", " + detail::block_range(c);
            return text + "\n  the jobs finished so far are kept: the same command resumes from them";
        });
        std::vector<std::uint64_t> rounds(static_cast<std::size_t>(mpi::size()), 1);  // per rank, its next chunk's
        std::vector<std::pair<std::size_t, Partial>> finished;
        std::vector<std::jthread> pool;
        for (std::uint64_t t = 0; t < util::thread_count(threads); ++t) pool.emplace_back(trace_here);
        try {
            // Polls, sleeping between probes: 20 us after a message, doubling to 1 ms while none comes (the other
            // ranks hold their next chunk already, so an answer 1 ms late costs them nothing, and rank 0's own
            // threads keep the cores).
            std::chrono::microseconds nap{20};
            for (int active = detail::depth * (mpi::size() - 1); active > 0 && !failed;) {
                std::optional<mpi::Message> m = mpi::try_recv_any();
                if (!m) {
                    std::this_thread::sleep_for(nap);
                    nap = std::min(2 * nap, std::chrono::microseconds(1000));
                    continue;
                }
                nap = std::chrono::microseconds(20);
                const auto served_from = std::chrono::steady_clock::now();
                if (m->tag != detail::tag_result) throw std::runtime_error("cluster: an unexpected message from rank " + std::to_string(m->from));
                mpi::Reader in(m->bytes);
                const auto capacity = in.get<std::int64_t>(), count = in.get<std::int64_t>();
                std::vector<char> reply;
                {
                    const double seconds = count > 0 ? in.get<double>() : 0.0;
                    const std::size_t j = count > 0 ? static_cast<std::size_t>(in.get<std::int64_t>()) : 0;
                    const std::uint64_t first = count > 0 ? in.get<std::uint64_t>() : 0;
                    if (count > 0 && j >= n) throw std::runtime_error("cluster: a job out of range from rank " + std::to_string(m->from));
                    std::vector<Partial> parts;
                    for (std::int64_t k = 0; k < count; ++k) parts.push_back(plan.get(in, j));
                    if (!in.done()) throw std::runtime_error("cluster: a longer message than its contents from rank " + std::to_string(m->from));
                    const std::lock_guard guard(lock);
                    for (std::int64_t k = 0; k < count; ++k)
                        deliver(j, first + static_cast<std::uint64_t>(k), std::move(parts[static_cast<std::size_t>(k)]), finished);
                    traffic.blocks_elsewhere += static_cast<std::uint64_t>(count);
                    const auto threads_there = static_cast<std::uint64_t>(std::max<std::int64_t>(capacity, 1));
                    std::uint64_t& r = rounds[static_cast<std::size_t>(m->from)];
                    if (count > 0) r = detail::rounds_for(seconds, (static_cast<std::uint64_t>(count) + threads_there - 1) / threads_there);
                    const detail::Chunk c = take(r * threads_there);
                    mpi::put(reply, static_cast<std::int64_t>(c.job));
                    mpi::put(reply, c.first);
                    mpi::put(reply, c.count);
                    if (c.count == 0) --active;
                    const std::lock_guard ledger(ledger_lock);
                    std::vector<detail::Chunk>& h = held[static_cast<std::size_t>(m->from)];
                    if (count > 0) std::erase_if(h, [&](const detail::Chunk& d) { return d.job == j && d.first == first; });
                    if (c.count > 0) h.push_back(c);
                }
                mpi::send(m->from, detail::tag_work, reply);  // before finishing jobs: the rank goes on at once
                traffic.messages += 2;
                traffic.bytes += static_cast<std::int64_t>(m->bytes.size() + reply.size());
                traffic.serving_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - served_from).count();
                finish(finished);
            }
        } catch (...) {
            fail();
        }
    }
    if (error) std::rethrow_exception(error);
    if (!open.empty() || merged != all) throw std::logic_error("cluster: jobs left open");
    return traffic;
}

}  // namespace smithlab::cluster
