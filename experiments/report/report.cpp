#include "report/report.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "report/figures.hpp"
#include "report/g1_table.hpp"
#include "report/g2_table.hpp"
#include "report/references.hpp"
#include "report/sampling_experiment.hpp"
#include "smithlab/errors.hpp"
#include "output/staged_directory.hpp"
#include "report/timing.hpp"
#include "cluster/mpi_world.hpp"
#include "report/walk_section.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

std::string machine() {
    std::ifstream cpu("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(cpu, line))
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return model;
}

void require_positive_axis(const std::vector<double>& mus, const char* key) {
    for (double mu : mus) require(mu > 0.0 && std::isfinite(mu), key, "finite and > 0", mu);
}

// The sections whose keys and domains are checked before anything is computed (sampling checks its own).
struct Checked {
    G1Table g1;
    G2Table g2;
    std::vector<WalkCell> walk;  // empty without [walk]
};

Checked checked_sections(const Scene& scene, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    G1Table g1 = g1_table(scene, ndfs, variants);
    require_positive_axis(scene.mus, "scene: grid.mu");
    require_positive_axis(scene.g2.mus, "scene: g2.mu");
    require_g1_domain(g1, scene.mus);
    G2Table g2 = g2_table(scene, ndfs);
    return {std::move(g1), std::move(g2), walk_cells(scene.walk, ndfs)};
}

// The sampling experiment validates its keys before it computes anything. None without [sampling].
std::vector<SamplingRow> sampling_rows(const Scene& scene, const NdfRegistry& ndfs) {
    if (scene.sampling.families.empty()) return {};
    std::fprintf(stderr, "report: sampling experiment, %zu x %zu estimates of %zu samples\n",
                 scene.sampling.families.size() * scene.sampling.alphas.size(), sampling_strategies.size(),
                 scene.sampling.samples);
    return run_sampling_experiment(scene.sampling, ndfs);
}

struct Walks {
    std::vector<WalkResult> results;
    double seconds = 0.0;
};

Walks traced_walks(const std::vector<WalkCell>& cells, const Scene::Walk& walk) {
    if (cells.empty()) return {};
    if (mpi::rank() == 0) std::fprintf(stderr, "report: walk section, %zu cells of %lld walks\n", cells.size(), static_cast<long long>(walk.walks));
    const auto t0 = std::chrono::steady_clock::now();
    Walks w{.results = trace_walk_cells(cells, walk)};
    w.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return w;
}

// The G1 and G2 tables against the references, read from and saved to the cache.
void measure_sections(Checked& s, const Scene& scene, const fs::path& cache_file) {
    ReferenceCache cache(cache_file);
    measure_g1(s.g1, scene.mus, cache, scene.figures.error_maps || scene.figures.pareto);
    measure_g2(s.g2, scene.g2.mus, cache);
    cache.save();
    std::fprintf(stderr, "report: references: %zu reused from the cache, %zu computed", cache.loaded(), cache.computed());
    if (cache.discarded()) std::fprintf(stderr, " (%zu damaged cache records discarded)", cache.discarded());
    std::fprintf(stderr, "\n");
}

void time_sections(Checked& s, std::vector<SamplingRow>& sampling, const Scene& scene, const fs::path& dir) {
    std::vector<Timed> timed;
    add_g1_timing(s.g1, timed);
    add_g2_timing(s.g2, timed);
    add_sampling_timing(sampling, scene.sampling, timed);
    std::fprintf(stderr, "report: timing %zu variants and estimators with Google Benchmark\n", timed.size());
    time_all(timed, scene.min_time, dir / "bench.json");
}

// DIR/report.md begun: the title, the machine, the compiler and the date.
void write_head(const Scene& scene, const fs::path& dir) {
    std::ofstream md(dir / "report.md");
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "# " << scene.title << "\n\n"
       << "Machine: " << machine() << ", one core; compiler " << __VERSION__ << ", flags `" << SMITHLAB_BUILD_FLAGS
       << "`; " << date << ".\n\n";
}

}  // namespace

int run_report(const Scene& scene, const std::string& out_dir, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    // Validate everything before computing or writing anything.
    output::require_output_directory(out_dir);
    Checked sections = checked_sections(scene, ndfs, variants);
    // Under MPI every rank has checked the scene alike; the ranks trace the walk section together, rank 0 alone does
    // the rest (the other ranks wait meanwhile, asleep).
    if (mpi::size() > 1) mpi::set_talking();
    std::vector<SamplingRow> sampling = mpi::rank() == 0 ? sampling_rows(scene, ndfs) : std::vector<SamplingRow>{};
    const Walks walks = traced_walks(sections.walk, scene.walk);
    if (mpi::rank() != 0) return 0;

    // Everything but the cache is written to a stage and moved into out_dir when complete (staged_directory.hpp).
    output::StagedDirectory staged(out_dir, "report");
    const fs::path& dir = staged.path();
    measure_sections(sections, scene, fs::path(out_dir) / "cache" / "references.csv");
    time_sections(sections, sampling, scene, dir);

    write_head(scene, dir);
    write_g1_table(sections.g1, scene, dir);
    write_g2_table(sections.g2, dir);
    if (!sampling.empty()) write_sampling_section(sampling, scene.sampling, dir);
    if (!walks.results.empty()) write_walk_section(walks.results, scene.walk, walks.seconds, dir);
    if (scene.figures.error_maps || scene.figures.pareto) write_g1_points(sections.g1, dir);
    write_figures(scene, dir);
    staged.publish();
    std::fprintf(stderr, "report: wrote %s/report.md and its data\n", out_dir.c_str());
    return 0;
}

}  // namespace smithlab::report
