#include "fit/fit_data.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <type_traits>
#include <variant>
#include <numbers>
#include <sstream>

#include "cluster/block_jobs.hpp"
#include "cluster/mpi_world.hpp"
#include "output/output_file.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/rng.hpp"

namespace smithlab::fitrun {

namespace fs = std::filesystem;

namespace {

enum Set : std::uint64_t { training_set = 0, validation_set = 1, albedo_set = 2 };
const char* const set_name[] = {"training", "validation", "albedo"};

// One alpha of one set: its points' directions, traced together on one microsurface.
struct Group {
    Set set;
    std::uint64_t index;
    double alpha;
    std::vector<fit::Directions> dirs;
    std::int64_t walks;
};

std::uint64_t stream(Set set, std::uint64_t ndf, std::uint64_t group, std::uint64_t point) {
    return set << 48 | ndf << 32 | group << 16 | point;
}

// theta_i <= theta_o from the axis, every phi (one where either is 0: phi means nothing there).
std::vector<fit::Directions> training_directions(const FitScene::Training& t) {
    std::vector<fit::Directions> d;
    for (std::size_t i = 0; i < t.theta.size(); ++i)
        for (std::size_t o = i; o < t.theta.size(); ++o) {
            if (t.theta[i] == 0.0 || t.theta[o] == 0.0) d.push_back({t.theta[i], t.theta[o], 0.0});
            else
                for (double phi : t.phi) d.push_back({t.theta[i], t.theta[o], phi});
        }
    return d;
}

// n pairs uniform in solid angle up to 85 degrees, phi in [0, 180], from the scene's seed (its own stream).
std::vector<fit::Directions> validation_directions(std::uint64_t seed, std::uint64_t ndf, std::uint64_t group,
                                                   std::int64_t n) {
    const double deg = 180.0 / std::numbers::pi, c_min = std::cos(85.0 / deg);
    WalkRng g(seed, stream(validation_set, ndf, group, 0xffff), 0);
    auto theta = [&] { return std::acos(1.0 - uniform01(g) * (1.0 - c_min)) * deg; };
    std::vector<fit::Directions> d;
    for (std::int64_t k = 0; k < n; ++k) {
        const double ti = theta(), to = theta();
        d.push_back({ti, to, 180.0 * uniform01(g)});
    }
    return d;
}

std::vector<Group> groups(const FitScene& s, std::uint64_t ndf, const std::vector<double>& validation_alphas) {
    std::vector<Group> out;
    const std::vector<fit::Directions> train = training_directions(s.training);
    for (std::size_t a = 0; a < s.training.alpha.size(); ++a)
        out.push_back({training_set, a, s.training.alpha[a], train, s.training.walks});
    for (std::size_t a = 0; a < validation_alphas.size(); ++a) {
        out.push_back({validation_set, a, validation_alphas[a],
                       validation_directions(s.seed, ndf, a, s.validation.points), s.validation.walks});
        std::vector<fit::Directions> alb;
        for (double t : s.validation.albedo_theta) alb.push_back({t, 0.0, 0.0});
        out.push_back({albedo_set, a, validation_alphas[a], alb, s.validation.albedo_walks});
    }
    return out;
}

std::string directory_name(const std::string& label) {
    std::string d = label;
    for (char& c : d)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-')) c = '_';
    return d;
}

std::string group_key(const FitScene& s, const AnyNdf& ndf, const Group& g, std::uint64_t ndf_index) {
    std::ostringstream k;
    k << "smithlab " << SMITHLAB_VERSION << "|ndf=" << ndf.key() << "|material=" << s.material
      << "|set=" << set_name[g.set] << "|walks=" << g.walks << "|seed=" << s.seed
      << "|stream=" << stream(g.set, ndf_index, g.index, 0) << "|points=" << g.dirs.size();
    return k.str();
}

std::vector<std::string> direction_fields(const fit::Directions& d) {
    return {format_g17(d.theta_i), format_g17(d.theta_o), format_g17(d.phi)};
}

// The group's moments from its cache file, if the file is whole and its key and directions are this group's.
std::optional<std::vector<fit::SplitMoments>> read_group(const fs::path& path, const std::string& key, const Group& g) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::vector<CsvRecord> rows;
    try {
        rows = read_csv(in);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (rows.size() != g.dirs.size() + 2 || rows[0].fields != std::vector<std::string>{"key", key}) return std::nullopt;
    for (const CsvRecord& r : rows)
        if (!r.error.empty()) return std::nullopt;
    std::vector<fit::SplitMoments> out(g.dirs.size());
    for (std::size_t j = 0; j < g.dirs.size(); ++j) {
        const std::vector<std::string>& f = rows[j + 2].fields;
        const std::vector<std::string> want = direction_fields(g.dirs[j]);
        if (f.size() < 3 || !std::equal(want.begin(), want.end(), f.begin())) return std::nullopt;
        if (!fit::read_moment_fields(f, 3, out[j]) || out[j].walks != g.walks) return std::nullopt;
    }
    return out;
}

void write_group(const fs::path& path, const std::string& key, const Group& g, const std::vector<fit::SplitMoments>& m) {
    fs::create_directories(path.parent_path());
    output::write_output(output::resolve_output(path.string()), [&](std::ostream& out) {
        write_csv_record(out, {"key", key});
        std::vector<std::string> header{"theta_i", "theta_o", "phi"};
        for (std::string& c : fit::moment_columns()) header.push_back(std::move(c));
        write_csv_record(out, header);
        for (std::size_t j = 0; j < g.dirs.size(); ++j) {
            std::vector<std::string> f = direction_fields(g.dirs[j]);
            for (std::string& x : fit::moment_fields(m[j])) f.push_back(std::move(x));
            write_csv_record(out, f);
        }
    });
}

std::vector<double> midpoints(const std::vector<double>& a) {
    if (a.size() < 2) return a;
    std::vector<double> m;
    for (std::size_t i = 0; i + 1 < a.size(); ++i) m.push_back(std::sqrt(a[i] * a[i + 1]));
    return m;
}

// One point's split moments on a concrete microsurface and facets, by the estimator asked for.
fit::SplitMoments trace_point(const AnySurface& surface, const walk::Material& m, const TracePoint& p,
                              Estimator estimator, std::uint64_t seed, std::int64_t walks) {
    return estimator == Estimator::albedo ? surface.albedo_point(m, p.wi, seed, p.stream, walks)
                                          : surface.eval_point(m, p.wi, p.wo, seed, p.stream, walks);
}

// The groups to trace as block jobs (cluster/block_jobs.hpp), for one process or MPI ranks: group j's blocks are its
// points, each traced whole (fit::trace_eval_point, trace_albedo_point) from its own stream, and a group's total is
// its points' moments in order: the same bits for any number of ranks and threads.
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
    GroupJobs(std::vector<GroupJob> jobs, const walk::Material& material, std::uint64_t seed, Finish finish)
        : jobs_(std::move(jobs)), material_(material), seed_(seed), finish_(std::move(finish)) {}

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
            const TracePoint p{g.dirs[k].wi(), g.dirs[k].wo(), stream(g.set, jobs_[job].ndf_index, g.index, k)};
            const Estimator e = g.set == albedo_set ? Estimator::albedo : Estimator::eval;
            return Partial{trace_point(*surface, material_, p, e, seed_, g.walks)};
        };
    }

    static_assert(std::is_trivially_copyable_v<fit::SplitMoments>);
    void put(std::vector<char>& out, const Partial& p) const {
        mpi::put(out, static_cast<std::int64_t>(p.size()));
        for (const fit::SplitMoments& m : p) mpi::put(out, m);
    }
    Partial get(mpi::Reader& in, std::size_t j) const {
        Partial p(static_cast<std::size_t>(in.get<std::int64_t>()));
        if (p.size() != 1) throw std::runtime_error("fit: another rank sent " + std::to_string(p.size()) + " points for one of " + name(j));
        for (fit::SplitMoments& m : p) m = in.get<fit::SplitMoments>();
        return p;
    }

