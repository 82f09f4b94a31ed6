#include "fit/fit_run.hpp"

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "cluster/mpi_world.hpp"
#include "cluster/traffic_json.hpp"
#include "compensation/stage.hpp"
#include "fit/fit_data.hpp"
#include "fit/fit_flags.hpp"
#include "fit/fit_models.hpp"
#include "fit/fit_pictures.hpp"
#include "fit/fit_report.hpp"
#include "fit/fit_shaders.hpp"
#include "fit/fit_tables.hpp"
#include "fit/fit_trends.hpp"
#include "fit/label_columns.hpp"
#include "output/progress.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/util/parallel.hpp"
#include "trace/capped_walks.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Every model fitted to and measured on every NDF's data (the models on `threads` threads at once): r.fits, the rows of
// errors.csv, and the flags.
std::vector<Flag> fit_all(const FitScene& s, Results& r, std::vector<ErrorRow>& errors, unsigned threads) {
    const FitSettings settings{s.albedos, s.floor, s.training.alpha, s.energy_bound, threads};
    const FitProgress progress{};
    std::vector<Flag> flags;
    for (const NdfData& d : r.data) {
        NdfFits f = fit_and_measure(d, s.models, settings, progress);
        r.fits.push_back(std::move(f.models));
        errors.insert(errors.end(), f.errors.begin(), f.errors.end());
        flags.insert(flags.end(), f.flags.begin(), f.flags.end());
    }
    return flags;
}

void print_trace_line(const std::vector<NdfData>& data, double seconds, unsigned threads) {
    std::int64_t points = 0, walks = 0, reused = 0;
    for (const NdfData& d : data) points += d.traced, walks += d.walks_traced, reused += d.reused;
    if (reused) std::fprintf(stderr, "fit: %lld points read from the cache\n", static_cast<long long>(reused));
    if (points)
        std::fprintf(stderr,
                     "fit: traced %lld points, %.4g walks, in %.1f s (%.0f ns a walk on %u threads x %d ranks)\n",
                     static_cast<long long>(points), static_cast<double>(walks), seconds,
                     seconds / static_cast<double>(walks) * 1e9, util::thread_count(threads), cluster::mpi::size());
}

// Says on stderr how many of the walks traced were cut short (trace/capped_walks.hpp): their energy is missing from
// the points' values (the fitter's alpha <= 1 keeps walks far below the cap).
void print_capped(const std::vector<NdfData>& data) {
    std::int64_t capped = 0, walks = 0;
    for (const NdfData& d : data) {
        walks += d.walks_traced;
        for (const auto* set : {&d.training, &d.validation, &d.albedo})
            for (const fit::DataPoint& p : *set) capped += p.moments.capped;
    }
    if (capped > 0)
        std::fprintf(stderr, "fit: warning: %s: the points' values miss the energy they would have carried\n",
                     trace::capped_text(capped, walks).c_str());
}

// Every output but meta.json into dir.
void write_outputs(const fs::path& dir, const FitScene& s, const Results& r, const std::vector<ErrorRow>& errors,
                   const std::vector<Flag>& flags, const NdfRegistry& registry, unsigned threads,
                   const fs::path& cache) {
    const LabelColumns columns = label_columns(r.data, registry, s.training.alpha.front());
    write_constants(dir, r, columns);
    write_errors(dir, errors, columns);
    write_values(dir / "training.csv", r, ValueSet::training, s.albedos, columns);
    write_values(dir / "validation.csv", r, ValueSet::validation, s.albedos, columns);
    write_shaders(dir, r);
    const std::string compensation =
        compensation::run_compensation(dir, s.ndfs, s.compensation, registry, {"fit", s.seed, threads}).markdown;
    const std::string pictures =
        write_pictures(dir, cache, {s.pictures, s.material, s.seed, s.estimator}, r, columns, registry, threads);
    const std::string trends = write_parameter_trends(dir, r);
    write_report(dir, {s.title, s.material, s.albedos, s.floor}, r, errors, flags_markdown(flags),
                 trends + compensation + pictures);
}

void write_meta(const fs::path& dir, const FitScene& s, const std::string& source, const std::string& scene_text,
                const FitSummary& sum, const std::vector<NdfData>& data, double trace_seconds, unsigned threads,
                const cluster::Traffic& traffic) {
    std::int64_t walks = 0;
    for (const NdfData& d : data) walks += d.walks_traced;
    nlohmann::ordered_json meta = {{"title", s.title},
                                   {"source", source},
                                   {"scene", scene_text},
                                   {"version", SMITHLAB_VERSION},
                                   {"seed", s.seed},
                                   {"points_traced", sum.traced},
                                   {"points_reused", sum.reused},
                                   {"walks_traced", walks},
                                   {"seconds", sum.seconds},
                                   {"trace_seconds", trace_seconds},
                                   {"threads", util::thread_count(threads)}};
    if (cluster::mpi::size() > 1) meta["mpi"] = cluster::traffic_json(traffic);  // and threads is per rank
    output::write_file(dir / "meta.json", meta.dump(2) + "\n");
}

}  // namespace

FitSummary run_fit(const FitScene& s, const std::string& source, const std::string& scene_text,
                   const NdfRegistry& registry, const fs::path& out, unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<output::StagedDirectory> stage;
    output::ProgressLine line;
    auto progress = [&](std::int64_t done, std::int64_t total) {
        line(static_cast<double>(done) / static_cast<double>(total),
             [&] { return "fit: traced " + std::to_string(done) + " of " + std::to_string(total) + " points"; });
    };
    // Under MPI every rank checks the scene's NDFs alike, then the ranks trace together; rank 0 alone owns OUT, and
    // fits, measures and draws (the pictures' few traces on its threads) while the others are done.
    cluster::Traffic traffic;
    Results r{gather(
                  data_spec(s), registry, out / "cache", threads, progress,
                  [&] {
                      if (cluster::mpi::size() > 1) cluster::mpi::set_talking();
                      if (cluster::mpi::rank() == 0) stage.emplace(out, "fit");  // refuses a bad OUT before any work
                  },
                  &traffic),
              {}};
    if (cluster::mpi::rank() != 0) return {};
    const double trace_seconds = seconds_since(t0);
    print_trace_line(r.data, trace_seconds, threads);
    print_capped(r.data);
    FitSummary sum;
    for (const NdfData& d : r.data) sum.traced += d.traced, sum.reused += d.reused;
    sum.points = sum.traced + sum.reused;
    const std::vector<Flag> flags = fit_all(s, r, sum.errors, threads);
    print_flags(flags);
    write_outputs(stage->path(), s, r, sum.errors, flags, registry, threads, out / "cache");
    sum.seconds = seconds_since(t0);
    write_meta(stage->path(), s, source, scene_text, sum, r.data, trace_seconds, threads, traffic);
    stage->publish();
    return sum;
}

}  // namespace smithlab::fit
