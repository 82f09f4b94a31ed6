#include "report/walk_section.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <thread>
#include <variant>

#include "output/ndf_columns.hpp"
#include "output/progress.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/walk/trace.hpp"
#include "trace/capped_walks.hpp"
#include "trace/cell_jobs.hpp"

namespace smithlab::report {

namespace fs = std::filesystem;

namespace {

// The albedo of orders 2 and up. Each walk puts its weight in exactly one bin (tally.hpp), so the moments of the
// union are the sums of its bins' and its standard error is exact.
walk::Estimate multiple_scattering(const walk::AlbedoTally& t) {
    walk::Moments m;
    for (int h = 0; h < 2; ++h)
        for (int o = 1; o < walk::order_bins; ++o)
            for (int c = 0; c < 2; ++c) m.merge(t.bins[walk::AlbedoTally::index(h, o, c)]);
    return walk::estimate(m, t.walks);
}

std::array<walk::Estimate, walk_orders.size()> by_order(const walk::AlbedoTally& t) {
    const auto of = [&](int order) { return t.albedo(walk::Hemisphere::all, order, walk::Component::all); };
    return {of(0), of(1), of(2), of(3), multiple_scattering(t), of(walk::all_orders)};
}

// "ggx", "gtr (gamma 1.5)": the NDF as the table's rows name it, alpha apart.
std::string family_label(const WalkCell& c) {
    std::string out;
    for (const auto& [name, v] : c.params) out += (out.empty() ? "" : ", ") + name + " " + format_shortest(v);
    return out.empty() ? c.family : c.family + " (" + out + ")";
}

std::string cell_name(const WalkCell& c) {
    return "walk cell " + std::to_string(c.index) + " (" + c.ndf.spec() + ", " + c.material.spec() + ", theta_i " +
        format_shortest(c.theta_i) + ")";
}

// Says on stderr which cells had walks cut short; refuses the first whose capped walks could carry more than its
// albedo's standard error (the last of walk_orders: every order).
void answer_capped(const std::vector<WalkResult>& results, std::int64_t walks) {
    std::int64_t cells = 0, capped = 0;
    for (const WalkResult& r : results) {
        const walk::Estimate& all = r.albedo.back();
        if (trace::capped_beyond_error(r.capped, walks, all.stderr_))
            throw input_error(r.cell.where + " '" + r.cell.family + "': " + cell_name(r.cell) + ": " +
                              trace::capped_text(r.capped, walks) + "; the energy they would have carried out (up to " +
                              format_shortest(static_cast<double>(r.capped) / static_cast<double>(walks)) +
                              " of the albedo) could exceed its standard error (" + format_shortest(all.stderr_) +
                              "), so it is no estimate");
        cells += r.capped > 0;
        capped += r.capped;
    }
    if (capped > 0)
        std::fprintf(stderr,
                     "report: warning: walk section: %lld cells with walks cut short, %lld walks in all (the cap: "
                     "%lld facet events a walk), each within its albedo's standard error (report.md counts them)\n",
                     static_cast<long long>(cells), static_cast<long long>(capped),
                     static_cast<long long>(walk::WalkLimits{}.max_events));
}

}  // namespace

std::vector<WalkCell> walk_cells(const WalkScene& w, const NdfRegistry& registry) {
    std::vector<walk::Material> materials;
    for (const std::string& m : w.materials) materials.push_back(registry.materials().make(m));  // checked by the scene
    std::vector<WalkCell> cells;
    for (const scene::NdfEntry& e : w.ndfs)
        for (const scene::ParamPoint& p : e.points()) {
            const std::vector<std::optional<double>> alphas = e.roughness_given
                ? std::vector<std::optional<double>>{std::nullopt}
                : std::vector<std::optional<double>>(w.alphas.begin(), w.alphas.end());
            for (const std::optional<double>& a : alphas) {
                const AnyNdf ndf = scene::make_entry_ndf(e, registry, p, a);
                try {
                    make_surface(ndf);  // its tables may refuse it
                } catch (const input_error& err) {
                    throw input_error(e.where + " '" + e.family + "' at " + ndf.spec() + ": " + err.what());
                }
                // The label's parameters: all but alpha (its own column), and but the one alpha set.
                const NdfInfo& info = *registry.find(e.family);
                const std::string set_by_alpha = a && info.roughness ? info.roughness->parameter : "alpha";
                scene::ParamPoint shown;
                for (const auto& [name, v] : ndf.parts().params)
                    if (name != "alpha" && name != set_by_alpha) shown.emplace_back(name, v);
                const double alpha = a ? *a : ndf.has_param("alpha") ? ndf.param("alpha") : NAN;
                for (const walk::Material& m : materials)
                    for (double t : w.theta_i)
                        cells.push_back({cells.size(), e.family, shown, alpha, ndf, m, t, e.where});
            }
        }
    return cells;
}

std::vector<WalkResult> trace_walk_cells(const std::vector<WalkCell>& cells, const WalkScene& w) {
    std::vector<trace::CellJob> jobs;
    for (const WalkCell& c : cells) {
        walk::CellRequest r;
        r.seed = w.seed;
        r.walks = w.walks;
        r.wi = direction_from_deg(c.theta_i, 0.0);
        r.cell = c.index;
        jobs.push_back({c.ndf, c.material, r, cell_name(c)});
    }
    std::vector<std::optional<WalkResult>> done(cells.size());
    trace::CellJobs plan(std::move(jobs), {}, [&](std::size_t i, walk::CellPartial&& total) {
        done[i] = WalkResult{cells[i], by_order(total.albedo), total.albedo.events, total.albedo.capped};
    });
    output::ProgressLine progress;
    cluster::run_jobs(plan, 0, [&](std::uint64_t merged, std::uint64_t all) {
        progress(static_cast<double>(merged) / static_cast<double>(all),
                 [&] { return "report: walk section, " + std::to_string(merged * 100 / all) + "% of the walks"; });
    });
    std::vector<WalkResult> out;  // rank 0's; none on the others
    for (std::optional<WalkResult>& r : done)
        if (r) out.push_back(std::move(*r));
    answer_capped(out, w.walks);
    return out;
}

namespace {

void write_walk_csv(const std::vector<WalkResult>& results, const WalkScene& w, const fs::path& dir) {
    std::vector<AnyNdf> ndfs;
    for (const WalkResult& r : results) ndfs.push_back(r.cell.ndf);
    const output::NdfColumns params = output::ndf_columns(ndfs, {"alpha", "gamma"});
    std::vector<std::string> head = {"ndf",   "family", "gamma",  "alpha", "material", "theta_i",
                                     "order", "albedo", "stderr", "walks", "label"};
    head.insert(head.end(), params.names.begin(), params.names.end());
    std::ofstream csv(dir / "walk_albedo.csv");
    write_csv_record(csv, head);
    for (const WalkResult& r : results) {
        const WalkCell& c = r.cell;
        const std::vector<std::string> param_cells = params.cells(c.ndf);
        for (std::size_t o = 0; o < walk_orders.size(); ++o) {
            std::vector<std::string> f = {c.ndf.spec(),
                                          c.family,
                                          c.ndf.has_param("gamma") ? format_g17(c.ndf.param("gamma")) : "",
                                          format_g17(c.alpha),
                                          c.material.spec(),
                                          format_shortest(c.theta_i),
                                          walk_orders[o],
                                          format_g17(r.albedo[o].value),
                                          format_g17(r.albedo[o].stderr_),
                                          std::to_string(w.walks),
                                          family_label(c)};
            f.insert(f.end(), param_cells.begin(), param_cells.end());
            write_csv_record(csv, f);
        }
    }
    output::finish(csv, dir / "walk_albedo.csv");
}

void write_walk_markdown(const std::vector<WalkResult>& results, const WalkScene& w, double seconds,
                         const fs::path& dir) {
    std::int64_t events = 0, capped = 0;
    for (const WalkResult& r : results) {
        events += r.events;
        capped += r.capped;
    }
    std::ofstream md(dir / "report.md", std::ios::app);
    const std::string threads = std::to_string(util::thread_count(0)) + " threads",
                      where = cluster::mpi::size() > 1
        ? std::to_string(cluster::mpi::size()) + " MPI ranks x " + threads
        : threads;
    md << format_printf(
              "\n## Multiple scattering: albedo by scattering order (path-traced)\n\nThe Smith microsurface traced "
              "by smithlab's random walk (Heitz, Hanika, d'Eon and Dachsbacher 2016, alg. 1-3: uniform heights, "
              "Smith's downward Lambda, hit normals the visible normals of the ray): the fraction of the incident "
              "energy that leaves after exactly 1, 2, 3 and 4 or more facet events, %lld walks per cell (seed %llu), "
              "+- one standard error. **lost** = orders 2+: the energy a single-scattering BRDF drops, 1 - order 1 "
              "where the facets absorb nothing (mirror, lambert(albedo=1)), what a multiple-scattering model must "
              "restore. %zu cells, %.3g walks, %.3g events (%lld walks capped), %.1f s on %s.\n\n"
              "![](walk_albedo.png)\n\n",
              static_cast<long long>(w.walks), w.seed, results.size(), static_cast<double>(results.size()) * w.walks,
              static_cast<double>(events), static_cast<long long>(capped), seconds, where.c_str())
       << "| ndf | material | alpha | theta_i | order 1 | order 2 | order 3 | order 4+ | lost (2+) | all |\n"
       << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const WalkResult& r : results) {
        md << "| " << family_label(r.cell) << " | " << r.cell.material.spec() << " | " << format_shortest(r.cell.alpha)
           << " | " << format_shortest(r.cell.theta_i);
        for (const walk::Estimate& e : r.albedo) md << format_printf(" | %.5f +- %.5f", e.value, e.stderr_);
        md << " |\n";
    }
    output::finish(md, dir / "report.md");
}

}  // namespace

void write_walk_section(const std::vector<WalkResult>& results, const WalkScene& w, double seconds,
                        const fs::path& dir) {
    write_walk_csv(results, w, dir);
    write_walk_markdown(results, w, seconds, dir);
}

}  // namespace smithlab::report