private:
    std::vector<GroupJob> jobs_;
    walk::Material material_;
    std::uint64_t seed_;
    Finish finish_;
};

}  // namespace

std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<TracePoint>& points, Estimator estimator,
                                            std::uint64_t seed, std::int64_t walks, unsigned threads,
                                            const std::function<void(std::uint64_t)>& done) {
    const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
    return util::reduce_blocks(
        points.size(), threads, std::vector<fit::SplitMoments>{},
        [&](std::uint64_t j) {
            return std::vector<fit::SplitMoments>{trace_point(*surface, material, points[j], estimator, seed, walks)};
        },
        [](std::vector<fit::SplitMoments>& all, const std::vector<fit::SplitMoments>& one) {
            all.insert(all.end(), one.begin(), one.end());
        },
        [&](std::uint64_t k) {
            if (done) done(k);
        });
}

AnyNdf make_ndf(const NdfRegistry& registry, const FitFamily& f, double alpha) {
    return report::make_entry_ndf(f.entry, registry, f.params, alpha);
}

std::vector<NdfData> gather(const FitScene& s, const NdfRegistry& registry, const fs::path& cache, unsigned threads,
                            const ProgressFn& progress, const std::function<void()>& checked,
                            cluster::Traffic* traffic) {
    const walk::Material material = walk::parse_material(s.material);
    struct Plan {
        NdfData data;
        std::vector<Group> groups;
        std::vector<AnyNdf> ndfs;  // per group
    };
    std::vector<Plan> plans;
    for (std::size_t n = 0; n < s.ndfs.size(); ++n) {
        Plan p;
        p.data.family = s.ndfs[n];
        p.data.label = family_label(s.ndfs[n]);
        p.data.validation_alphas = midpoints(s.training.alpha);
        p.groups = groups(s, n, p.data.validation_alphas);
        for (const Group& g : p.groups) {
            p.ndfs.push_back(make_ndf(registry, p.data.family, g.alpha));
            // A D-only NDF's tables are built here once, and may refuse the NDF: before anything is traced.
            make_surface(p.ndfs.back());
        }
        plans.push_back(std::move(p));
    }
    if (checked) checked();

    // Every group of every NDF, in order; rank 0 reads back what the cache holds and writes each group traced.
    struct Place {
        std::size_t n, i;
        std::string key;
        fs::path file;
    };
    std::vector<Place> places;
    std::vector<GroupJob> jobs;
    std::vector<std::optional<std::vector<fit::SplitMoments>>> moments;
    for (std::size_t n = 0; n < plans.size(); ++n)
        for (std::size_t i = 0; i < plans[n].groups.size(); ++i) {
            const Group& g = plans[n].groups[i];
            const std::string key = group_key(s, plans[n].ndfs[i], g, n);
            const fs::path file = cache / directory_name(plans[n].data.label) /
                                  (std::string(set_name[g.set]) + "-" + std::to_string(g.index) + ".csv");
            moments.push_back(mpi::rank() == 0 ? read_group(file, key, g) : std::nullopt);
            jobs.push_back({&plans[n].ndfs[i], &g, n,
                            plans[n].data.label + ", " + set_name[g.set] + " alpha " + format_shortest(g.alpha) +
                                " (group " + std::to_string(g.index) + ")",
                            mpi::rank() == 0 && !moments.back()});
            places.push_back({n, i, key, file});
        }
    GroupJobs plan(std::move(jobs), material, s.seed, [&](std::size_t j, std::vector<fit::SplitMoments>&& total) {
        const Place& at = places[j];
        write_group(at.file, at.key, plans[at.n].groups[at.i], total);
        plans[at.n].data.traced += static_cast<std::int64_t>(total.size());
        plans[at.n].data.walks_traced += static_cast<std::int64_t>(total.size()) * plans[at.n].groups[at.i].walks;
        moments[j] = std::move(total);
    });
    const cluster::Traffic t = cluster::run_jobs(plan, threads, [&](std::uint64_t merged, std::uint64_t all) {
        if (progress) progress(static_cast<std::int64_t>(merged), static_cast<std::int64_t>(all));
    });
    if (traffic) *traffic = t;
    if (mpi::rank() != 0) return {};

    for (std::size_t j = 0; j < places.size(); ++j) {
        Plan& p = plans[places[j].n];
        const Group& g = p.groups[places[j].i];
        if (plan.blocks(j) == 0) p.data.reused += static_cast<std::int64_t>(g.dirs.size());
        std::vector<fit::DataPoint>& dest = g.set == training_set     ? p.data.training
                                            : g.set == validation_set ? p.data.validation
                                                                      : p.data.albedo;
        for (std::size_t k = 0; k < g.dirs.size(); ++k) dest.push_back({g.alpha, g.dirs[k], (*moments[j])[k]});
    }
    std::vector<NdfData> out;
    for (Plan& p : plans) out.push_back(std::move(p.data));
    return out;
}

}  // namespace smithlab::fitrun
