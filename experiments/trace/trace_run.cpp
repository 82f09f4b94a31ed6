#include "trace/trace_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>

#include "cluster/mpi_world.hpp"
#include "cluster/traffic_json.hpp"
#include "output/progress.hpp"
#include "output/staged_directory.hpp"
#include "scene/walk_options.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/util/parallel.hpp"
#include "smithlab/walk/trace.hpp"
#include "trace/capped_walks.hpp"
#include "trace/cell_file.hpp"
#include "trace/cell_jobs.hpp"
#include "trace/trace_meta.hpp"
#include "trace/trace_rows.hpp"

namespace smithlab::trace {

namespace fs = std::filesystem;

namespace {

// A cell with its specs checked and in canonical form, and the key its cell file must carry.
struct Prepared {
    TraceCell cell;
    AnyNdf ndf;
    walk::Material material;
    std::string key;
};

// Every NDF of the scene made once by the registry, and its microsurface prepared once (a D-only NDF's table may
// refuse it); an NDF's note goes to stderr, from rank 0 alone.
std::map<std::string, AnyNdf> checked_ndfs(const std::vector<SceneNdf>& scene_ndfs, const NdfRegistry& registry,
                                           const walk::MicrosurfaceOptions& opts) {
    std::map<std::string, AnyNdf> ndfs;
    for (const SceneNdf& n : scene_ndfs)
        if (!ndfs.count(n.spec)) {
            const AnyNdf& ndf = ndfs.emplace(n.spec, n.make(registry)).first->second;
            if (!ndf.note().empty() && cluster::mpi::rank() == 0)
                std::fprintf(stderr, "trace: note: %s\n", ndf.note().c_str());
            make_surface(ndf, opts);
        }
    return ndfs;
}

std::map<std::string, walk::Material> parsed_materials(const std::vector<std::string>& specs,
                                                       const MaterialRegistry& registry) {
    std::map<std::string, walk::Material> materials;
    for (const std::string& spec : specs) materials.emplace(spec, registry.make(spec));
    return materials;
}

// The cells with their NDF, material and cell-file key; light from below (theta_i > 90) is refused for any material
// but a dielectric.
std::vector<Prepared> prepare_cells(const std::vector<TraceCell>& cells, const std::map<std::string, AnyNdf>& ndfs,
                                    const std::map<std::string, walk::Material>& materials, const CellSettings& w,
                                    const std::string& source) {
    std::vector<Prepared> prepared;
    for (const TraceCell& c : cells) {
        const AnyNdf& ndf = ndfs.at(c.ndf);
        const walk::Material& m = materials.at(c.material);
        if (c.theta_i > 90.0 && !m.transmits())
            throw input_error(source + ": theta_i = " + format_shortest(c.theta_i) +
                              " is light from below the surface, which '" + m.spec() +
                              "' facets never see (only a dielectric takes it; theta_i < 90 for the others)");
        prepared.push_back({c, ndf, m, cell_key(w, c, ndf, m)});
    }
    return prepared;
}

// The request of one cell: the scene's walks, seed, max_order and brdf bins, with the cell's direction, index (its
// random stream) and hemispheres.
walk::CellRequest request_for(const CellSettings& w, const Prepared& p) {
    walk::CellRequest r;
    r.seed = w.seed;
    r.walks = w.walks;
    r.limits.max_order = w.max_order;
    r.brdf = w.brdf;
    r.wi = direction_from_deg(p.cell.theta_i, p.cell.phi_i);
    r.cell = p.cell.index;
    r.brdf.transmission = p.material.transmits();
    return r;
}

// "cell 12 (ggx(alpha=0.3), mirror, theta_i 45, phi_i 0)": a cell in messages.
std::string cell_name(const Prepared& p) {
    return "cell " + std::to_string(p.cell.index) + " (" + p.ndf.spec() + ", " + p.material.spec() + ", theta_i " +
        format_shortest(p.cell.theta_i) + ", phi_i " + format_shortest(p.cell.phi_i) + ")";
}

std::vector<CellJob> cell_jobs(const std::vector<Prepared>& prepared, const CellSettings& w) {
    std::vector<CellJob> jobs;
    for (const Prepared& p : prepared) jobs.push_back({p.ndf, p.material, request_for(w, p), cell_name(p)});
    return jobs;
}

// Rank 0: the rows of the cells an earlier run finished (OUT/cells, when the key matches), those jobs marked as not
// needed; says on stderr how many it reused.
std::vector<std::optional<CellRows>> reuse_cells(const fs::path& out, const std::vector<Prepared>& prepared,
                                                 const walk::BrdfBins& bins, std::vector<CellJob>& jobs) {
    fs::create_directories(out / "cells");
    std::vector<std::optional<CellRows>> done(prepared.size());
    std::int64_t reused = 0;
    for (std::size_t i = 0; i < prepared.size(); ++i) {
        const Prepared& p = prepared[i];
        done[i] = read_cell(cell_path(out, p.cell.index), p.key, albedo_row_count(),
                            brdf_row_count(bins, p.material.transmits()));
        jobs[i].needed = !done[i];
        reused += done[i].has_value();
    }
    if (reused)
        std::fprintf(stderr, "trace: %lld of %lld cells reused from %s\n", static_cast<long long>(reused),
                     static_cast<long long>(prepared.size()), (out / "cells").string().c_str());
    return done;
}

// The progress line: "trace: 3 of 48 cells done on 2 ranks, 12% of the walks".
std::string progress_text(std::int64_t traced, std::int64_t to_trace, std::uint64_t merged, std::uint64_t all) {
    const std::string ranks = cluster::mpi::size() > 1 ? " on " + std::to_string(cluster::mpi::size()) + " ranks" : "";
    return format_printf("trace: %lld of %lld cells done%s, %.0f%% of the walks", static_cast<long long>(traced),
                         static_cast<long long>(to_trace), ranks.c_str(),
                         100.0 * static_cast<double>(merged) / static_cast<double>(all));
}

// Traces the needed jobs on every rank (cluster/block_jobs.hpp); on rank 0 each finished cell's rows go to done[i]
// and at once to its cell file. Returns what rank 0 saw of the other ranks; `traced` counts the cells traced.
cluster::Traffic trace_cells(std::vector<CellJob> jobs, const walk::MicrosurfaceOptions& opts,
                             const std::vector<Prepared>& prepared, std::int64_t walks, const fs::path& out,
                             std::vector<std::optional<CellRows>>& done, unsigned threads, std::int64_t& traced) {
    std::int64_t to_trace = 0;
    for (const CellJob& j : jobs) to_trace += j.needed;
    std::atomic<std::int64_t> finished{0};  // finish runs beside the progress line (cluster/block_jobs.hpp)
    CellJobs plan(std::move(jobs), opts, [&](std::size_t i, walk::CellPartial&& total) {
        const Prepared& p = prepared[i];
        done[i] = cell_rows(cell_label(p.ndf, p.material, p.cell, walks),
                            walk::CellResult{std::move(total.albedo), std::move(total.brdf)});
        write_cell(cell_path(out, p.cell.index), p.key, *done[i]);
        ++finished;
    });
    output::ProgressLine progress;
    const cluster::Traffic traffic = cluster::run_jobs(plan, threads, [&](std::uint64_t merged, std::uint64_t all) {
        progress(static_cast<double>(merged) / static_cast<double>(all),
                 [&] { return progress_text(finished.load(), to_trace, merged, all); });
    });
    traced = finished;
    return traffic;
}

// Rank 0, every cell finished: says on stderr which cells had walks cut short (trace/capped_walks.hpp), and refuses
// the run (input_error, nothing published; the cell files stay) when any cell's capped walks could carry more than
// its albedo's standard error.
void answer_capped(const std::vector<Prepared>& prepared, const std::vector<std::optional<CellRows>>& done,
                   std::int64_t walks, const fs::path& out) {
    constexpr std::size_t shown = 5;  // cells named in the warning
    std::vector<std::size_t> capped;
    for (std::size_t i = 0; i < prepared.size(); ++i)
        if (done[i]->capped > 0) capped.push_back(i);
    for (std::size_t i : capped)
        if (capped_beyond_error(done[i]->capped, walks, done[i]->total.stderr_))
            throw input_error(
                "trace: " + cell_name(prepared[i]) + ": " + capped_text(done[i]->capped, walks) +
                "; the energy they would have carried out (up to " +
                format_shortest(static_cast<double>(done[i]->capped) / static_cast<double>(walks)) +
                " of the albedo) could exceed the albedo's standard error (" + format_shortest(done[i]->total.stderr_) +
                "), so it is no estimate: nothing written (cells with capped walks: " + std::to_string(capped.size()) +
                "; the traced cells stay in " + (out / "cells").string() + ")");
    for (std::size_t k = 0; k < std::min(capped.size(), shown); ++k)
        std::fprintf(stderr, "trace: warning: %s: %s, within the albedo's standard error (meta.json capped_walks)\n",
                     cell_name(prepared[capped[k]]).c_str(), capped_text(done[capped[k]]->capped, walks).c_str());
    if (capped.size() > shown)
        std::fprintf(stderr, "trace: warning: and %zu more cells with capped walks (meta.json capped_walks)\n",
                     capped.size() - shown);
}

// Rank 0, every cell finished: albedo.csv and brdf.csv in dir, and what meta.json lists of the cells; adds the
// bounces and each cell's total to sum.
RunMeta write_outputs(const fs::path& dir, const std::vector<Prepared>& prepared,
                      std::vector<std::optional<CellRows>>&& done, bool brdf, RunSummary& sum) {
    std::vector<AnyNdf> ndfs;
    std::vector<CellRows> rows;
    RunMeta meta;
    for (std::size_t i = 0; i < prepared.size(); ++i) {
        const Prepared& p = prepared[i];
        const CellRows& r = rows.emplace_back(std::move(*done[i]));
        ndfs.push_back(p.ndf);
        meta.cells.push_back(
            {p.cell.index, p.ndf.spec(), p.material.spec(), p.cell.theta_i, p.cell.phi_i, r.bounces, r.capped});
        sum.bounces += r.bounces;
        sum.total.push_back(r.total);
    }
    write_tables(dir, ndfs, rows, brdf);
    return meta;
}

}  // namespace

RunSummary run_scene(const TraceScene& s, const std::string& source, const NdfRegistry& registry, const fs::path& out,
                     unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    // Everything is checked first: every spec, every microsurface once, every cell's direction.
    const walk::MicrosurfaceOptions opts = scene::parse_walk_options(s.downward, s.hit_normal, source + ": walks.");
    const CellSettings settings = cell_settings(s);
    const std::vector<Prepared> prepared =
        prepare_cells(cells(s), checked_ndfs(s.ndfs, registry, opts),
                      parsed_materials(s.materials, registry.materials()), settings, source);
    std::vector<CellJob> jobs = cell_jobs(prepared, settings);

    // Under MPI with more than one rank, every rank has checked the scene alike; from here rank 0 alone owns OUT and
    // the others trace what it hands out (cluster/block_jobs.hpp).
    if (cluster::mpi::size() > 1) cluster::mpi::set_talking();
    RunSummary sum;
    sum.cells = static_cast<std::int64_t>(prepared.size());
    std::vector<std::optional<CellRows>> done(prepared.size());
    std::optional<output::StagedDirectory> stage;
    if (cluster::mpi::rank() == 0) {
        stage.emplace(out, "trace");  // refuses a bad OUT before any work
        done = reuse_cells(out, prepared, s.brdf, jobs);
        for (const auto& d : done) sum.reused += d.has_value();
    }
    const cluster::Traffic traffic =
        trace_cells(std::move(jobs), opts, prepared, s.walks, out, done, threads, sum.traced);
    if (cluster::mpi::rank() != 0) return sum;

    answer_capped(prepared, done, s.walks, out);
    RunMeta run = write_outputs(stage->path(), prepared, std::move(done), !s.brdf.empty(), sum);
    sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.traced = sum.traced;
    run.reused = sum.reused;
    run.bounces = sum.bounces;
    run.seconds = sum.seconds;
    run.threads = util::thread_count(threads);
    nlohmann::ordered_json meta = trace_meta(s, source, run);
    if (cluster::mpi::size() > 1) meta["mpi"] = cluster::traffic_json(traffic);  // threads is then per rank
    output::write_file(stage->path() / "meta.json", meta.dump(2) + "\n");
    stage->publish();
    return sum;
}

}  // namespace smithlab::trace
