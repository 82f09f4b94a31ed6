// cluster/runner_cache.hpp -- a plan's runner (job, block) -> partial, built once per kind of job on each rank.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>

namespace smithlab::cluster {

template <class Partial>
using Runner = std::function<Partial(std::size_t job, std::uint64_t block)>;

namespace detail {

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

}  // namespace detail

}  // namespace smithlab::cluster
