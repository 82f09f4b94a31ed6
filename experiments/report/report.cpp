#include "report.hpp"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>

#include "figures.hpp"
#include "references.hpp"
#include "sampling_experiment.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "staged_directory.hpp"
#include "timing.hpp"
#include "walk_section.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

// A grid point as the timing sees it: the variant prepared for the point's NDF (once per NDF, shared), and mu.
struct Point {
    std::shared_ptr<const LambdaOfMu> Lambda;
    double mu;
};

struct PointError {
    double alpha, gamma, mu, dG1, rel;
};

struct Row {
    const LambdaVariant* variant;
    std::vector<Point> grid;           // the grid points it applies to
    std::vector<PointError> errors;    // per point, kept only for the figures
    std::size_t points = 0;
    double max_dG1 = 0.0, sum_dG1 = 0.0, max_rel = 0.0;
    std::string worst_at;
    double ns = NAN;
};

double G1_of(double L) { return std::isinf(L) ? 0.0 : 1.0 / (1.0 + L); }

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

struct G2Point {
    AnyNdf ndf;
    double mu_i, mu_o;
};

struct G2Row {
    const G2Variant* variant;
    std::vector<G2Point> grid;
    double max_d = 0.0, sum_d = 0.0, ns = NAN;
    std::string worst_at;
};

// sampling.csv and the report's section: per (family, alpha) the three strategies side by side.
void write_sampling(const std::vector<SamplingRow>& rows, const Scene::Sampling& s, const fs::path& dir) {
    std::ofstream csv(dir / "sampling.csv");
    write_csv_record(csv, {"family", "alpha", "strategy", "samples", "mean", "stderr", "variance", "ns_per_sample", "efficiency"});
    std::ofstream md(dir / "report.md", std::ios::app);
    char head[600];
    std::snprintf(head, sizeof head,
                  "\n## Sampling efficiency: cosine, D cos and visible-normal sampling\n\nDirectional albedo of a white "
                  "conductor (F = 1, height-correlated G2) seen from theta_o = %g deg under a uniform white environment, "
                  "%zu samples per estimate. Efficiency = 1 / (variance x seconds per sample); time per sample by Google "
                  "Benchmark on one core. The three means estimate the same albedo.\n\n![](sampling_efficiency.png)\n\n",
                  s.theta_o, s.samples);
    md << head << "| ndf | strategy | albedo (mean +- stderr) | variance | ns/sample | efficiency (1/s) |\n"
       << "|---|---|---|---:|---:|---:|\n";
    for (const SamplingRow& r : rows) {
        const double se = std::sqrt(r.variance / static_cast<double>(r.samples)), eff = 1e9 / (r.variance * r.ns);
        write_csv_record(csv, {r.family, format_g17(r.alpha), r.strategy, std::to_string(r.samples), format_g17(r.mean),
                               format_g17(se), format_g17(r.variance), format_g17(r.ns), format_g17(eff)});
        char line[300];
        std::snprintf(line, sizeof line, "| %s(%g) | %s | %.5f +- %.5f | %.3e | %.0f | %.3e |\n", r.family.c_str(), r.alpha,
                      r.strategy.c_str(), r.mean, se, r.variance, r.ns, eff);
        md << line;
    }
}

}  // namespace

