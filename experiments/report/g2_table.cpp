#include "report/g2_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "output/ndf_columns.hpp"
#include "output/staged_directory.hpp"
#include "report/scene.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

std::vector<AnyNdf> g2_ndfs(const std::vector<std::string>& families, const std::vector<double>& alphas,
                            const NdfRegistry& ndfs) {
    std::vector<AnyNdf> out;
    for (const std::string& family : families)
        for (double a : alphas) out.push_back(ndfs.make(family, {{"alpha", a}}));
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
                row.worst = row.grid.size() - 1;
            }
        }
}

std::string worst_at(const G2Row& r) {
    if (r.grid.empty()) return "";
    const G2Point& p = r.grid[r.worst];
    return p.ndf.spec() + " mu_i=" + format_g17(p.mu_i) + " mu_o=" + format_g17(p.mu_o);
}

// A row's cells: the table's, then where its worst point is (the NDF, one column per parameter, mu_i and mu_o).
std::vector<std::string> csv_fields(const G2Row& r, const output::NdfColumns& params) {
    const std::size_t n = r.grid.size();
    std::vector<std::string> f = {
        r.variant.name, std::to_string(n), format_g17(r.max_d),  n ? format_g17(r.sum_d / n) : "",
        worst_at(r),    format_g17(r.ns),  r.variant.description};
    if (n == 0) {
        f.resize(f.size() + 3 + params.names.size());
        return f;
    }
    const G2Point& p = r.grid[r.worst];
    f.push_back(p.ndf.spec());
    for (const std::string& cell : params.cells(p.ndf)) f.push_back(cell);
    f.push_back(format_g17(p.mu_i));
    f.push_back(format_g17(p.mu_o));
    return f;
}

}  // namespace

G2Table g2_table(const std::vector<std::string>& include, const std::vector<std::string>& families,
                 const std::vector<double>& alphas, const std::vector<double>& mus, const NdfRegistry& ndfs) {
    for (double mu : mus) require(mu > 0.0 && std::isfinite(mu), "scene: g2.mu", "finite and > 0", mu);
    if (include.empty()) return {};
    G2Table table{.ndfs = g2_ndfs(families, alphas, ndfs), .rows = {}};
    require_g2_domain(table.ndfs, mus);
    for (const G2Variant& v : builtin_G2_variants())
        if (std::any_of(include.begin(), include.end(), [&](const auto& p) { return glob_match(p, v.name); }))
            table.rows.push_back(G2Row{.variant = v, .grid = {}});
    return table;
}

void measure_g2(G2Table& table, const std::vector<double>& mus, ReferenceCache& cache) {
    for (G2Row& row : table.rows) {
        std::fprintf(stderr, "report: G2 %s\n", row.variant.name.c_str());
        for (const AnyNdf& ndf : table.ndfs)
            if (row.variant.applies(ndf)) measure_on(row, ndf, mus, cache);
    }
}

void add_g2_timing(G2Table& table, Timing& timing) {
    for (G2Row& r : table.rows) {
        std::vector<G2Point> points;
        for (const GridIndex& i : timing_points(1, r.grid.size())) points.push_back(r.grid[i.mu]);
        timing.add(
            r.variant.name, std::move(points),
            [G2 = r.variant.G2](const G2Point& p) { return G2(p.ndf, p.mu_i, p.mu_o); }, &r.ns);
    }
}

void write_g2_table(const G2Table& table, const fs::path& dir) {
    if (table.rows.empty()) return;
    const output::NdfColumns params = output::ndf_columns(table.ndfs);
    std::vector<std::string> head = {"variant",  "points",      "max_abs_dG2", "mean_abs_dG2",
                                     "worst_at", "ns_per_eval", "description", "worst_ndf"};
    for (const std::string& p : params.names) head.push_back("worst_" + p);
    head.push_back("worst_mu_i");
    head.push_back("worst_mu_o");
    std::ofstream csv(dir / "g2_variants.csv");
    write_csv_record(csv, head);
    std::ofstream md(dir / "report.md", std::ios::app);
    md << "\n## G2 variants (two directions, reflection)\n\nAgainst the exact height-correlated G2 = 1/(1 + Lambda_i + "
          "Lambda_o), on alpha x mu_i x mu_o.\n\n| variant | points | max abs dG2 | mean abs dG2 | ns/eval | worst at "
          "|\n"
          "|---|---:|---:|---:|---:|---|\n";
    for (const G2Row& r : table.rows) {
        const std::size_t n = r.grid.size();
        write_csv_record(csv, csv_fields(r, params));
        md << format_printf("| %s | %zu | %.2e | %.2e | %.0f | %s |\n", r.variant.name.c_str(), n, r.max_d,
                            n ? r.sum_d / n : NAN, r.ns, worst_at(r).c_str());
    }
    output::finish(csv, dir / "g2_variants.csv");
    output::finish(md, dir / "report.md");
}

}  // namespace smithlab::report
