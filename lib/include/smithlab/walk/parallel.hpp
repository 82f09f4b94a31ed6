// smithlab/walk/parallel.hpp -- a cell's walks in fixed blocks over threads, reduced in block order.
//
// Block b is a pure function of b (its walks draw from WalkRng(seed, cell, walk)), and the partial sums are merged in
// the order 0, 1, 2, ... whatever thread finished first, so the result is the same bits for any number of threads.
// Memory: a partial result waits only until every block before it is merged.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace smithlab::walk {

// run(b) -> Partial for b in [0, blocks), on `threads` threads (0: all cores); merge(total, partial) in block order;
// progress(merged_blocks) after each merge. The first exception a block throws is rethrown here.
template <class Partial, class Run, class Merge, class Progress>
Partial reduce_blocks(std::uint64_t blocks, unsigned threads, Partial total, Run run, Merge merge, Progress progress) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    threads = static_cast<unsigned>(std::min<std::uint64_t>(threads, std::max<std::uint64_t>(blocks, 1)));
    std::atomic<std::uint64_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex lock;
    std::map<std::uint64_t, Partial> pending;
    std::uint64_t merged = 0;
    std::exception_ptr error;
    auto worker = [&] {
        try {
            for (std::uint64_t b; !failed && (b = next.fetch_add(1)) < blocks;) {
                Partial p = run(b);
                const std::lock_guard guard(lock);
                pending.emplace(b, std::move(p));
                for (auto it = pending.begin(); it != pending.end() && it->first == merged; it = pending.erase(it)) {
                    merge(total, it->second);
                    progress(++merged);
                }
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
    return total;
}

}  // namespace smithlab::walk
