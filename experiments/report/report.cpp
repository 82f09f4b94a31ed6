#include "report.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/gtr.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

// The reference a variant is measured against: a closed form where the NDF has one; otherwise a quadrature route
// other than the variant's own (the 2D nested route for the Boost 1D variants, Boost 1D at 1e-13 for the rest).
// Both agree with the 50-digit references of the test suite to ~1e-15; GSL's QAG can stop at ~1e-11.
enum class Route { closed, q1d_boost, q2d_boost };

const char* name_of(Route r) { return r == Route::closed ? "closed" : r == Route::q1d_boost ? "q1d-boost-1e-13" : "q2d-boost-1e-12"; }

Route route_for(const LambdaVariant& v, const AnyNdf& ndf) {
    if (ndf.has_closed_Lambda()) return Route::closed;
    return v.name.rfind("q1d-boost", 0) == 0 ? Route::q2d_boost : Route::q1d_boost;
}

double compute_reference(const AnyNdf& ndf, double mu, Route r) {
    switch (r) {
        case Route::closed: return ndf.Lambda(mu);
        case Route::q1d_boost: return Lambda_1d(ndf, mu, {Backend::boost, 1e-13});
        case Route::q2d_boost: return Lambda_2d(ndf, mu, {Backend::boost, 1e-12});
    }
    return NAN;
}

// References by (spec, mu, route), kept in DIR/cache/references.csv between runs of the same scene.
class ReferenceCache {
public:
    explicit ReferenceCache(fs::path file) : file_(std::move(file)) {
        std::ifstream in(file_);
        if (!in) return;
        const auto records = read_csv(in);
        for (std::size_t i = 1; i < records.size(); ++i)
            if (records[i].error.empty() && records[i].fields.size() == 4)
                values_[records[i].fields[0] + "|" + records[i].fields[1] + "|" + records[i].fields[2]] =
                    std::strtod(records[i].fields[3].c_str(), nullptr);
        loaded_ = values_.size();
    }
    double get(const AnyNdf& ndf, double mu, Route r) {
        const std::string key = ndf.spec() + "|" + format_g17(mu) + "|" + name_of(r);
        if (auto it = values_.find(key); it != values_.end()) return it->second;
        ++computed_;
        return values_[key] = compute_reference(ndf, mu, r);
    }
    void save() const {
        fs::create_directories(file_.parent_path());
        std::ofstream out(file_);
        write_csv_record(out, {"spec", "mu", "route", "lambda"});
        for (const auto& [key, v] : values_) {
            const auto a = key.find('|'), b = key.find('|', a + 1);
            write_csv_record(out, {key.substr(0, a), key.substr(a + 1, b - a - 1), key.substr(b + 1), format_g17(v)});
        }
    }
    std::size_t loaded() const { return loaded_; }
    std::size_t computed() const { return computed_; }

private:
    fs::path file_;
    std::map<std::string, double> values_;
    std::size_t loaded_ = 0, computed_ = 0;
};

struct Point {
    AnyNdf ndf;
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

// Something to time: evaluation k of n (cycled), and where its ns/eval goes.
struct Timed {
    std::string name;
    std::size_t n;
    std::function<double(std::size_t)> eval;
    double* ns;
};

// Google Benchmark, one core, each item cycling through its sample; the JSON it writes is what we read.
void time_all(const std::vector<Timed>& items, double min_time, const fs::path& json_file) {
    for (const Timed& t : items) {
        if (t.n == 0) continue;  // applies to no NDF of the scene: nothing to time
        benchmark::RegisterBenchmark(t.name.c_str(), [t](benchmark::State& s) {
            std::size_t k = 0;
            for (auto _ : s) benchmark::DoNotOptimize(t.eval(k++ % t.n));
        });
    }
    std::string flag = "--benchmark_min_time=" + format_g17(min_time);
    char arg0[] = "smithlab-report";
    char* argv[] = {arg0, flag.data(), nullptr};
    int argc = 2;
    benchmark::Initialize(&argc, argv);
    std::ofstream out(json_file);
    benchmark::JSONReporter reporter;
    reporter.SetOutputStream(&out);
    reporter.SetErrorStream(&std::cerr);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();
    out.close();
    std::ifstream in(json_file);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& b : j.at("benchmarks")) {
        const std::string name = b.at("name");
        const double scale = b.at("time_unit") == "ns" ? 1.0 : b.at("time_unit") == "us" ? 1e3 : 1e6;
        for (const Timed& t : items)
            if (t.name == name) *t.ns = b.at("cpu_time").get<double>() * scale;
    }
}

