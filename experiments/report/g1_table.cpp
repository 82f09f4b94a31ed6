#include "report/g1_table.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "output/ndf_columns.hpp"
#include "output/staged_directory.hpp"
#include "report/scene.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/family_stream.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

double G1_of(double L) { return std::isinf(L) ? 0.0 : 1.0 / (1.0 + L); }

bool matches_any(const std::vector<std::string>& patterns, const std::string& name) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return glob_match(p, name); });
}

void add_grid_ndfs(const std::vector<scene::NdfEntry>& entries, const std::vector<double>& alphas,
                   const NdfRegistry& ndfs, G1Table& table) {
    for (const scene::NdfEntry& e : entries) {
        if (e.roughness_given) {
            for (const scene::ParamPoint& p : e.points()) {
                table.ndfs.push_back(scene::make_entry_ndf(e, ndfs, p, std::nullopt));
                table.alphas.push_back(table.ndfs.back().has_param("alpha") ? table.ndfs.back().param("alpha") : NAN);
            }
            continue;
        }
        for (double a : alphas)
            for (const scene::ParamPoint& p : e.points()) {
                table.ndfs.push_back(scene::make_entry_ndf(e, ndfs, p, a));
                table.alphas.push_back(a);
            }
    }
}

// One point's |dG1| (and relative error of Lambda, rel: NaN where not measured), folded into its row.
void add_error(G1Row& row, std::size_t ndf, double mu, double dG1, double rel, bool keep_errors) {
    if (keep_errors) row.errors.push_back({ndf, mu, dG1, rel});
    ++row.points;
    row.sum_dG1 += dG1;
    row.max_dG1 = std::max(row.max_dG1, dG1);
}

// A Lambda row's point: the worst is the largest relative error of Lambda where the reference is >= DBL_MIN.
void add_point(G1Row& row, std::size_t ndf, double mu, double got, double want, bool keep_errors) {
    add_error(row, ndf, mu, std::abs(G1_of(got) - G1_of(want)), want >= DBL_MIN ? std::abs(got - want) / want : NAN,
              keep_errors);
    if (want < DBL_MIN) return;
    const double rel = std::isinf(got) ? INFINITY : std::abs(got - want) / want;
    if (rel > row.max_rel || std::isnan(rel)) {
        row.max_rel = rel;
        row.worst_ndf = ndf;
        row.worst_mu = mu;
    }
}

// The stream's point: G1 only; the worst is the largest |dG1|.
void add_stream_point(G1Row& row, std::size_t ndf, double mu, double G1, double want, bool keep_errors) {
    const double dG1 = std::abs(G1 - G1_of(want));
    if (row.points == 0 || dG1 > row.max_dG1) row.worst_ndf = ndf, row.worst_mu = mu;
    add_error(row, ndf, mu, dG1, NAN, keep_errors);
}

void measure_one_call(G1Row& row, const G1Table& table, std::size_t n, const std::vector<double>& mus,
                      ReferenceCache& cache, bool keep_errors) {
    const AnyNdf& ndf = table.ndfs[n];
    const LambdaRoute route = route_for(*row.variant, ndf);
    row.prepared.push_back(prepare(*row.variant, ndf));
    for (double mu : mus) {
        const double want = cache.get(ndf, mu, route);
        add_point(row, n, mu, row.prepared.back()(mu), want, keep_errors);
    }
}

void measure_stream(G1Row& row, const G1Table& table, std::size_t n, const std::vector<double>& mus,
                    ReferenceCache& cache, bool keep_errors) {
    const AnyNdf& ndf = table.ndfs[n];
    const std::vector<double> alpha(mus.size(), ndf.param("alpha")), gamma(mus.size(), ndf.param("gamma"));
    std::vector<double> G1(mus.size());
    GtrFamilyStream::get().G1_up(alpha.data(), gamma.data(), mus.data(), G1.data(), mus.size());
    const LambdaRoute route = route_for(*row.variant, ndf);
    for (std::size_t i = 0; i < mus.size(); ++i)
        add_stream_point(row, n, mus[i], G1[i], cache.get(ndf, mus[i], route), keep_errors);
}

