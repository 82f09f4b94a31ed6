// cluster/ledger.hpp -- which chunks each other rank holds, for the note rank 0 prints when a signal ends the run
// (mpirun sends SIGTERM when a rank died; its own message names that rank).
#pragma once

#include <algorithm>
#include <mutex>
#include <string>
#include <vector>

#include "cluster/protocol.hpp"

namespace smithlab::cluster::detail {

class Ledger {
public:
    explicit Ledger(int ranks) : held_(static_cast<std::size_t>(ranks)) {}

    // Rank r sent back the chunk `back` (count 0: none) and was handed `out` (count 0: none).
    void update(int r, const Chunk& back, const Chunk& out) {
        const std::lock_guard guard(lock_);
        std::vector<Chunk>& h = held_[static_cast<std::size_t>(r)];
        if (back.count > 0)
            std::erase_if(h, [&](const Chunk& d) { return d.job == back.job && d.first == back.first; });
        if (out.count > 0) h.push_back(out);
    }

    // "rank 2 held cell 12 (ggx(alpha=0.3), mirror, theta_i 45), blocks 8-15", one line per chunk held.
    template <class Plan>
    std::string note(const Plan& plan) {
        const std::lock_guard guard(lock_);
        std::string text = "smithlab: stopped by a signal (mpirun sends one when a rank dies, and names it)";
        for (std::size_t r = 1; r < held_.size(); ++r)
            for (const Chunk& c : held_[r])
                text += "\n  rank " + std::to_string(r) + " held " + plan.name(c.job) + ", " + block_range(c);
        return text + "\n  the jobs finished so far are kept: the same command resumes from them";
    }

private:
    std::mutex lock_;
    std::vector<std::vector<Chunk>> held_;  // per rank
};

}  // namespace smithlab::cluster::detail
