#include "fit/fit_data.hpp"

#include <optional>

#include "cluster/mpi_world.hpp"
#include "fit/data_sets.hpp"
#include "fit/group_jobs.hpp"
#include "fit/point_cache.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

// One NDF family's groups, and its NDF at each group's alpha.
struct Plan {
    NdfData data;
    std::vector<Group> groups;
    std::vector<AnyNdf> ndfs;  // per group
};

// Every family's groups and NDFs, each microsurface built once here: a D-only NDF's tables may refuse the NDF, and
// do so before anything is traced.
std::vector<Plan> plan_ndfs(const DataSpec& s, const NdfRegistry& registry) {
    std::vector<Plan> plans;
    for (std::size_t n = 0; n < s.ndfs.size(); ++n) {
        Plan p;
        p.data.family = s.ndfs[n];
        p.data.label = family_label(s.ndfs[n]);
        p.data.validation_alphas = midpoints(s.training.alpha);
        p.groups = data_groups(s.training, s.validation, s.seed, n, p.data.validation_alphas);
        for (const Group& g : p.groups) {
            p.ndfs.push_back(make_ndf(registry, p.data.family, g.alpha));
            make_surface(p.ndfs.back());
        }
        plans.push_back(std::move(p));
    }
    return plans;
}

// A group's cache file: OUT/cache/NDF/SET-G.csv, its points' fields their directions.
CacheFile group_file(const DataSpec& s, const fs::path& cache, const Plan& p, std::size_t i, std::uint64_t n) {
    const Group& g = p.groups[i];
    CacheFile f{cache / cache_directory_name(p.data.label) /
                    (std::string(set_name(g.set)) + "-" + std::to_string(g.index) + ".csv"),
                cache_key(p.ndfs[i], s.material, set_name(g.set), g.walks, s.seed, data_stream(g.set, n, g.index, 0),
                          g.dirs.size(), s.estimator),
                {"theta_i", "theta_o", "phi"},
                {},
                g.walks};
    for (const fit::Directions& d : g.dirs)
        f.points.push_back({format_g17(d.theta_i), format_g17(d.theta_o), format_g17(d.phi)});
    return f;
}

// Every group of every NDF, in order: its place in the plans, its cache file and (rank 0) what the cache holds.
struct Place {
    std::size_t n, i;
    CacheFile file;
    std::optional<std::vector<fit::SplitMoments>> moments;
};

std::vector<Place> places(const DataSpec& s, const fs::path& cache, const std::vector<Plan>& plans) {
    std::vector<Place> out;
    for (std::size_t n = 0; n < plans.size(); ++n)
        for (std::size_t i = 0; i < plans[n].groups.size(); ++i) {
            Place p{n, i, group_file(s, cache, plans[n], i, n), std::nullopt};
            if (cluster::mpi::rank() == 0) p.moments = read_cache(p.file);
            out.push_back(std::move(p));
        }
    return out;
}

std::vector<GroupJob> group_jobs(const std::vector<Plan>& plans, const std::vector<Place>& at) {
    std::vector<GroupJob> jobs;
    for (const Place& p : at) {
        const Group& g = plans[p.n].groups[p.i];
        jobs.push_back({&plans[p.n].ndfs[p.i], &g, p.n,
                        plans[p.n].data.label + ", " + set_name(g.set) + " alpha " + format_shortest(g.alpha) +
                            " (group " + std::to_string(g.index) + ")",
                        cluster::mpi::rank() == 0 && !p.moments});
    }
    return jobs;
}

// Rank 0: the groups' points into their NDF's sets, in order, and what was reused.
std::vector<NdfData> assemble(std::vector<Plan>& plans, const std::vector<Place>& at, const std::vector<bool>& traced) {
    for (std::size_t j = 0; j < at.size(); ++j) {
        Plan& p = plans[at[j].n];
        const Group& g = p.groups[at[j].i];
        if (!traced[j]) p.data.reused += static_cast<std::int64_t>(g.dirs.size());
        std::vector<fit::DataPoint>& dest = g.set == training_set ? p.data.training
            : g.set == validation_set                             ? p.data.validation
                                                                  : p.data.albedo;
        for (std::size_t k = 0; k < g.dirs.size(); ++k) dest.push_back({g.alpha, g.dirs[k], (*at[j].moments)[k]});
    }
    std::vector<NdfData> out;
    for (Plan& p : plans) out.push_back(std::move(p.data));
    return out;
}

}  // namespace

DataSpec data_spec(const FitScene& s) { return {s.material, s.ndfs, s.training, s.validation, s.seed, s.estimator}; }

std::vector<NdfData> gather(const DataSpec& s, const NdfRegistry& registry, const fs::path& cache, unsigned threads,
                            const ProgressFn& progress, const std::function<void()>& checked,
                            cluster::Traffic* traffic) {
    const walk::Material material = registry.materials().make(s.material);
    std::vector<Plan> plans = plan_ndfs(s, registry);
    if (checked) checked();
    std::vector<Place> at = places(s, cache, plans);
    std::vector<bool> traced(at.size(), false);
    GroupJobs jobs(group_jobs(plans, at), material, s.seed, s.estimator,
                   [&](std::size_t j, std::vector<fit::SplitMoments>&& total) {
                       Plan& p = plans[at[j].n];
                       write_cache(at[j].file, total);
                       p.data.traced += static_cast<std::int64_t>(total.size());
                       p.data.walks_traced += static_cast<std::int64_t>(total.size()) * p.groups[at[j].i].walks;
                       at[j].moments = std::move(total);
                       traced[j] = true;
                   });
    const cluster::Traffic t = cluster::run_jobs(jobs, threads, [&](std::uint64_t merged, std::uint64_t all) {
        if (progress) progress(static_cast<std::int64_t>(merged), static_cast<std::int64_t>(all));
    });
    if (traffic) *traffic = t;
    if (cluster::mpi::rank() != 0) return {};
    return assemble(plans, at, traced);
}

}  // namespace smithlab::fit