// At most 64 evenly spread elements of v.
template <class T>
std::vector<T> sample_of(const std::vector<T>& v) {
    std::vector<T> out;
    const std::size_t step = std::max<std::size_t>(1, v.size() / 64);
    for (std::size_t k = 0; k < v.size(); k += step) out.push_back(v[k]);
    return out;
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

// Linear grid of n points on [lo, hi].
std::vector<double> lin(double lo, double hi, int n) {
    std::vector<double> v;
    for (int i = 0; i < n; ++i) v.push_back(lo + (hi - lo) * i / (n - 1));
    return v;
}

// The figures' data as CSV, the Dimov numbers into report.md, then the PNGs by the plot script.
void write_figures(const Scene& scene, const fs::path& dir, const std::vector<Row>& rows) {
    const auto& fig = scene.figures;
    std::ofstream md(dir / "report.md", std::ios::app);
    if (fig.error_maps || fig.pareto) {
        fs::create_directories(dir / "points");
        for (const Row& row : rows) {
            if (row.errors.empty()) continue;
            std::ofstream out(dir / "points" / (row.variant->name + ".csv"));
            write_csv_record(out, {"alpha", "gamma", "mu", "abs_dG1", "rel_dLambda"});
            for (const PointError& e : row.errors)
                write_csv_record(out, {format_g17(e.alpha), format_g17(e.gamma), format_g17(e.mu), format_g17(e.dG1), format_g17(e.rel)});
        }
    }
    if (fig.dimov_heightfields || fig.dimov_gamma4_vs_10) fs::create_directories(dir / "dimov");
    if (fig.dimov_heightfields) {
        std::ofstream out(dir / "dimov" / "heightfields.csv");
        write_csv_record(out, {"gamma", "alpha", "mu", "g1"});
        for (int g = 0; g <= 4; ++g)
            for (double a : lin(0.1, 0.5, 41))
                for (double mu : lin(0.0, 5.0, 51))
                    write_csv_record(out, {std::to_string(g), format_g17(a), format_g17(mu), format_g17(G1(gtr(a, g), mu))});
    }
    if (fig.dimov_spline_mean) {
        // Dimov 2015 sec. 5: "the mean difference was 0.001", against Monte Carlo, domain unstated. Here: his plot's
        // alpha in [0.1, 0.5], mu in (0, 5], gamma between the knots, against 1D quadrature.
        double sum = 0.0, worst = 0.0;
        int n = 0;
        for (double a : lin(0.1, 0.5, 9))
            for (double mu : lin(0.25, 5.0, 20))
                for (double g : lin(0.25, 3.75, 15)) {
                    const auto ndf = gtr(a, g);
                    const double d = std::abs(G1(ndf, mu, {.method = Method::spline}) - G1(ndf, mu, {.method = Method::quadrature}));
                    sum += d;
                    worst = std::max(worst, d);
                    ++n;
                }
        char line[400];
        std::snprintf(line, sizeof line,
                      "\n## Dimov 2015, sec. 5: the spline's mean difference\n\nPublished: about 0.001 (against Monte "
                      "Carlo). Measured against 1D quadrature on alpha in [0.1, 0.5], mu in [0.25, 5], 15 gamma between the "
                      "knots (%d points): mean |dG1| = %.2e, max |dG1| = %.2e.\n",
                      n, sum / n, worst);
        md << line;
    }
    if (fig.dimov_gamma4_vs_10) {
        std::ofstream out(dir / "dimov" / "gamma4_vs_10.csv");
        write_csv_record(out, {"alpha", "mu", "abs_diff"});
        double worst = 0.0;
        for (double a : lin(0.02, 1.0, 50))
            for (double mu : lin(0.04, 2.0, 50)) {
                const double d = std::abs(G1(gtr(a, 4.0), mu) - G1(gtr(a, 10.0), mu));
                worst = std::max(worst, d);
                write_csv_record(out, {format_g17(a), format_g17(mu), format_g17(d)});
            }
        char line[400];
        std::snprintf(line, sizeof line,
                      "\n## Dimov 2015, sec. 6: |G1(gamma = 4) - G1(gamma = 10)|\n\nPublished: \"up to 0.3\", largest for "
                      "mu in (0, 1), read off a plot scaled 10x. Measured with the closed forms (gamma = 10 generated) on "
                      "alpha in (0, 1], mu in (0, 2]: max = %.3f (%.2f on the 10x scale of the figure below). So the "
                      "published 0.3 is the difference itself, not the scaled height.\n\n![](gamma4_vs_10.png)\n",
                      worst, 10 * worst);
        md << line;
    }
    if (fig.pareto) md << "\n## Error against cost\n\n![](pareto.png)\n";
    if (fig.error_maps) md << "\n## Where each variant fails: |dG1| over (alpha, mu), worst over gamma\n\n![](error_maps.png)\n";
    if (fig.dimov_heightfields) md << "\n## Dimov 2015, sec. 4: G1 height fields, gamma = 0..4\n\n![](dimov_heightfields.png)\n";
    md.close();
    if (!(fig.pareto || fig.error_maps || fig.dimov_heightfields || fig.dimov_gamma4_vs_10)) return;

    // The plot script: next to an installed binary, or in the source tree of this build.
    const fs::path exe = fs::canonical("/proc/self/exe");
    fs::path script = exe.parent_path().parent_path() / "share" / "smithlab" / "report_plots.py";
    if (!fs::exists(script)) script = SMITHLAB_PLOT_SCRIPT;
    const std::string cmd = "/usr/bin/python3 '" + script.string() + "' '" + dir.string() + "'";
    std::fprintf(stderr, "report: drawing the figures (%s)\n", cmd.c_str());
    if (std::system(cmd.c_str()) != 0) {
        std::fprintf(stderr, "report: warning: the figures were not drawn; their data is in %s (needs Debian's "
                             "python3-matplotlib, see .ci/deps)\n", dir.string().c_str());
        std::ofstream(dir / "report.md", std::ios::app) << "\n**The figures were not drawn** (python3-matplotlib missing?); "
                                                            "their data is beside this file.\n";
    }
}

}  // namespace