std::string worst_at(const G1Row& r, const G1Table& table) {
    if (std::isnan(r.worst_mu)) return "";
    return table.ndfs[r.worst_ndf].spec() + " mu=" + format_g17(r.worst_mu);
}

void write_csv(const G1Table& table, const fs::path& dir) {
    const output::NdfColumns params = output::ndf_columns(table.ndfs);
    std::vector<std::string> head = {"variant",  "points",      "max_abs_dG1", "mean_abs_dG1", "max_rel_dLambda",
                                     "worst_at", "ns_per_eval", "description", "worst_ndf",    "worst_mu"};
    for (const std::string& p : params.names) head.push_back("worst_" + p);
    std::ofstream csv(dir / "variants.csv");
    write_csv_record(csv, head);
    for (const G1Row& r : table.rows) {
        std::vector<std::string> f = {r.name(), std::to_string(r.points), "", "", "", "", "", r.description(), "", ""};
        const bool located = r.points > 0 && !std::isnan(r.worst_mu);
        if (r.points > 0) {  // else selected, but it applies to no NDF of this scene
            f = {r.name(),
                 std::to_string(r.points),
                 format_g17(r.max_dG1),
                 format_g17(r.sum_dG1 / r.points),
                 r.stream ? "" : format_g17(r.max_rel),
                 worst_at(r, table),
                 format_g17(r.ns),
                 r.description(),
                 located ? table.ndfs[r.worst_ndf].spec() : "",
                 located ? format_g17(r.worst_mu) : ""};
        }
        for (const std::string& cell : params.cells(table.ndfs[r.worst_ndf])) f.push_back(located ? cell : "");
        write_csv_record(csv, f);
    }
    output::finish(csv, dir / "variants.csv");
}

void write_markdown(const G1Table& table, const std::vector<double>& alphas, const std::vector<double>& mus,
                    const fs::path& dir) {
    std::ofstream md(dir / "report.md", std::ios::app);
    md << "Grid: " << alphas.size() << " alpha x " << mus.size() << " mu per NDF, " << table.ndfs.size()
       << " NDFs. Reference: the closed form where the NDF has one, else a different quadrature route than the "
          "variant's (Boost 1D at 1e-13, or the nested 2D route for the Boost 1D variants); never the variant's own "
          "(closed-form: Boost 1D; table: Boost 1D or 2D). Sorted by cost.\n\n"
       << "| variant | points | max abs dG1 | mean abs dG1 | max rel dLambda | ns/eval | worst at |\n"
       << "|---|---:|---:|---:|---:|---:|---|\n";
    for (const G1Row& r : table.rows) {
        if (r.points == 0) {
            md << "| " << r.name() << " | 0 | | | | | applies to no NDF of this scene |\n";
            continue;
        }
        const std::string rel = r.stream ? "(G1 only)" : format_printf("%.2e", r.max_rel);
        md << format_printf("| %s | %zu | %.2e | %.2e | %s | %.0f | %s |\n", r.name().c_str(), r.points, r.max_dG1,
                            r.sum_dG1 / r.points, rel.c_str(), r.ns, worst_at(r, table).c_str());
    }
    output::finish(md, dir / "report.md");
}

}  // namespace

std::string G1Row::description() const {
    if (!stream) return variant->description;
    return "the family evaluator as a stream (family_stream.hpp): G1 at many points a call, eight at a time where the "
           "CPU has AVX-512, four where it has AVX2; measured in G1 only";
}

G1Table g1_table(const std::vector<scene::NdfEntry>& entries, const std::vector<double>& alphas,
                 const NdfRegistry& ndfs, const VariantRegistry& variants, const std::vector<std::string>& include,
                 const std::vector<std::string>& exclude) {
    G1Table table;
    add_grid_ndfs(entries, alphas, ndfs, table);
    for (const LambdaVariant& v : variants.list())
        if (matches_any(include, v.name) && !matches_any(exclude, v.name)) {
            table.rows.emplace_back().variant = &v;
            if (v.name == "family") {
                table.rows.emplace_back().variant = &v;
                table.rows.back().stream = true;
            }
        }
    if (table.rows.empty()) throw input_error("scene selects no variant (see smithlab eval --list-methods)");
    for (G1Row& row : table.rows)
        for (std::size_t n = 0; n < table.ndfs.size(); ++n)
            if (row.variant->applies(table.ndfs[n])) row.ndfs.push_back(n);
    return table;
}