int run_report(const Scene& scene, const std::string& out_dir, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    // Validate everything before computing or writing anything.
    output::require_output_directory(out_dir);
    std::vector<AnyNdf> grid_ndfs;
    for (const NdfFamily& f : scene.ndfs) {
        const NdfInfo* info = ndfs.find(f.family);
        if (!info) throw input_error("scene: unknown ndf family '" + f.family + "'");
        for (double a : scene.alphas) {
            if (f.gammas.empty()) grid_ndfs.push_back(ndfs.make(format_spec({f.family, {{"alpha", a}}})));
            for (double g : f.gammas) grid_ndfs.push_back(ndfs.make(format_spec({f.family, {{"alpha", a}, {"gamma", g}}})));
        }
    }
    std::vector<Row> rows;
    for (const LambdaVariant& v : variants.list()) {
        const auto matches = [&](const std::vector<std::string>& pats) {
            return std::any_of(pats.begin(), pats.end(), [&](const std::string& p) { return glob_match(p, v.name); });
        };
        if (matches(scene.include) && !matches(scene.exclude)) rows.push_back(Row{.variant = &v, .grid = {}, .errors = {}, .worst_at = {}});
    }
    if (rows.empty()) throw input_error("scene selects no variant (see smithlab eval --list-methods)");
    for (double mu : scene.mus) require(mu > 0.0 && std::isfinite(mu), "scene: grid.mu", "finite and > 0", mu);
    for (double mu : scene.g2.mus) require(mu > 0.0 && std::isfinite(mu), "scene: g2.mu", "finite and > 0", mu);
    for (const Row& row : rows)
        for (const AnyNdf& ndf : grid_ndfs)
            if (row.variant->applies(ndf))
                for (double mu : scene.mus) try {
                        require_row_domain(*row.variant, ndf, mu);
                    } catch (const input_error& e) {
                        throw input_error("scene: grid.mu = " + format_g17(mu) + " for " + ndf.spec() + " (variant " +
                                          row.variant->name + "): " + e.what());
                    }
    std::vector<AnyNdf> g2_ndfs;
    if (!scene.g2.include.empty())
        for (const std::string& family : scene.g2.families)
            for (double a : scene.alphas) g2_ndfs.push_back(ndfs.make(format_spec({family, {{"alpha", a}}})));
    for (const AnyNdf& ndf : g2_ndfs)  // the exact G2's Lambdas come by quadrature where there is no closed form
        if (!ndf.has_closed_Lambda())
            for (double mu : scene.g2.mus) try {
                    require_quadrature_domain(ndf, mu);
                } catch (const input_error& e) {
                    throw input_error("scene: g2.mu = " + format_g17(mu) + " for " + ndf.spec() + ": " + e.what());
                }

    const std::vector<WalkCell> walk_sweep = walk_cells(scene.walk, ndfs);  // empty without [walk]

    // The sampling experiment validates its keys before it computes anything.
    std::vector<SamplingRow> sampling;
    if (!scene.sampling.families.empty()) {
        std::fprintf(stderr, "report: sampling experiment, %zu x %zu estimates of %zu samples\n",
                     scene.sampling.families.size() * scene.sampling.alphas.size(), sampling_strategies.size(),
                     scene.sampling.samples);
        sampling = run_sampling_experiment(scene.sampling, ndfs);
    }
    std::vector<WalkResult> walks;
    double walk_seconds = 0.0;
    if (!walk_sweep.empty()) {
        std::fprintf(stderr, "report: walk section, %zu cells of %lld walks\n", walk_sweep.size(),
                     static_cast<long long>(scene.walk.walks));
        const auto t0 = std::chrono::steady_clock::now();
        walks = trace_walk_cells(walk_sweep, scene.walk);
        walk_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    // Everything but the cache is written to a stage and moved into out_dir when complete (staged_directory.hpp).
    output::StagedDirectory staged(out_dir, "report");
    const fs::path& dir = staged.path();
    ReferenceCache cache(fs::path(out_dir) / "cache" / "references.csv");

    for (std::size_t i = 0; i < rows.size(); ++i) {
        Row& row = rows[i];
        std::fprintf(stderr, "report: [%zu/%zu] %s\n", i + 1, rows.size(), row.variant->name.c_str());
        for (const AnyNdf& ndf : grid_ndfs) {
            if (!row.variant->applies(ndf)) continue;
            const Route route = route_for(*row.variant, ndf);
            const auto prepared = std::make_shared<const LambdaOfMu>(prepare(*row.variant, ndf));
            for (double mu : scene.mus) {
                row.grid.push_back({prepared, mu});
                const double want = cache.get(ndf, mu, route);
                const double got = (*prepared)(mu);
                const double dG1 = std::abs(G1_of(got) - G1_of(want));
                if (scene.figures.error_maps || scene.figures.pareto)
                    row.errors.push_back({ndf.param("alpha"), ndf.family() == "gtr" ? ndf.param("gamma") : NAN, mu, dG1,
                                         want >= DBL_MIN ? std::abs(got - want) / want : NAN});
                ++row.points;
                row.sum_dG1 += dG1;
                row.max_dG1 = std::max(row.max_dG1, dG1);
                if (want >= DBL_MIN) {
                    const double rel = std::isinf(got) ? INFINITY : std::abs(got - want) / want;
                    if (rel > row.max_rel || std::isnan(rel)) {
                        row.max_rel = rel;
                        row.worst_at = ndf.spec() + " mu=" + format_g17(mu);
                    }
                }
            }
        }
    }
    // G2: every selected G2 variant against the exact height-correlated G2, with the cached references' Lambdas.
    const std::vector<G2Variant> g2_variants = builtin_G2_variants();
    std::vector<G2Row> g2_rows;
    for (const G2Variant& v : g2_variants)
        if (std::any_of(scene.g2.include.begin(), scene.g2.include.end(), [&](const auto& p) { return glob_match(p, v.name); }))
            g2_rows.push_back(G2Row{.variant = &v, .grid = {}, .worst_at = {}});
    for (G2Row& row : g2_rows) {
        std::fprintf(stderr, "report: G2 %s\n", row.variant->name.c_str());
        for (const AnyNdf& ndf : g2_ndfs) {
            if (!row.variant->applies(ndf)) continue;
            const Route route = ndf.has_closed_Lambda() ? Route::closed : Route::q1d_boost;
            for (double mi : scene.g2.mus)
                for (double mo : scene.g2.mus) {
                    const double want = 1.0 / (1.0 + cache.get(ndf, mi, route) + cache.get(ndf, mo, route));
                    const double d = std::abs(row.variant->G2(ndf, mi, mo) - want);
                    row.grid.push_back({ndf, mi, mo});
                    row.sum_d += d;
                    if (d >= row.max_d) {
                        row.max_d = d;
                        row.worst_at = ndf.spec() + " mu_i=" + format_g17(mi) + " mu_o=" + format_g17(mo);
                    }
                }
        }
    }
    cache.save();
    std::fprintf(stderr, "report: references: %zu reused from the cache, %zu computed", cache.loaded(), cache.computed());
    if (cache.discarded()) std::fprintf(stderr, " (%zu damaged cache records discarded)", cache.discarded());
    std::fprintf(stderr, "\n");

    std::vector<Timed> timed;
    for (Row& r : rows) {
        const std::vector<Point> sample = sample_of(r.grid);
        timed.push_back({r.variant->name, sample.size(), [sample](std::size_t k) { return (*sample[k].Lambda)(sample[k].mu); }, &r.ns});
    }
    for (G2Row& r : g2_rows) {
        const std::vector<G2Point> sample = sample_of(r.grid);
        const G2Variant* v = r.variant;
        timed.push_back({v->name, sample.size(),
                         [v, sample](std::size_t k) { return v->G2(sample[k].ndf, sample[k].mu_i, sample[k].mu_o); }, &r.ns});
    }
    for (SamplingRow& r : sampling) {
        auto g = std::make_shared<Rng>(make_rng(scene.sampling.seed, 1u << 20));
        timed.push_back({"sampling/" + r.family + "(" + format_g17(r.alpha) + ")/" + r.strategy, 1,
                         [w = r.weight, g](std::size_t) { return w(*g); }, &r.ns});
    }
    std::fprintf(stderr, "report: timing %zu variants and estimators with Google Benchmark\n", timed.size());
    time_all(timed, scene.min_time, dir / "bench.json");

    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.ns < b.ns; });
    {
        std::ofstream csv(dir / "variants.csv");
        write_csv_record(csv, {"variant", "points", "max_abs_dG1", "mean_abs_dG1", "max_rel_dLambda", "worst_at", "ns_per_eval",
                               "description"});
        for (const Row& r : rows) {
            if (r.points == 0) {  // selected, but it applies to no NDF of this scene
                write_csv_record(csv, {r.variant->name, "0", "", "", "", "", "", r.variant->description});
                continue;
            }
            write_csv_record(csv, {r.variant->name, std::to_string(r.points), format_g17(r.max_dG1), format_g17(r.sum_dG1 / r.points),
                                   format_g17(r.max_rel), r.worst_at, format_g17(r.ns), r.variant->description});
        }
    }
    {
        std::ofstream md(dir / "report.md");
        const std::time_t now = std::time(nullptr);
        char date[32];
        std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
        md << "# " << scene.title << "\n\n"
           << "Machine: " << machine() << ", one core; compiler " << __VERSION__ << ", flags `" << SMITHLAB_BUILD_FLAGS
           << "`; " << date << ".\n\n"
           << "Grid: " << scene.alphas.size() << " alpha x " << scene.mus.size() << " mu per NDF, " << grid_ndfs.size()
           << " NDFs. Reference: the closed form where the NDF has one, else a different quadrature route than the "
              "variant's (Boost 1D at 1e-13, or the nested 2D route for the Boost 1D variants); never the variant's own (closed-form: Boost 1D; table: Boost 1D or 2D). Sorted by cost.\n\n"
           << "| variant | points | max abs dG1 | mean abs dG1 | max rel dLambda | ns/eval | worst at |\n"
           << "|---|---:|---:|---:|---:|---:|---|\n";
        for (const Row& r : rows) {
            if (r.points == 0) {
                md << "| " << r.variant->name << " | 0 | | | | | applies to no NDF of this scene |\n";
                continue;
            }
            char line[512];
            std::snprintf(line, sizeof line, "| %s | %zu | %.2e | %.2e | %.2e | %.0f | %s |\n", r.variant->name.c_str(), r.points,
                          r.max_dG1, r.sum_dG1 / r.points, r.max_rel, r.ns, r.worst_at.c_str());
            md << line;
        }
    }
    if (!g2_rows.empty()) {
        std::ofstream csv(dir / "g2_variants.csv");
        write_csv_record(csv, {"variant", "points", "max_abs_dG2", "mean_abs_dG2", "worst_at", "ns_per_eval", "description"});
        std::ofstream md(dir / "report.md", std::ios::app);
        md << "\n## G2 variants (two directions, reflection)\n\nAgainst the exact height-correlated G2 = 1/(1 + Lambda_i + "
              "Lambda_o), on alpha x mu_i x mu_o.\n\n| variant | points | max abs dG2 | mean abs dG2 | ns/eval | worst at |\n"
              "|---|---:|---:|---:|---:|---|\n";
        for (const G2Row& r : g2_rows) {
            const std::size_t n = r.grid.size();
            write_csv_record(csv, {r.variant->name, std::to_string(n), format_g17(r.max_d), n ? format_g17(r.sum_d / n) : "",
                                   r.worst_at, format_g17(r.ns), r.variant->description});
            char line[512];
            std::snprintf(line, sizeof line, "| %s | %zu | %.2e | %.2e | %.0f | %s |\n", r.variant->name.c_str(), n, r.max_d,
                          n ? r.sum_d / n : NAN, r.ns, r.worst_at.c_str());
            md << line;
        }
    }
    if (!sampling.empty()) write_sampling(sampling, scene.sampling, dir);
    if (!walks.empty()) write_walk_section(walks, scene.walk, walk_seconds, dir);
    if (scene.figures.error_maps || scene.figures.pareto) {
        fs::create_directories(dir / "points");
        for (const Row& row : rows) {
            if (row.errors.empty()) continue;
            std::ofstream out(dir / "points" / (row.variant->name + ".csv"));
            write_csv_record(out, {"alpha", "gamma", "mu", "abs_dG1", "rel_dLambda"});
            for (const PointError& e : row.errors)
                write_csv_record(out, {format_g17(e.alpha), format_g17(e.gamma), format_g17(e.mu), format_g17(e.dG1), format_g17(e.rel)});
        }
    }
    write_figures(scene, dir);
    staged.publish();
    std::fprintf(stderr, "report: wrote %s/report.md and its data\n", out_dir.c_str());
    return 0;
}

}  // namespace smithlab::report
