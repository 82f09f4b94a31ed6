// The `smithlab` subcommands. Each returns the process exit code: 0 fine, 1 a check failed, 2 bad input; main()
// answers 3 for an internal error (a bug on an accepted input: please report it), never 1.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "evaluation/route.hpp"
#include "scene/limits.hpp"
#include "smithlab/fit/diffuse_registry.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/smith.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::cli {

constexpr int exit_ok = 0, exit_failed = 1, exit_bad_input = 2, exit_internal = 3;

struct EvalArgs {
    std::string ndf, input, output;
    // The points, as text so that "inf" and "nan" reach our own validation: one of mu, theta (degrees), a range of
    // either (eval_points.hpp), or the input file above.
    std::string mu, theta, mu_range, theta_range;
    evaluation::RouteOptions route;  // --method, --backend, --tolerance, --downward
    bool list_methods = false;
};
void add_eval(CLI::App& app, EvalArgs& args);
int run_eval(const EvalArgs& args, const NdfRegistry& registry, const VariantRegistry& variants);

struct CheckArgs {
    std::vector<std::string> ndfs;
    bool all = false;
    bool no_2d = false;
    std::string backend;  // empty: the NDF's own (AnyNdf::quadrature_backend), else boost
};
void add_check(CLI::App& app, CheckArgs& args);
int run_check(const CheckArgs& args, const NdfRegistry& registry);

struct ReportArgs {
    std::string scene;  // a scene file; empty: the embedded default
    std::string output = "report";
    bool print_scene = false;
    double scale = 1.0;     // --scale (SizeLimits::scale)
    double max_work = 0.0;  // evaluations a scene may cost: report::default_max_work (set by add_report) or --max-work
};
void add_report(CLI::App& app, ReportArgs& args);
int run_report(const ReportArgs& args, const NdfRegistry& registry, const VariantRegistry& variants);

struct SampleArgs {
    std::string ndf, sampler, output;
    double theta_i = 0.0;
    long long n = 1000;
    std::string seed = "1";  // text, parsed strictly (evaluation::parse_seed): no sign, no wrap-around
    bool list_samplers = false;
};
void add_sample(CLI::App& app, SampleArgs& args);
int run_sample(const SampleArgs& args, const NdfRegistry& registry);

struct TraceArgs {
    std::string scene;  // a scene file; empty: the cell flags below, or the default sweep when none is given
    std::string ndf = "ggx(alpha=0.5)", material = "mirror", downward = "smith", hit_normal = "visible",
                output = "trace";
    double theta_i = 45.0, phi_i = 0.0;
    long long walks = 1'000'000;
    int max_order = 0, threads = 0;
    std::string seed = "1";
    bool print_scene = false;
    std::vector<CLI::Option*> cell_options;  // the flags that name one cell: any given means "trace that cell"
    scene::SizeLimits limits;                // --max-cells, --max-walks, --scale
};
void add_trace(CLI::App& app, TraceArgs& args, const MaterialRegistry& materials);
int run_trace(const TraceArgs& args, const NdfRegistry& registry);

struct BrdfArgs {
    std::string ndf, material, wi, wo, downward = "smith", estimator = "next_event";
    long long walks = 1'000'000;
    int threads = 0;
    std::string seed = "1";
};
void add_brdf(CLI::App& app, BrdfArgs& args);
int run_brdf(const BrdfArgs& args, const NdfRegistry& registry);

struct FitArgs {
    std::string scene;  // a scene file; empty: the embedded default (GGX)
    std::string output = "fit";
    int threads = 0;
    bool print_scene = false, list_models = false;
    scene::SizeLimits limits;  // --max-cells, --max-walks, --scale
};
void add_fit(CLI::App& app, FitArgs& args, const fit::DiffuseRegistry& models);
int run_fit(const FitArgs& args, const NdfRegistry& registry);

struct TablesArgs {
    std::string scene;  // a scene file; empty: the embedded default (GGX)
    std::string output = "tables";
    int threads = 0;
    bool print_scene = false;
    scene::SizeLimits limits;  // --max-walks, --scale
};
void add_tables(CLI::App& app, TablesArgs& args);
int run_tables(const TablesArgs& args, const NdfRegistry& registry);

CLI::App* add_list(CLI::App& app);
int run_list(const NdfRegistry& registry);

// Parses a double, accepting "inf"; NaN and trailing junk are input errors naming `what`.
double parse_number(const std::string& text, const std::string& what);
// CLI11 checks for a number option, run on its text before CLI11 converts it: strict_real reads it by parse_double
// (a value beyond the doubles, a nonzero value that would read as 0, NaN and junk refused), strict_integer as a
// decimal 64-bit integer (beyond it refused; CLI11 alone clamps and reads 010 as octal). The message names the option.
CLI::Validator strict_real();
CLI::Validator strict_integer();
// The text of a scene file (at most scene::max_scene_bytes: a larger file, /dev/zero or an endless pipe is refused); a
// directory, a missing or unreadable file is an input error naming it.
std::string read_scene_file(const std::string& path);
// The options several subcommands share, spelled and described once.
// --backend, its accepted names and its help from backend_names (quadrature.hpp).
void add_backend_option(CLI::App& command, std::string& backend);
// -o/--output PATH: every output of every command.
CLI::Option* add_output_option(CLI::App& command, std::string& output, const std::string& what);
// --threads N (0: all cores); run_* checks it with require_threads.
CLI::Option* add_threads_option(CLI::App& command, int& threads);
void require_threads(int threads);
// --seed, an integer in [0, 2^64) as text (evaluation::parse_seed reads it).
CLI::Option* add_seed_option(CLI::App& command, std::string& seed);
// --downward, from downward_names (smith.hpp).
CLI::Option* add_downward_option(CLI::App& command, std::string& downward);
// --max-cells N and --max-walks N: the size a scene may ask for (scene/limits.hpp), inf for no limit.
void add_limit_options(CLI::App& command, scene::SizeLimits& limits);
// --max-walks N alone, for a command whose scene has no cells (tables).
void add_max_walks_option(CLI::App& command, scene::SizeLimits& limits);
// The optional positional SCENE (a TOML file), --print-scene and --scale F (SizeLimits::scale), of report, trace
// and fit; run_* checks the scale with require_scale.
void add_scene_options(CLI::App& command, std::string& scene, bool& print_scene, double& scale,
                       const std::string& none);
void require_scale(double scale);

}  // namespace smithlab::cli
