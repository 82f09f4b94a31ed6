// cluster/job_board.hpp -- rank 0's account of a block-jobs run (block_jobs.hpp): which block goes out next, and each
// job's partials merged in block order whoever traced them, its total handed to the plan's finish when whole.
//
// Blocks go out in (job, block) order. Rank 0's threads and its main thread (serving the other ranks) share one
// board: everything but the plan's finish under one lock; the finish (writing a cell file) under another, one at a
// time, not holding up the hand-out.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cluster/protocol.hpp"
#include "cluster/traffic.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::cluster::detail {

// Progress: progress(blocks merged, blocks in all), called after each merge, under the board's lock.
template <class Plan, class Progress>
class JobBoard {
public:
    using Partial = typename Plan::Partial;

    JobBoard(Plan& plan, Progress& progress) : plan_(plan), progress_(progress), blocks_(plan.jobs()) {
        for (std::size_t j = 0; j < blocks_.size(); ++j) all_ += blocks_[j] = plan.blocks(j);
    }

    const Plan& plan() const { return plan_; }
    std::size_t jobs() const { return blocks_.size(); }
    std::uint64_t blocks_in_all() const { return all_; }
    bool failed() const { return failed_; }
    Traffic& traffic() { return traffic_; }

    // For a thread of rank 0: the next block (count 0: none left, or a block or finish failed).
    Chunk next_block() {
        const std::lock_guard guard(lock_);
        if (failed_) return {};
        return take(1);
    }

    // A block that a thread of rank 0 traced; finishes the job it completes.
    void traced_here(const Chunk& c, Partial&& p) {
        std::vector<std::pair<std::size_t, Partial>> done;
        {
            const std::lock_guard guard(lock_);
            deliver(c.job, c.first, std::move(p), done);
            ++traffic_.blocks_here;
        }
        finish(done);
    }

    // The partials of blocks [first, first + parts.size()) of job j from another rank, and that rank's next chunk, of
    // at most `most` blocks. The jobs they complete wait for finish_completed(), once the chunk is on its way.
    Chunk traced_elsewhere(std::size_t j, std::uint64_t first, std::vector<Partial>&& parts, std::uint64_t most) {
        const std::lock_guard guard(lock_);
        for (std::size_t k = 0; k < parts.size(); ++k) deliver(j, first + k, std::move(parts[k]), completed_);
        traffic_.blocks_elsewhere += parts.size();
        return take(most);
    }
    void finish_completed() { finish(completed_); }

    // The exception being handled ends the run: the threads take no more blocks, and result() rethrows the first.
    void fail() {
        const std::lock_guard guard(lock_);
        if (!error_) error_ = std::current_exception();
        failed_ = true;
    }

    // Once every thread is done: what rank 0 saw, or the first exception of a block or of finish.
    Traffic result() const {
        if (error_) std::rethrow_exception(error_);
        if (!open_.empty() || merged_ != all_) throw std::logic_error("cluster: jobs left open");
        return traffic_;
    }

private:
    // Under the lock: the next chunk of at most `most` blocks of one job, opening the job at its first block.
    Chunk take(std::uint64_t most) {
        const std::size_t n = blocks_.size();
        while (job_ < n && next_ == blocks_[job_]) {
            ++job_;
            next_ = 0;
        }
        if (job_ == n) return Chunk{n, 0, 0};
        if (next_ == 0) open_.emplace(job_, util::InOrder<Partial>(plan_.empty(job_)));
        const Chunk c{job_, next_, std::min(most, blocks_[job_] - next_)};
        next_ += c.count;
        return c;
    }

    // Under the lock: block b of job j merged in block order; a job whose last block this was goes to `done`, for
    // finish() once the lock is released.
    void deliver(std::size_t j, std::uint64_t b, Partial&& p, std::vector<std::pair<std::size_t, Partial>>& done) {
        const auto it = open_.find(j);
        if (it == open_.end() || b >= blocks_[j])
            throw std::runtime_error("cluster: a block that was not handed out came back");
        merged_ += it->second.add(b, std::move(p), [&](Partial& t, const Partial& q) { plan_.merge(t, q); });
        if (it->second.merged() == blocks_[j]) {
            done.emplace_back(j, std::move(it->second.total()));
            open_.erase(it);
        }
        progress_(merged_, all_);
    }

    // Not under the lock: the plan's finish of each completed job, one call at a time.
    void finish(std::vector<std::pair<std::size_t, Partial>>& done) {
        if (done.empty()) return;
        const std::lock_guard guard(finish_lock_);
        const auto t0 = std::chrono::steady_clock::now();
        for (auto& [j, total] : done) plan_.finish(j, std::move(total));
        done.clear();
        traffic_.finishing_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    Plan& plan_;
    Progress& progress_;
    std::vector<std::uint64_t> blocks_;  // per job, 0 for one that needs none
    std::uint64_t all_ = 0;
    std::mutex lock_;         // everything but the plan's finish
    std::mutex finish_lock_;  // the plan's finish
    std::size_t job_ = 0;     // the next block to hand out: (job_, next_)
    std::uint64_t next_ = 0, merged_ = 0;
    std::map<std::size_t, util::InOrder<Partial>> open_;
    std::vector<std::pair<std::size_t, Partial>> completed_;  // by other ranks' blocks, not yet finished
    Traffic traffic_;
    std::exception_ptr error_;
    std::atomic<bool> failed_{false};
};

// A thread of rank 0: traces blocks one at a time until none is left or the run failed.
template <class Board, class Cache>
void trace_blocks_here(Board& board, Cache& cache) {
    try {
        for (;;) {
            const Chunk c = board.next_block();
            if (c.count == 0) return;
            board.traced_here(c, (*cache.get(c.job))(c.job, c.first));
        }
    } catch (...) {
        board.fail();
    }
}

}  // namespace smithlab::cluster::detail
