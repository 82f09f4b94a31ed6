// smithlab report: the error-against-run-time report of the Lambda variants (and the sampling experiment), from a
// scene file.
#include <cstdio>
#include <iostream>

#include "cli/commands.hpp"
#include "cluster/mpi_world.hpp"
#include "report/report.hpp"
#include "report/scene.hpp"
#include "report/work_estimate.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

void add_report(CLI::App& app, ReportArgs& a) {
    CLI::App* c = app.add_subcommand(
        "report", "Measure every Lambda variant's error and cost on one grid, and the samplers' efficiency");
    c->footer(
        "Runs the scene (TOML; default: the embedded experiments/scenes/g1_report.toml, see --print-scene):\n"
        "every selected variant on the grid against an independent reference, timed with Google Benchmark;\n"
        "with [g2], the G2 approximations; with [sampling], the sampling-efficiency experiment (cosine, D cos and\n"
        "visible-normal sampling of a conductor's albedo); with [walk], the Smith microsurface path-traced: albedo\n"
        "by scattering order against alpha and what single scattering loses; the figures named in [figures].\n"
        "Writes into DIR (-o, default report/): report.md, variants.csv, bench.json (and g2_variants.csv,\n"
        "sampling.csv, walk_albedo.csv, *.png); references are cached in DIR/cache and reused when the same scene\n"
        "runs again. Only what the scene names is computed.\n"
        "The scene is read strictly: an unknown key or section (the nearest known one is suggested), a value of the\n"
        "wrong type (an integer is taken where a real is meant), an integer out of bounds is an error naming the key\n"
        "and FILE:LINE, exit 2, and nothing is written.\n"
        "Before computing, the work is estimated in evaluations (Lambda evaluations: selected variants x NDFs x mu;\n"
        "G2 evaluations; reference Lambdas; samples of the sampling experiment; walks, each counted alpha times above\n"
        "alpha = 1); a scene above --max-work is refused\n"
        "with the estimate, exit 2. The default scene is about 1.2e7.\n"
        "Examples:\n"
        "  smithlab report\n"
        "  smithlab report my_scene.toml -o my_report\n"
        "  smithlab report big.toml --max-work 1e9");
    add_scene_options(*c, a.scene, a.print_scene, a.scale, "the embedded default");
    add_output_option(*c, a.output, "output directory")->capture_default_str();
    a.max_work = report::default_max_work;
    c->add_option("--max-work", a.max_work, "the most evaluations a scene may cost (inf: no limit)")
        ->capture_default_str();
}

int run_report(const ReportArgs& a, const NdfRegistry& registry, const VariantRegistry& variants) {
    if (a.print_scene) {
        std::cout << report::default_scene_text();
        return exit_ok;
    }
    require(a.max_work > 0.0, "--max-work", "> 0 (inf: no limit)", a.max_work);
    require_scale(a.scale);
    const std::string source = a.scene.empty() ? "<default scene>" : a.scene;
    report::Scene scene = report::parse_scene(a.scene.empty() ? report::default_scene_text() : read_scene_file(a.scene),
                                              source, registry, a.scale);
    const report::Work work = report::estimate_work(scene, variants);
    report::check_work(work, a.max_work, source);
    if (cluster::mpi::rank() == 0)
        std::fprintf(stderr, "report: work estimated at %s (limit --max-work %g)\n", report::describe(work).c_str(),
                     a.max_work);
    return report::run_report(scene, a.output, registry, variants);  // under mpirun, every rank (rank 0 reports)
}

}  // namespace smithlab::cli