int run_report(const Scene& scene, const std::string& out_dir, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    // Validate everything before computing or writing anything.
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

    const fs::path dir(out_dir);
    fs::create_directories(dir);
    ReferenceCache cache(dir / "cache" / "references.csv");

    for (std::size_t i = 0; i < rows.size(); ++i) {
        Row& row = rows[i];
        std::fprintf(stderr, "report: [%zu/%zu] %s\n", i + 1, rows.size(), row.variant->name.c_str());
        for (const AnyNdf& ndf : grid_ndfs) {
            if (!row.variant->applies(ndf)) continue;
            const Route route = route_for(*row.variant, ndf);
            for (double mu : scene.mus) {
                row.grid.push_back({ndf, mu});
                const double want = cache.get(ndf, mu, route);
                const double got = Lambda(*row.variant, ndf, mu);
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
        for (const std::string& family : scene.g2.families)
            for (double a : scene.alphas) {
                const AnyNdf ndf = ndfs.make(format_spec({family, {{"alpha", a}}}));
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
    std::fprintf(stderr, "report: references: %zu reused from the cache, %zu computed\n", cache.loaded(), cache.computed());

    std::vector<Timed> timed;
    for (Row& r : rows) {
        const std::vector<Point> sample = sample_of(r.grid);
        const LambdaVariant* v = r.variant;
        timed.push_back({v->name, sample.size(), [v, sample](std::size_t k) { return v->Lambda(sample[k].ndf, sample[k].mu); }, &r.ns});
    }
    for (G2Row& r : g2_rows) {
        const std::vector<G2Point> sample = sample_of(r.grid);
        const G2Variant* v = r.variant;
        timed.push_back({v->name, sample.size(),
                         [v, sample](std::size_t k) { return v->G2(sample[k].ndf, sample[k].mu_i, sample[k].mu_o); }, &r.ns});
    }
    std::fprintf(stderr, "report: timing %zu variants with Google Benchmark\n", timed.size());
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
              "variant's (Boost 1D at 1e-13, or the nested 2D route for the Boost 1D variants). Sorted by cost.\n\n"
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
    write_figures(scene, dir, rows);
    std::fprintf(stderr, "report: wrote %s/report.md and its data\n", dir.string().c_str());
    return 0;
}

}  // namespace smithlab::report
