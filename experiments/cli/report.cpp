// smithlab report: the error-against-run-time report of the Lambda variants (and the sampling experiment), from a
// scene file.
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "report.hpp"
#include "scene.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::cli {

void add_report(CLI::App& app, ReportArgs& a) {
    CLI::App* c = app.add_subcommand(
        "report", "Measure every Lambda variant's error and cost on one grid, and the samplers' efficiency");
    c->footer(
        "Runs the scene (TOML; default: the embedded experiments/scenes/g1_report.toml, see --print-scene):\n"
        "every selected variant on the grid against an independent reference, timed with Google Benchmark;\n"
        "with [g2], the G2 approximations; with [sampling], the sampling-efficiency experiment (cosine, D cos and\n"
        "visible-normal sampling of a conductor's albedo); the figures named in [figures].\n"
        "Writes OUT/report.md, OUT/variants.csv, OUT/bench.json (and g2_variants.csv, sampling.csv, *.png);\n"
        "references are cached in OUT/cache and reused when the same scene runs again. Only what the scene names\n"
        "is computed; a malformed scene is an error naming the key, exit 2, and nothing is written.\n"
        "Examples:\n"
        "  smithlab report\n"
        "  smithlab report --scene my_scene.toml --out my_report");
    c->add_option("--scene", a.scene, "scene file (TOML)");
    c->add_option("--out", a.out, "output directory")->capture_default_str();
    c->add_flag("--print-scene", a.print_scene, "print the default scene and exit");
}

int run_report(const ReportArgs& a, const NdfRegistry& registry, const VariantRegistry& variants) {
    if (a.print_scene) {
        std::cout << report::default_scene_text();
        return exit_ok;
    }
    std::string text = report::default_scene_text(), source = "<default scene>";
    if (!a.scene.empty()) {
        std::ifstream in(a.scene);
        if (!in) throw input_error("cannot open scene file '" + a.scene + "'");
        std::stringstream ss;
        ss << in.rdbuf();
        text = ss.str();
        source = a.scene;
    }
    return report::run_report(report::parse_scene(text, source), a.out, registry, variants);
}

}  // namespace smithlab::cli
