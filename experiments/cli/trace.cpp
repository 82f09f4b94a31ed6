// smithlab trace / smithlab brdf: the microsurface walk (lib/walk/) from the command line. Types are erased here,
// once per cell: the NDF spec picks the concrete NDF type and the material spec the facet type, and the cell's
// walks run on those (no virtual call per bounce).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/ndfs.hpp"
#include "smithlab/single_scattering.hpp"
#include "smithlab/walk/trace.hpp"
#include "staged_directory.hpp"

namespace smithlab::cli {

namespace {

// f(concrete microsurface) for the NDF the spec names: the built-in families by their own types, anything else
// registered through AnyNdf (its D and Lambda then cost a virtual call each).
template <class F>
auto with_microsurface(const AnyNdf& ndf, const walk::MicrosurfaceOptions& opts, F&& f) {
    const std::string& family = ndf.family();
    if (family == "ggx") return f(walk::Microsurface(ggx(ndf.param("alpha")), opts));
    if (family == "beckmann") return f(walk::Microsurface(beckmann(ndf.param("alpha")), opts));
    if (family == "blinn") return f(walk::Microsurface(blinn(ndf.param("n")), opts));
    if (family == "gtr") return f(walk::Microsurface(gtr(ndf.param("alpha"), ndf.param("gamma")), opts));
    return f(walk::Microsurface(ndf, opts));
}

Vec3 incident(double theta, double phi, const char* what) {
    require(theta >= 0.0 && theta < 90.0, what, "in [0, 90) degrees (light from above the surface)", theta);
    require(std::isfinite(phi), what, "finite", phi);
    return direction_from_deg(theta, phi);
}

// "THETA,PHI" in degrees.
Vec3 parse_direction(const std::string& text, const char* what, bool upper) {
    const auto comma = text.find(',');
    if (comma == std::string::npos) throw input_error(std::string(what) + ": expected THETA,PHI in degrees, got '" + text + "'");
    const double theta = parse_number(text.substr(0, comma), std::string(what) + " theta");
    const double phi = parse_number(text.substr(comma + 1), std::string(what) + " phi");
    if (upper) return incident(theta, phi, what);
    require(theta >= 0.0 && theta <= 180.0, what, "theta in [0, 180] degrees", theta);
    require(std::isfinite(phi), what, "phi finite", phi);
    return direction_from_deg(theta, phi);
}

walk::MicrosurfaceOptions options(const std::string& downward) {
    if (downward == "smith") return {Downward::smith};
    if (downward == "hammon") return {Downward::hammon_symmetric};
    throw input_error("--downward must be smith or hammon, got '" + downward + "'");
}

// Progress with an ETA on stderr, at most every 2 s, for runs past a few seconds.
struct Progress {
    std::string what;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now(), last = start;
    void operator()(double done) {
        const auto now = std::chrono::steady_clock::now();
        const double t = std::chrono::duration<double>(now - start).count();
        if (t < 3.0 || std::chrono::duration<double>(now - last).count() < 2.0 || done >= 1.0) return;
        last = now;
        std::fprintf(stderr, "%s: %.0f%% done, %.0f s elapsed, ETA %.0f s\n", what.c_str(), 100.0 * done, t,
                     t * (1.0 - done) / done);
    }
};

const char* hemisphere_name[] = {"reflection", "transmission", "all"};
const char* component_name[] = {"specular", "diffuse", "all"};
const char* order_name[] = {"1", "2", "3", "4+", "all"};

}  // namespace

void add_trace(CLI::App& app, TraceArgs& a) {
    CLI::App* c = app.add_subcommand("trace", "Path trace the Smith microsurface: albedo by hemisphere, order, component");
    c->footer(
        "Examples:\n"
        "  smithlab trace --ndf 'ggx(alpha=0.5)' --material mirror --theta-i 45 --walks 1000000\n"
        "  smithlab trace --ndf 'gtr(alpha=0.3, gamma=1.5)' --material 'lambert(albedo=1)' --theta-i 70 --output t/\n"
        "Materials: mirror, conductor(eta=, k=), lambert(albedo=1), fresnel-diffuse(f0=0.02, albedo=1).\n"
        "Writes DIR/albedo.csv (ndf,material,theta_i,phi_i,hemisphere,order,component,albedo,stderr,walks) and\n"
        "DIR/meta.json (the cell, seed, version, walks, bounces traced, seconds, threads), both only when complete.\n"
        "Walk k draws from a counter-based generator keyed by (seed, cell, k): the files are the same bits for any\n"
        "--threads. --max-order N ends every walk after N hits (the orders beyond are not traced).");
    c->add_option("--ndf", a.ndf, "NDF spec")->capture_default_str();
    c->add_option("--material", a.material, "facet material spec")->capture_default_str();
    c->add_option("--theta-i", a.theta_i, "incident polar angle, degrees in [0, 90)")->capture_default_str();
    c->add_option("--phi-i", a.phi_i, "incident azimuth, degrees")->capture_default_str();
    c->add_option("--walks", a.walks, "walks in the cell (> 0)")->capture_default_str();
    c->add_option("--max-order", a.max_order, "end walks after this many hits (0: no limit)")->capture_default_str();
    c->add_option("--downward", a.downward, "Lambda of downward rays: smith (-1 - Lambda) or hammon (-Lambda)")
        ->capture_default_str();
    c->add_option("--seed", a.seed, "seed, an integer in [0, 2^64)")->capture_default_str();
    c->add_option("--threads", a.threads, "threads (0: all cores)")->capture_default_str();
    c->add_option("--output", a.output, "output directory")->capture_default_str();
}

int run_trace(const TraceArgs& a, const NdfRegistry& registry) {
    const unsigned long long seed = parse_seed(a.seed, "--seed");
    require(a.walks > 0, "--walks", "> 0", static_cast<double>(a.walks));
    require(a.max_order >= 0, "--max-order", ">= 0", a.max_order);
    const AnyNdf ndf = registry.make(a.ndf);
    const walk::Material material = walk::parse_material(a.material);
    const walk::MicrosurfaceOptions opts = options(a.downward);
    walk::CellRequest r;
    r.wi = incident(a.theta_i, a.phi_i, "--theta-i");
    r.seed = seed;
    r.walks = a.walks;
    r.limits.max_order = a.max_order;
    r.threads = static_cast<unsigned>(a.threads);
    output::StagedDirectory out(a.output, "trace");  // checked before any work

    const auto t0 = std::chrono::steady_clock::now();
    Progress progress{"trace"};
    const walk::CellResult cell = with_microsurface(ndf, opts, [&](const auto& ms) {
        return std::visit([&](const auto& m) { return walk::trace_cell(ms, m, r, std::ref(progress)); }, material);
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    {
        std::ofstream csv(out.path() / "albedo.csv");
        write_csv_record(csv, {"ndf", "material", "theta_i", "phi_i", "hemisphere", "order", "component", "albedo",
                               "stderr", "walks"});
        for (int h = 0; h < 3; ++h)
            for (int o = 0; o <= walk::order_bins; ++o)
                for (int c = 0; c < 3; ++c) {
                    const walk::Estimate e = cell.albedo.albedo(static_cast<walk::Hemisphere>(h),
                                                                o == walk::order_bins ? walk::all_orders : o,
                                                                static_cast<walk::Component>(c));
                    write_csv_record(csv, {ndf.spec(), walk::format_material(material), format_g17(a.theta_i),
                                           format_g17(a.phi_i), hemisphere_name[h], order_name[o], component_name[c],
                                           format_g17(e.value), format_g17(e.stderr_), std::to_string(a.walks)});
                }
        nlohmann::json meta = {{"ndf", ndf.spec()},
                               {"material", walk::format_material(material)},
                               {"theta_i", a.theta_i},
                               {"phi_i", a.phi_i},
                               {"downward", a.downward},
                               {"max_order", a.max_order},
                               {"seed", seed},
                               {"cell", r.cell},
                               {"version", SMITHLAB_VERSION},
                               {"walks", a.walks},
                               {"bounces", cell.albedo.events},
                               {"capped_walks", cell.albedo.capped},
                               {"seconds", seconds},
                               {"threads", a.threads}};
        std::ofstream(out.path() / "meta.json") << meta.dump(2) << "\n";
        if (!csv) throw std::runtime_error("trace: could not write albedo.csv");
    }
    out.publish();
    const walk::Estimate all = cell.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    std::printf("albedo %.17g\nstderr %.17g\nwalks %lld\nbounces %lld\nseconds %.3g\n", all.value, all.stderr_,
                static_cast<long long>(a.walks), static_cast<long long>(cell.albedo.events), seconds);
    return exit_ok;
}

void add_brdf(CLI::App& app, BrdfArgs& a) {
    CLI::App* c = app.add_subcommand("brdf", "f(wi, wo) |cos theta_o| of the Smith microsurface by the eval estimator");
    c->footer(
        "Example:\n"
        "  smithlab brdf --ndf 'ggx(alpha=0.5)' --material mirror --wi 45,0 --wo 60,180 --n 1000000\n"
        "Prints value and stderr (the eval estimator: next-event estimation toward wo at every hit), then\n"
        "order_1 .. order_4+ as 'value stderr', and single_analytic (F D G2 / (4 cos theta_i), height-correlated G2)\n"
        "for mirror and conductor facets.");
    c->add_option("--ndf", a.ndf, "NDF spec")->required();
    c->add_option("--material", a.material, "facet material spec")->required();
    c->add_option("--wi", a.wi, "THETA,PHI of the light, degrees, theta in [0, 90)")->required();
    c->add_option("--wo", a.wo, "THETA,PHI of the viewer, degrees")->required();
    c->add_option("--n", a.n, "walks (> 0)")->capture_default_str();
    c->add_option("--downward", a.downward, "smith or hammon")->capture_default_str();
    c->add_option("--seed", a.seed, "seed, an integer in [0, 2^64)")->capture_default_str();
    c->add_option("--threads", a.threads, "threads (0: all cores)")->capture_default_str();
}

int run_brdf(const BrdfArgs& a, const NdfRegistry& registry) {
    const unsigned long long seed = parse_seed(a.seed, "--seed");
    require(a.n > 0, "--n", "> 0", static_cast<double>(a.n));
    const AnyNdf ndf = registry.make(a.ndf);
    const walk::Material material = walk::parse_material(a.material);
    walk::EvalRequest r{.wi = parse_direction(a.wi, "--wi", true), .wo = parse_direction(a.wo, "--wo", false)};
    r.seed = seed;
    r.walks = a.n;
    r.threads = static_cast<unsigned>(a.threads);
    const walk::EvalTally t = with_microsurface(ndf, options(a.downward), [&](const auto& ms) {
        return std::visit([&](const auto& m) { return walk::eval_cell(ms, m, r); }, material);
    });
    const walk::Estimate v = t.value();
    std::printf("value %.17g\nstderr %.17g\n", v.value, v.stderr_);
    for (int o = 0; o < walk::order_bins; ++o) {
        const walk::Estimate e = t.value(o, walk::Component::all);
        std::printf("order_%s %.17g %.17g\n", order_name[o], e.value, e.stderr_);
    }
    auto single = [&](auto F) { return single_scattering_reflection(ndf, r.wi, r.wo, F); };
    if (std::holds_alternative<walk::Mirror>(material))
        std::printf("single_analytic %.17g\n", single([](double) { return 1.0; }));
    if (const auto* c = std::get_if<walk::Conductor>(&material))
        std::printf("single_analytic %.17g\n", single([c](double x) { return fresnel_conductor(x, c->eta, c->k); }));
    return exit_ok;
}

}  // namespace smithlab::cli
