#include "report/g1_table.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

double G1_of(double L) { return std::isinf(L) ? 0.0 : 1.0 / (1.0 + L); }

bool matches_any(const std::vector<std::string>& patterns, const std::string& name) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return glob_match(p, name); });
}

void add_grid_ndfs(const Scene& scene, const NdfRegistry& ndfs, G1Table& table) {
    for (const NdfEntry& e : scene.ndfs) {
        if (e.roughness_given) {
            for (const ParamPoint& p : e.points()) {
                table.ndfs.push_back(make_entry_ndf(e, ndfs, p, std::nullopt));
                table.alphas.push_back(table.ndfs.back().has_param("alpha") ? table.ndfs.back().param("alpha") : NAN);
            }
            continue;
        }
        for (double a : scene.alphas)
            for (const ParamPoint& p : e.points()) {
                table.ndfs.push_back(make_entry_ndf(e, ndfs, p, a));
                table.alphas.push_back(a);
            }
    }
}

// One point's |dG1| and relative error of Lambda, folded into its row.
void add_point(G1Row& row, const AnyNdf& ndf, double alpha, double mu, double got, double want, bool keep_errors) {
    const double dG1 = std::abs(G1_of(got) - G1_of(want));
    if (keep_errors)
        row.errors.push_back({alpha, ndf.has_param("gamma") ? ndf.param("gamma") : NAN, mu, dG1,
                              want >= DBL_MIN ? std::abs(got - want) / want : NAN});
    ++row.points;
    row.sum_dG1 += dG1;
    row.max_dG1 = std::max(row.max_dG1, dG1);
    if (want < DBL_MIN) return;
    const double rel = std::isinf(got) ? INFINITY : std::abs(got - want) / want;
    if (rel > row.max_rel || std::isnan(rel)) {
        row.max_rel = rel;
        row.worst_at = ndf.spec() + " mu=" + format_g17(mu);
    }
}

void measure_on(G1Row& row, const AnyNdf& ndf, double alpha, const std::vector<double>& mus, ReferenceCache& cache,
                bool keep_errors) {
    const LambdaRoute route = route_for(*row.variant, ndf);
    const auto prepared = std::make_shared<const LambdaOfMu>(prepare(*row.variant, ndf));
    for (double mu : mus) {
        row.grid.push_back({prepared, mu});
        const double want = cache.get(ndf, mu, route);
        const double got = (*prepared)(mu);
        add_point(row, ndf, alpha, mu, got, want, keep_errors);
    }
}

void write_csv(const std::vector<G1Row>& rows, const fs::path& dir) {
    std::ofstream csv(dir / "variants.csv");
    write_csv_record(csv, {"variant", "points", "max_abs_dG1", "mean_abs_dG1", "max_rel_dLambda", "worst_at", "ns_per_eval",
                           "description"});
    for (const G1Row& r : rows) {
        if (r.points == 0) {  // selected, but it applies to no NDF of this scene
            write_csv_record(csv, {r.variant->name, "0", "", "", "", "", "", r.variant->description});
            continue;
        }
        write_csv_record(csv, {r.variant->name, std::to_string(r.points), format_g17(r.max_dG1), format_g17(r.sum_dG1 / r.points),
                               format_g17(r.max_rel), r.worst_at, format_g17(r.ns), r.variant->description});
    }
}

void write_markdown(const G1Table& table, const Scene& scene, const fs::path& dir) {
    std::ofstream md(dir / "report.md", std::ios::app);
    md << "Grid: " << scene.alphas.size() << " alpha x " << scene.mus.size() << " mu per NDF, " << table.ndfs.size()
       << " NDFs. Reference: the closed form where the NDF has one, else a different quadrature route than the "
          "variant's (Boost 1D at 1e-13, or the nested 2D route for the Boost 1D variants); never the variant's own (closed-form: Boost 1D; table: Boost 1D or 2D). Sorted by cost.\n\n"
       << "| variant | points | max abs dG1 | mean abs dG1 | max rel dLambda | ns/eval | worst at |\n"
       << "|---|---:|---:|---:|---:|---:|---|\n";
    for (const G1Row& r : table.rows) {
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

}  // namespace

G1Table g1_table(const Scene& scene, const NdfRegistry& ndfs, const VariantRegistry& variants) {
    G1Table table;
    add_grid_ndfs(scene, ndfs, table);
    for (const LambdaVariant& v : variants.list())
        if (matches_any(scene.include, v.name) && !matches_any(scene.exclude, v.name))
            table.rows.push_back(G1Row{.variant = &v, .grid = {}, .errors = {}, .worst_at = {}});
    if (table.rows.empty()) throw input_error("scene selects no variant (see smithlab eval --list-methods)");
    return table;
}

void require_g1_domain(const G1Table& table, const std::vector<double>& mus) {
    for (const G1Row& row : table.rows)
        for (const AnyNdf& ndf : table.ndfs)
            if (row.variant->applies(ndf))
                for (double mu : mus) try {
                        require_row_domain(*row.variant, ndf, mu);
                    } catch (const input_error& e) {
                        throw input_error("scene: grid.mu = " + format_g17(mu) + " for " + ndf.spec() + " (variant " +
                                          row.variant->name + "): " + e.what());
                    }
}

void measure_g1(G1Table& table, const std::vector<double>& mus, ReferenceCache& cache, bool keep_errors) {
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        G1Row& row = table.rows[i];
        std::fprintf(stderr, "report: [%zu/%zu] %s\n", i + 1, table.rows.size(), row.variant->name.c_str());
        for (std::size_t n = 0; n < table.ndfs.size(); ++n)
            if (row.variant->applies(table.ndfs[n])) measure_on(row, table.ndfs[n], table.alphas[n], mus, cache, keep_errors);
    }
}

void add_g1_timing(G1Table& table, std::vector<Timed>& timed) {
    for (G1Row& r : table.rows) {
        const std::vector<G1Point> sample = sample_of(r.grid);
        timed.push_back({r.variant->name, sample.size(), [sample](std::size_t k) { return (*sample[k].Lambda)(sample[k].mu); }, &r.ns});
    }
}

void write_g1_table(G1Table& table, const Scene& scene, const fs::path& dir) {
    std::sort(table.rows.begin(), table.rows.end(), [](const G1Row& a, const G1Row& b) { return a.ns < b.ns; });
    write_csv(table.rows, dir);
    write_markdown(table, scene, dir);
}

void write_g1_points(const G1Table& table, const fs::path& dir) {
    fs::create_directories(dir / "points");
    for (const G1Row& row : table.rows) {
        if (row.errors.empty()) continue;
        std::ofstream out(dir / "points" / (row.variant->name + ".csv"));
        write_csv_record(out, {"alpha", "gamma", "mu", "abs_dG1", "rel_dLambda"});
        for (const PointError& e : row.errors)
            write_csv_record(out, {format_g17(e.alpha), format_g17(e.gamma), format_g17(e.mu), format_g17(e.dG1), format_g17(e.rel)});
    }
}

}  // namespace smithlab::report
