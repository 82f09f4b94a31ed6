#include "report/g2_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

std::vector<AnyNdf> g2_ndfs(const Scene& scene, const NdfRegistry& ndfs) {
    std::vector<AnyNdf> out;
    if (scene.g2.include.empty()) return out;
    for (const std::string& family : scene.g2.families)
        for (double a : scene.alphas) out.push_back(ndfs.make(family, {{"alpha", a}}));
    return out;
}

// The exact G2's Lambdas come by quadrature where there is no closed form.
void require_g2_domain(const std::vector<AnyNdf>& ndfs, const std::vector<double>& mus) {
    for (const AnyNdf& ndf : ndfs)
        if (!ndf.has_closed_Lambda())
            for (double mu : mus) try {
                    require_quadrature_domain(ndf, mu);
                } catch (const input_error& e) {
                    throw input_error("scene: g2.mu = " + format_g17(mu) + " for " + ndf.spec() + ": " + e.what());
                }
}

void measure_on(G2Row& row, const AnyNdf& ndf, const std::vector<double>& mus, ReferenceCache& cache) {
    const LambdaRoute route = ndf.has_closed_Lambda() ? LambdaRoute::closed : LambdaRoute::q1d_boost;
    for (double mi : mus)
        for (double mo : mus) {
            const double want = 1.0 / (1.0 + cache.get(ndf, mi, route) + cache.get(ndf, mo, route));
            const double d = std::abs(row.variant.G2(ndf, mi, mo) - want);
            row.grid.push_back({ndf, mi, mo});
            row.sum_d += d;
            if (d >= row.max_d) {
                row.max_d = d;
                row.worst_at = ndf.spec() + " mu_i=" + format_g17(mi) + " mu_o=" + format_g17(mo);
            }
        }
}

}  // namespace

G2Table g2_table(const Scene& scene, const NdfRegistry& ndfs) {
    G2Table table{.ndfs = g2_ndfs(scene, ndfs), .rows = {}};
    require_g2_domain(table.ndfs, scene.g2.mus);
    for (const G2Variant& v : builtin_G2_variants())
        if (std::any_of(scene.g2.include.begin(), scene.g2.include.end(), [&](const auto& p) { return glob_match(p, v.name); }))
            table.rows.push_back(G2Row{.variant = v, .grid = {}, .worst_at = {}});
    return table;
}

void measure_g2(G2Table& table, const std::vector<double>& mus, ReferenceCache& cache) {
    for (G2Row& row : table.rows) {
        std::fprintf(stderr, "report: G2 %s\n", row.variant.name.c_str());
        for (const AnyNdf& ndf : table.ndfs)
            if (row.variant.applies(ndf)) measure_on(row, ndf, mus, cache);
    }
}

void add_g2_timing(G2Table& table, std::vector<Timed>& timed) {
    for (G2Row& r : table.rows) {
        const std::vector<G2Point> sample = sample_of(r.grid);
        timed.push_back({r.variant.name, sample.size(),
                         [G2 = r.variant.G2, sample](std::size_t k) { return G2(sample[k].ndf, sample[k].mu_i, sample[k].mu_o); },
                         &r.ns});
    }
}

void write_g2_table(const G2Table& table, const fs::path& dir) {
    if (table.rows.empty()) return;
    std::ofstream csv(dir / "g2_variants.csv");
    write_csv_record(csv, {"variant", "points", "max_abs_dG2", "mean_abs_dG2", "worst_at", "ns_per_eval", "description"});
    std::ofstream md(dir / "report.md", std::ios::app);
    md << "\n## G2 variants (two directions, reflection)\n\nAgainst the exact height-correlated G2 = 1/(1 + Lambda_i + "
          "Lambda_o), on alpha x mu_i x mu_o.\n\n| variant | points | max abs dG2 | mean abs dG2 | ns/eval | worst at |\n"
          "|---|---:|---:|---:|---:|---|\n";
    for (const G2Row& r : table.rows) {
        const std::size_t n = r.grid.size();
        write_csv_record(csv, {r.variant.name, std::to_string(n), format_g17(r.max_d), n ? format_g17(r.sum_d / n) : "",
                               r.worst_at, format_g17(r.ns), r.variant.description});
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %zu | %.2e | %.2e | %.0f | %s |\n", r.variant.name.c_str(), n, r.max_d,
                      n ? r.sum_d / n : NAN, r.ns, r.worst_at.c_str());
        md << line;
    }
}

}  // namespace smithlab::report
