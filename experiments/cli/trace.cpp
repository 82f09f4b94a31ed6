// smithlab trace / smithlab brdf: the microsurface walk (lib/walk/) from the command line. `trace` runs a scene
// (experiments/trace/: a file, the embedded default sweep, or one cell given by flags); `brdf` evaluates one
// (wi, wo) pair. Types are erased once per cell (smithlab/surface.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cluster/mpi_world.hpp"
#include "evaluation/seed.hpp"
#include "scene/walk_options.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/walk/trace.hpp"
#include "trace/capped_walks.hpp"
#include "trace/incidence.hpp"
#include "trace/single_analytic.hpp"
#include "trace/trace_run.hpp"
#include "trace/trace_scene.hpp"

namespace smithlab::cli {

namespace {

// "THETA,PHI" in degrees: the light's direction (incident), or the viewer's anywhere.
Vec3 parse_direction(const std::string& text, const char* what, const walk::Material* light_on) {
    const auto comma = text.find(',');
    if (comma == std::string::npos)
        throw input_error(std::string(what) + ": expected THETA,PHI in degrees, got '" + text + "'");
    const double theta = parse_number(text.substr(0, comma), std::string(what) + " theta");
    const double phi = parse_number(text.substr(comma + 1), std::string(what) + " phi");
    if (light_on) return trace::incident_direction(theta, phi, what, what, *light_on);
    require(theta >= 0.0 && theta <= 180.0, what, "theta in [0, 180] degrees", theta);
    require(std::isfinite(phi), what, "phi finite", phi);
    return direction_from_deg(theta, phi);
}

const char* order_name[] = {"1", "2", "3", "4+"};

// "Materials: mirror, conductor(eta=, k=), ...", every registered material's spec with its defaults, wrapped at 100
// columns; one that transmits says what its hemisphere of transmission is.
std::string materials_line(const MaterialRegistry& materials) {
    const std::vector<const walk::MaterialInfo*> all = materials.list();
    std::string text, line = "Materials:";
    for (std::size_t i = 0; i < all.size(); ++i) {
        std::string item = all[i]->spec();
        if (all[i]->transmits) item += " (reflection and transmission: hemisphere transmission is the light below)";
        item += i + 1 < all.size() ? "," : ".";
        if (line.size() + 1 + item.size() > 100) text += line + "\n", line = item;
        else line += " " + item;
    }
    return text + line + "\n";
}

// The one cell the flags name, as a scene.
trace::TraceScene cell_scene(const TraceArgs& a, const MaterialRegistry& materials) {
    require(a.walks > 0, "--walks", "> 0", static_cast<double>(a.walks));
    require(static_cast<double>(a.walks) <= a.limits.max_walks, "--walks",
            "<= --max-walks (raise it with --max-walks N)", static_cast<double>(a.walks));
    require(std::isfinite(a.phi_i), "--phi-i", "finite", a.phi_i);
    require(a.max_order >= 0, "--max-order", ">= 0", a.max_order);
    trace::incident_direction(a.theta_i, a.phi_i, "--theta-i", "--phi-i", materials.make(a.material));
    scene::parse_walk_options(a.downward, a.hit_normal, "--");
    trace::TraceScene s;
    s.title = "one cell";
    s.ndfs = {{a.ndf, std::nullopt}};
    s.materials = {a.material};
    s.theta_i = {a.theta_i};
    s.phi_i = {a.phi_i};
    s.walks = a.walks;
    s.seed = evaluation::parse_seed(a.seed, "--seed");
    s.max_order = a.max_order;
    s.downward = a.downward;
    s.hit_normal = a.hit_normal;
    return s;
}

// The eval estimator has no finite value where the BSDF holds a Dirac delta (walk::dirac_at): refused, naming --wo.
void require_density(const walk::Material& m, const walk::EvalRequest& r, const BrdfArgs& a) {
    if (m.dirac_at(r.wi, r.wo))
        throw input_error("--wo " + a.wo + ": '" + m.spec() +
                          "' facets are index-matched (eta = 1): they pass every ray straight through, so the BSDF "
                          "is a Dirac delta at wo = -wi (--wi " +
                          a.wi + "), which has no finite density to estimate (every other --wo gives 0)");
}

// Walks cut short leave the eval estimator low by what their next-event terms would still have added, which has no
// bound (trace/capped_walks.hpp): any such walk leaves no estimate.
void require_uncapped(const walk::EvalTally& t, const BrdfArgs& a) {
    if (t.capped > 0)
        throw input_error("brdf: --ndf '" + a.ndf + "' with --material '" + a.material +
                          "': " + trace::capped_text(t.capped, t.walks) +
                          "; the eval estimator cannot bound what they would still have added, so there is no "
                          "estimate to print");
}

// A line of brdf's answer: its name, then its numbers.
struct BrdfLine {
    std::string name;
    std::vector<double> numbers;
};

// value, stderr, order_1 .. order_4+ (value and stderr), and single_analytic where the facets have one.
std::vector<BrdfLine> brdf_lines(const walk::EvalTally& t, const AnyNdf& ndf, const walk::Material& material,
                                 const walk::EvalRequest& r) {
    const walk::Estimate v = t.value();
    std::vector<BrdfLine> lines = {{"value", {v.value}}, {"stderr", {v.stderr_}}};
    for (int o = 0; o < walk::order_bins; ++o) {
        const walk::Estimate e = t.value(o, walk::Component::all);
        lines.push_back({std::string("order_") + order_name[o], {e.value, e.stderr_}});
    }
    if (trace::has_single_analytic(material, r.wi.z() < 0.0))
        lines.push_back({"single_analytic", {trace::single_analytic(ndf, material, r.wi, r.wo)}});
    return lines;
}

// Prints the lines (17 significant digits), or none: a number that is not finite on an accepted input is a defect,
// reported as such (exit 3) rather than printed.
void print_brdf_lines(const std::vector<BrdfLine>& lines, const BrdfArgs& a) {
    for (const BrdfLine& l : lines)
        for (double x : l.numbers)
            if (!std::isfinite(x))
                throw std::runtime_error("brdf: " + l.name + " at --wi " + a.wi + " --wo " + a.wo + " is " +
                                         format_shortest(x) + ", not a finite number; nothing printed");
    for (const BrdfLine& l : lines) {
        std::printf("%s", l.name.c_str());
        for (double x : l.numbers) std::printf(" %.17g", x);
        std::printf("\n");
    }
}

}  // namespace

void add_trace(CLI::App& app, TraceArgs& a, const MaterialRegistry& materials) {
    CLI::App* c =
        app.add_subcommand("trace", "Path trace the Smith microsurface: albedo by hemisphere, order, component");
    c->footer(
        "Runs a scene (TOML, read strictly like report's; --print-scene shows the embedded default and documents\n"
        "every key): NDFs x materials x incident directions, one cell each. With neither a scene nor cell flags it\n"
        "runs the default sweep (GGX and GTR gamma = 1.5, mirror and lambert(albedo=1), alpha 0.1..1, theta_i 0, 45,\n"
        "75; a few seconds). The cell flags (--ndf ... --downward) trace one cell instead, defaults as shown.\n"
        "Examples:\n"
        "  smithlab trace\n"
        "  smithlab trace my_sweep.toml -o sweep/ --threads 8\n"
        "  smithlab trace --ndf 'ggx(alpha=0.5)' --material mirror --theta-i 45 --walks 1000000\n"
        "  smithlab trace --ndf 'gtr(alpha=0.3, gamma=1.5)' --material 'lambert(albedo=1)' --theta-i 70 -o t/\n" +
        materials_line(materials) +
        "Writes into DIR (-o, default trace/): albedo.csv (ndf,material,theta_i,phi_i,hemisphere,order,component,\n"
        "albedo,stderr,walks), with [brdf] in the scene brdf.csv (f |cos theta_o| per equal-solid-angle bin, order\n"
        "and component), and meta.json (the scene, seed, version, walks, bounces traced, seconds, threads), all only\n"
        "when complete.\n"
        "Each finished cell is kept in DIR/cells/: a killed run resumes from its last finished cell, and the same\n"
        "scene run again traces nothing. Walk k of cell c draws from a counter-based generator keyed by (seed, c, k):\n"
        "the files are the same bits for any --threads, resumed or not. max_order = N ends every walk after N hits\n"
        "(the orders beyond are not traced).");
    add_scene_options(*c, a.scene, a.print_scene, a.limits.scale, "the default sweep, or the cell the flags name");
    a.cell_options = {
        c->add_option("--ndf", a.ndf, "NDF spec")->capture_default_str(),
        c->add_option("--material", a.material, "facet material spec")->capture_default_str(),
        c->add_option("--theta-i", a.theta_i,
                      "incident polar angle, degrees in [0, 90) (dielectric: also (90, 180], light from below)")
            ->capture_default_str()
            ->check(strict_real()),
        c->add_option("--phi-i", a.phi_i, "incident azimuth, degrees")->capture_default_str()->check(strict_real()),
        c->add_option("--walks", a.walks, "walks in the cell (> 0)")->capture_default_str()->check(strict_integer()),
        c->add_option("--max-order", a.max_order, "end walks after this many hits (0: no limit)")
            ->capture_default_str()
            ->check(strict_integer()),
        add_downward_option(*c, a.downward),
        c->add_option("--hit-normal", a.hit_normal,
                      "hit normal: " + join_described(scene::hit_normal_names, ", ", " or "))
            ->capture_default_str(),
        add_seed_option(*c, a.seed)};
    add_threads_option(*c, a.threads);
    add_limit_options(*c, a.limits);
    add_output_option(*c, a.output, "output directory")->capture_default_str();
}

int run_trace(const TraceArgs& a, const NdfRegistry& registry) {
    if (a.print_scene) {
        std::cout << trace::default_trace_scene_text();
        return exit_ok;
    }
    require_threads(a.threads);
    const bool flags =
        std::any_of(a.cell_options.begin(), a.cell_options.end(), [](const CLI::Option* o) { return o->count() > 0; });
    if (flags && !a.scene.empty())
        throw input_error("trace: give a scene file or the cell flags (--ndf, --material, ...), not both");
    require_scale(a.limits.scale);
    if (flags && a.limits.scale != 1.0)
        throw input_error("trace: --scale goes with a scene; the cell flags give the walks (--walks N)");
    const std::string source = !a.scene.empty() ? a.scene : flags ? "<flags>" : "<default scene>";
    const trace::TraceScene scene = flags
        ? cell_scene(a, registry.materials())
        : trace::parse_trace_scene(a.scene.empty() ? trace::default_trace_scene_text() : read_scene_file(a.scene),
                                   source, registry, a.limits);
    const trace::RunSummary sum = trace::run_scene(scene, source, registry, a.output, static_cast<unsigned>(a.threads));
    if (cluster::mpi::rank() != 0) return exit_ok;  // a worker of rank 0's run (mpirun): rank 0 reports
    if (sum.total.size() == 1) std::printf("albedo %.17g\nstderr %.17g\n", sum.total[0].value, sum.total[0].stderr_);
    std::printf("cells %lld\ntraced %lld\nreused %lld\nwalks %lld\nbounces %lld\nseconds %.3g\noutput %s\n",
                static_cast<long long>(sum.cells), static_cast<long long>(sum.traced),
                static_cast<long long>(sum.reused), static_cast<long long>(scene.walks),
                static_cast<long long>(sum.bounces), sum.seconds, a.output.c_str());
    return exit_ok;
}

void add_brdf(CLI::App& app, BrdfArgs& a) {
    CLI::App* c = app.add_subcommand("brdf", "f(wi, wo) |cos theta_o| of the Smith microsurface by the eval estimator");
    c->footer(
        "Example:\n"
        "  smithlab brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 60,180 --walks 1000000\n"
        "Prints value and stderr (the eval estimator, --estimator: next-event estimation toward wo at every hit), "
        "then\n"
        "order_1 .. order_4+ as 'value stderr', and single_analytic (the single-scattering BSDF times |cos theta_o|,\n"
        "Walter 2007 eq. 20 and 21 with the height-correlated G2) for mirror, conductor and dielectric facets.\n"
        "With dielectric facets, --wo below the surface (theta > 90) is transmission.");
    c->add_option("--ndf", a.ndf, "NDF spec")->required();
    c->add_option("--material", a.material, "facet material spec")->required();
    c->add_option("--wi", a.wi, "THETA,PHI of the light, degrees, theta in [0, 90) (dielectric: also (90, 180])")
        ->required();
    c->add_option("--wo", a.wo, "THETA,PHI of the viewer, degrees")->required();
    c->add_option("--walks", a.walks, "walks (> 0)")->capture_default_str()->check(strict_integer());
    add_downward_option(*c, a.downward);
    c->add_option(
         "--estimator", a.estimator,
         "the eval estimator (all unbiased; walk.hpp): " + join_described(walk::eval_estimator_names, " | ", " | "))
        ->capture_default_str()
        ->check(CLI::IsMember(names_of(walk::eval_estimator_names)));
    add_seed_option(*c, a.seed);
    add_threads_option(*c, a.threads);
}

int run_brdf(const BrdfArgs& a, const NdfRegistry& registry) {
    const unsigned long long seed = evaluation::parse_seed(a.seed, "--seed");
    require(a.walks > 0, "--walks", "> 0", static_cast<double>(a.walks));
    require_threads(a.threads);
    const AnyNdf ndf = registry.make(a.ndf);
    if (!ndf.note().empty()) std::fprintf(stderr, "smithlab: note: %s\n", ndf.note().c_str());
    const walk::Material material = registry.materials().make(a.material);
    walk::EvalRequest r{.wi = parse_direction(a.wi, "--wi", &material), .wo = parse_direction(a.wo, "--wo", nullptr)};
    r.seed = seed;
    r.walks = a.walks;
    r.threads = static_cast<unsigned>(a.threads);
    r.estimator = find_named(walk::eval_estimator_names, a.estimator)->value;  // checked by CLI11
    require_density(material, r, a);
    const walk::EvalTally t =
        make_surface(ndf, scene::parse_walk_options(a.downward, "visible", "--"))->eval_cell(material, r);
    require_uncapped(t, a);
    print_brdf_lines(brdf_lines(t, ndf, material, r), a);
    return exit_ok;
}

}  // namespace smithlab::cli