void require_g1_domain(const G1Table& table, const std::vector<double>& mus) {
    for (double mu : mus) require(mu > 0.0 && std::isfinite(mu), "scene: grid.mu", "finite and > 0", mu);
    for (const G1Row& row : table.rows)
        for (std::size_t n : row.ndfs)
            for (double mu : mus) try {
                    require_row_domain(*row.variant, table.ndfs[n], mu);
                } catch (const input_error& e) {
                    throw input_error("scene: grid.mu = " + format_g17(mu) + " for " + table.ndfs[n].spec() +
                                      " (variant " + row.variant->name + "): " + e.what());
                }
}

void measure_g1(G1Table& table, const std::vector<double>& mus, ReferenceCache& cache, bool keep_errors) {
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        G1Row& row = table.rows[i];
        std::fprintf(stderr, "report: [%zu/%zu] %s\n", i + 1, table.rows.size(), row.name().c_str());
        for (std::size_t n : row.ndfs)
            row.stream ? measure_stream(row, table, n, mus, cache, keep_errors)
                       : measure_one_call(row, table, n, mus, cache, keep_errors);
    }
}

void add_g1_timing(G1Table& table, const std::vector<double>& mus, Timing& timing) {
    for (G1Row& r : table.rows) {
        if (!r.stream) {
            timing.add(r.name(), lambda_timing_points(r.prepared, mus), lambda_point_value, &r.ns);
            continue;
        }
        std::vector<AnyNdf> ndfs;
        for (std::size_t n : r.ndfs) ndfs.push_back(table.ndfs[n]);
        GtrStreamPoints points = gtr_stream_timing_points(ndfs, mus);
        const std::size_t n = points.size();
        timing.add_stream(
            r.name(), n, [points = std::move(points)](double* out) { points.G1(out); }, &r.ns);
    }
}

void write_g1_table(G1Table& table, const std::vector<double>& alphas, const std::vector<double>& mus,
                    const fs::path& dir) {
    // By cost; a row not timed (it applies to no NDF of the scene) last.
    std::stable_sort(table.rows.begin(), table.rows.end(), [](const G1Row& a, const G1Row& b) {
        return a.ns < b.ns || (!std::isnan(a.ns) && std::isnan(b.ns));
    });
    write_csv(table, dir);
    write_markdown(table, alphas, mus, dir);
}

void write_g1_points(const G1Table& table, const fs::path& dir) {
    fs::create_directories(dir / "points");
    for (const G1Row& row : table.rows) {
        if (row.errors.empty()) continue;
        std::vector<AnyNdf> ndfs;
        for (std::size_t n : row.ndfs) ndfs.push_back(table.ndfs[n]);
        const output::NdfColumns params = output::ndf_columns(ndfs, {"alpha", "gamma"});
        std::vector<std::string> head = {"alpha", "gamma", "mu", "abs_dG1", "rel_dLambda"};
        head.insert(head.end(), params.names.begin(), params.names.end());
        std::ofstream out(dir / "points" / (row.name() + ".csv"));
        write_csv_record(out, head);
        for (const PointError& e : row.errors) {
            const AnyNdf& ndf = table.ndfs[e.ndf];
            std::vector<std::string> f = {format_g17(table.alphas[e.ndf]),
                                          format_g17(ndf.has_param("gamma") ? ndf.param("gamma") : NAN),
                                          format_g17(e.mu), format_g17(e.dG1), format_g17(e.rel)};
            for (const std::string& cell : params.cells(ndf)) f.push_back(cell);
            write_csv_record(out, f);
        }
        output::finish(out, dir / "points" / (row.name() + ".csv"));
    }
}

}  // namespace smithlab::report
