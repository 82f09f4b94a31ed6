// The data groups to trace as block jobs (cluster/block_jobs.hpp), for one process or MPI ranks: group j's blocks are
// its points, each traced whole from its own stream (fit/data_sets.hpp), and a group's total is its points' moments
// in order: the same bits for any number of ranks and threads.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "cluster/block_jobs.hpp"
#include "cluster/mpi_world.hpp"
#include "fit/data_sets.hpp"
#include "fit/trace_points.hpp"

namespace smithlab::fit {

struct GroupJob {
    const AnyNdf* ndf;
    const Group* group;
    std::uint64_t ndf_index;
    std::string name;    // "ggx, training alpha 0.25 (group 3)", for messages
    bool needed = true;  // rank 0: false for a group read back from the cache
};

class GroupJobs {
public:
    using Partial = std::vector<fit::SplitMoments>;
    using Finish = std::function<void(std::size_t, Partial&&)>;
    GroupJobs(std::vector<GroupJob> jobs, const walk::Material& material, std::uint64_t seed,
              walk::EvalEstimator estimator, Finish finish)
        : jobs_(std::move(jobs)), material_(material), seed_(seed), estimator_(estimator), finish_(std::move(finish)) {}

    std::size_t jobs() const { return jobs_.size(); }
    std::uint64_t blocks(std::size_t j) const { return jobs_[j].needed ? jobs_[j].group->dirs.size() : 0; }
    Partial empty(std::size_t) const { return {}; }
    void merge(Partial& all, const Partial& one) const { all.insert(all.end(), one.begin(), one.end()); }
    std::size_t kind(std::size_t j) const { return j; }  // a group is one alpha: its own microsurface
    std::string name(std::size_t j) const { return jobs_[j].name; }
    void finish(std::size_t j, Partial&& total) { finish_(j, std::move(total)); }

    cluster::Runner<Partial> runner(std::size_t j) const {
        return [surface = make_surface(*jobs_[j].ndf), this](std::size_t job, std::uint64_t k) {
            const Group& g = *jobs_[job].group;
            const TracePoint p{g.dirs[k].wi(), g.dirs[k].wo(), data_stream(g.set, jobs_[job].ndf_index, g.index, k)};
            const Estimator e{g.set == albedo_set, estimator_};
            return Partial{trace_point(*surface, material_, p, e, seed_, g.walks)};
        };
    }

    static_assert(std::is_trivially_copyable_v<fit::SplitMoments>);
    void put(std::vector<char>& out, const Partial& p) const {
        cluster::mpi::put(out, static_cast<std::int64_t>(p.size()));
        for (const fit::SplitMoments& m : p) cluster::mpi::put(out, m);
    }
    Partial get(cluster::mpi::Reader& in, std::size_t j) const {
        Partial p(static_cast<std::size_t>(in.get<std::int64_t>()));
        if (p.size() != 1)
            throw std::runtime_error("fit: another rank sent " + std::to_string(p.size()) + " points for one of " +
                                     name(j));
        for (fit::SplitMoments& m : p) m = in.get<fit::SplitMoments>();
        return p;
    }

private:
    std::vector<GroupJob> jobs_;
    walk::Material material_;
    std::uint64_t seed_;
    walk::EvalEstimator estimator_;
    Finish finish_;
};

}  // namespace smithlab::fit
