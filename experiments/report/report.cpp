#include "report/report.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "cluster/mpi_world.hpp"
#include "output/plot_script.hpp"
#include "output/staged_directory.hpp"

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

// Every section against the references, read from and saved to the cache.
void measure_sections(Scene& scene, const fs::path& cache_file) {
    ReferenceCache cache(cache_file);
    for (auto& section : scene.sections) section->measure(cache);
    cache.save();
    std::fprintf(stderr, "report: references: %zu reused from the cache, %zu computed", cache.loaded(),
                 cache.computed());
    if (cache.discarded()) std::fprintf(stderr, " (%zu damaged cache records discarded)", cache.discarded());
    std::fprintf(stderr, "\n");
}

// Every section's items in one Google Benchmark run.
void time_sections(Scene& scene, const fs::path& dir) {
    Timing timing;
    for (auto& section : scene.sections) section->add_timing(timing);
    std::fprintf(stderr, "report: timing %zu variants and estimators with Google Benchmark\n", timing.size());
    timing.run(scene.settings.min_time, dir / "bench.json");
}

// DIR/report.md begun: the title, the machine, the compiler and the date.
void write_head(const Settings& settings, const fs::path& dir) {
    std::ofstream md(dir / "report.md", std::ios::binary);
    const std::time_t now = std::time(nullptr);
    char date[32];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    md << "# " << settings.title << "\n\n"
       << "Machine: " << machine() << ", one core; compiler " << __VERSION__ << ", flags `" << SMITHLAB_BUILD_FLAGS
       << "`; " << date << ".\n\n";
    output::finish(md, dir / "report.md");
}

// report_plots.py over the files written, when any section has a figure; a note in report.md when it fails.
void draw_figures(const Scene& scene, const fs::path& dir) {
    bool any = false;
    for (const auto& section : scene.sections) any = any || section->draws(scene.settings);
    if (!any) return;
    const auto t0 = std::chrono::steady_clock::now();
    const bool drawn = output::run_plot_script("report_plots.py", SMITHLAB_PLOT_SCRIPT, dir, "report");
    std::fprintf(stderr, "report: figures %s in %.1f s\n", drawn ? "drawn" : "not drawn",
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!drawn) {
        std::ofstream md(dir / "report.md", std::ios::binary | std::ios::app);
        md << "\n**The figures were not drawn** (python3 has no matplotlib); their data is beside this file.\n";
        output::finish(md, dir / "report.md");
    }
}

// Rank 0, after every section computed: the references, the timing, and the files, staged and then published.
void write_report(Scene& scene, const std::string& out_dir) {
    // Everything but the cache is written to a stage and moved into out_dir when complete (staged_directory.hpp).
    output::StagedDirectory staged(out_dir, "report");
    const fs::path& dir = staged.path();
    measure_sections(scene, fs::path(out_dir) / "cache" / "references.csv");
    time_sections(scene, dir);
    write_head(scene.settings, dir);
    for (auto& section : scene.sections) section->write(dir, scene.settings);
    draw_figures(scene, dir);
    staged.publish();
    std::fprintf(stderr, "report: wrote %s/report.md and its data\n", out_dir.c_str());
}

}  // namespace

int run_report(Scene& scene, const std::string& out_dir, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    // Validate everything before computing or writing anything.
    output::require_output_directory(out_dir);
    for (auto& section : scene.sections) section->check(scene.settings, ndfs, variants);
    // Under MPI every rank has checked the scene alike; the ranks compute the sections that run on all ranks (the
    // walk) together, rank 0 alone does the rest (the other ranks wait meanwhile, asleep).
    if (cluster::mpi::size() > 1) cluster::mpi::set_talking();
    for (auto& section : scene.sections)
        if (cluster::mpi::rank() == 0 || section->on_all_ranks()) section->compute();
    if (cluster::mpi::rank() != 0) return 0;
    write_report(scene, out_dir);
    return 0;
}

}  // namespace smithlab::report
