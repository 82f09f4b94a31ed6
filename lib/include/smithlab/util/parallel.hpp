/// @file
/// smithlab/util/parallel.hpp -- numbered blocks of work over threads, reduced in block order.
///
/// Block b is a pure function of b (its walks draw from WalkRng(seed, cell, walk)), and the partial sums are merged in
/// the order 0, 1, 2, ... whatever thread finished first, so the result is the same bits for any number of threads.
/// Memory: a partial result waits only until every block before it is merged.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace smithlab::util {

/// The threads a run uses: `threads`, or all cores for 0.
inline unsigned thread_count(unsigned threads) {
    return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

/// Partials numbered 0, 1, 2, ... that arrive in any order, merged into a total in number order: a partial waits
/// only until every one before it is merged. Not thread-safe (its users lock). Also the distributed runs'
/// (experiments/cluster/block_jobs.hpp), which merge what other processes traced in the same order: the same bits.
template <class Partial>
class InOrder {
public:
    /// Starts from `total`, before any partial.
    explicit InOrder(Partial total) : total_(std::move(total)) {}
    /// Adds partial b; merge(total, partial) for each that is next in order. Returns how many were merged.
    template <class Merge>
    std::uint64_t add(std::uint64_t b, Partial p, Merge&& merge) {
        pending_.emplace(b, std::move(p));
        const std::uint64_t before = merged_;
        for (auto it = pending_.begin(); it != pending_.end() && it->first == merged_; it = pending_.erase(it)) {
            merge(total_, it->second);
            ++merged_;
        }
        return merged_ - before;
    }
    /// How many partials are merged: those numbered 0 .. merged() - 1.
    std::uint64_t merged() const { return merged_; }
    /// The total of the partials merged so far.
    Partial& total() { return total_; }

private:
    Partial total_;
    std::map<std::uint64_t, Partial> pending_;
    std::uint64_t merged_ = 0;
};

/// run(b) -> Partial for b in [0, blocks), on `threads` threads (0: all cores); merge(total, partial) in block order;
/// progress(merged_blocks) after each merge. The first exception a block throws is rethrown here.
template <class Partial, class Run, class Merge, class Progress>
Partial reduce_blocks(std::uint64_t blocks, unsigned threads, Partial total, Run run, Merge merge, Progress progress) {
    threads = static_cast<unsigned>(std::min<std::uint64_t>(thread_count(threads), std::max<std::uint64_t>(blocks, 1)));
    std::atomic<std::uint64_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex lock;
    InOrder<Partial> sum(std::move(total));
    std::exception_ptr error;
    auto worker = [&] {
        try {
            for (std::uint64_t b; !failed && (b = next.fetch_add(1)) < blocks;) {
                Partial p = run(b);
                const std::lock_guard guard(lock);
                for (std::uint64_t k = sum.add(b, std::move(p), merge); k > 0; --k) progress(sum.merged() - k + 1);
            }
        } catch (...) {
            const std::lock_guard guard(lock);
            if (!error) error = std::current_exception();
            failed = true;
        }
    };
    {
        std::vector<std::jthread> pool;
        for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
        worker();
    }
    if (error) std::rethrow_exception(error);
    return std::move(sum.total());
}

}  // namespace smithlab::util
