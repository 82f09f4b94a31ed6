#include "trace/trace_run.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <sstream>
#include <thread>
#include <toml.hpp>

#include "trace/cell_jobs.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/traffic_json.hpp"
#include "output/output_file.hpp"
#include "output/progress.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/walk/trace.hpp"
#include "output/staged_directory.hpp"
#include "scene/walk_options.hpp"

namespace smithlab::trace {

namespace fs = std::filesystem;

namespace {

const char* const hemisphere_name[] = {"reflection", "transmission", "all"};
const char* const component_name[] = {"specular", "diffuse", "all"};
const char* const order_name[] = {"1", "2", "3", "4+", "all"};
constexpr int order_columns = walk::order_bins + 1;  // 1, 2, 3, 4+, all

const std::string albedo_header = "ndf,material,theta_i,phi_i,hemisphere,order,component,albedo,stderr,walks";
const std::string brdf_header =
    "ndf,material,theta_i,phi_i,hemisphere,theta_o_lo,theta_o_hi,phi_o_lo,phi_o_hi,order,component,value,stderr,walks";

// A cell with its specs checked and in canonical form, and the key its cell file must carry.
struct Prepared {
    TraceCell cell;
    AnyNdf ndf;
    walk::Material material;
    std::string key;
};

// What a finished cell leaves: its rows as the output files will hold them.
struct CellRows {
    std::int64_t bounces = 0, capped = 0;
    walk::Estimate total{0.0, 0.0};
    std::vector<std::string> albedo, brdf;
};

std::string record(const std::vector<std::string>& fields) {
    std::ostringstream out;
    write_csv_record(out, fields);
    std::string s = out.str();
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
}

std::string cell_key(const TraceScene& s, const TraceCell& c, const AnyNdf& ndf, const walk::Material& m) {
    std::ostringstream k;
    k << "smithlab " << SMITHLAB_VERSION << "|ndf=" << ndf.key() << "|material=" << walk::format_material(m)
      << "|theta_i=" << format_g17(c.theta_i) << "|phi_i=" << format_g17(c.phi_i) << "|walks=" << s.walks
      << "|seed=" << s.seed << "|cell=" << c.index << "|max_order=" << s.max_order << "|downward=" << s.downward
      << "|hit_normal=" << s.hit_normal
      << "|brdf=" << s.brdf.n_theta << "x" << s.brdf.n_phi;
    return k.str();
}

fs::path cell_path(const fs::path& out, std::uint64_t index) {
    char name[32];
    std::snprintf(name, sizeof name, "cell-%06llu.csv", static_cast<unsigned long long>(index));
    return out / "cells" / name;
}

// Band t of n equal bands of |cos theta_o| from the pole, in degrees from the macro normal (tally.hpp).
std::pair<double, double> band_degrees(int t, int n, bool transmission) {
    const double deg = 180.0 / std::numbers::pi;
    const double lo = std::acos(1.0 - static_cast<double>(t) / n) * deg,
                 hi = std::acos(std::max(0.0, 1.0 - static_cast<double>(t + 1) / n)) * deg;
    return transmission ? std::pair{180.0 - hi, 180.0 - lo} : std::pair{lo, hi};
}

CellRows rows_of(const Prepared& p, const TraceScene& s, const walk::CellResult& r) {
    CellRows rows;
    rows.bounces = r.albedo.events;
    rows.capped = r.albedo.capped;
    rows.total = r.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    const std::string ndf = p.ndf.spec(), material = walk::format_material(p.material),
                      theta = format_shortest(p.cell.theta_i), phi = format_shortest(p.cell.phi_i),
                      walks = std::to_string(s.walks);
    for (int h = 0; h < 3; ++h)
        for (int o = 0; o < order_columns; ++o)
            for (int c = 0; c < 3; ++c) {
                const walk::Estimate e = r.albedo.albedo(static_cast<walk::Hemisphere>(h),
                                                         o == walk::order_bins ? walk::all_orders : o,
                                                         static_cast<walk::Component>(c));
                rows.albedo.push_back(record({ndf, material, theta, phi, hemisphere_name[h], order_name[o],
                                              component_name[c], format_g17(e.value), format_g17(e.stderr_), walks}));
            }
    if (!r.brdf) return rows;
    const walk::BrdfBins& b = r.brdf->bins;
    const double sector = 360.0 / b.n_phi;
    for (int h = 0; h < (b.transmission ? 2 : 1); ++h)
        for (int t = 0; t < b.n_theta; ++t)
            for (int q = 0; q < b.n_phi; ++q) {
                const auto [theta_lo, theta_hi] = band_degrees(t, b.n_theta, h == 1);
                for (int o = 0; o < order_columns; ++o)
                    for (int c = 0; c < 3; ++c) {
                        const walk::Estimate e = r.brdf->value(h, t, q, o == walk::order_bins ? walk::all_orders : o,
                                                               static_cast<walk::Component>(c));
                        rows.brdf.push_back(record({ndf, material, theta, phi, hemisphere_name[h], format_g17(theta_lo),
                                                    format_g17(theta_hi), format_g17(q * sector),
                                                    format_g17((q + 1) * sector), order_name[o], component_name[c],
                                                    format_g17(e.value), format_g17(e.stderr_), walks}));
                    }
            }
    return rows;
}

// brdf.csv's rows of a cell: both hemispheres for a material that transmits.
std::size_t brdf_rows(const TraceScene& s, const walk::Material& m) {
    if (s.brdf.empty()) return 0;
    return (walk::transmits(m) ? 2u : 1u) * static_cast<std::size_t>(s.brdf.n_theta) * s.brdf.n_phi * order_columns * 3;
}

void write_cell(const fs::path& path, const Prepared& p, const CellRows& rows) {
    output::write_output(output::resolve_output(path.string()), [&](std::ostream& out) {
        out << "key," << csv_field(p.key) << "\n"
            << "bounces," << rows.bounces << "\n"
            << "capped," << rows.capped << "\n"
            << "total," << format_g17(rows.total.value) << "," << format_g17(rows.total.stderr_) << "\n";
        for (const std::string& a : rows.albedo) out << "a," << a << "\n";
        for (const std::string& b : rows.brdf) out << "b," << b << "\n";
    });
}

// The cell file's rows, if it is whole and its key is this cell's.
std::optional<CellRows> read_cell(const fs::path& path, const Prepared& p, const TraceScene& s) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::string line;
    if (!std::getline(in, line) || line != "key," + csv_field(p.key)) return std::nullopt;
    CellRows rows;
    auto integer = [&](const char* tag, std::int64_t& v) {
        if (!std::getline(in, line) || line.rfind(std::string(tag) + ",", 0) != 0) return false;
        char* end = nullptr;
        v = std::strtoll(line.c_str() + std::strlen(tag) + 1, &end, 10);
        return *end == '\0';
    };
    if (!integer("bounces", rows.bounces) || !integer("capped", rows.capped)) return std::nullopt;
    if (!std::getline(in, line) || line.rfind("total,", 0) != 0) return std::nullopt;
    char* end = nullptr;
    rows.total.value = std::strtod(line.c_str() + 6, &end);
    if (*end != ',') return std::nullopt;
    rows.total.stderr_ = std::strtod(end + 1, &end);
    if (*end != '\0') return std::nullopt;
    while (std::getline(in, line)) {
        if (line.rfind("a,", 0) == 0) rows.albedo.push_back(line.substr(2));
        else if (line.rfind("b,", 0) == 0) rows.brdf.push_back(line.substr(2));
        else return std::nullopt;
    }
    if (rows.albedo.size() != 3u * order_columns * 3 || rows.brdf.size() != brdf_rows(s, p.material)) return std::nullopt;
    return rows;
}

// The request of one cell: the scene's (base) with the cell's direction, index and hemispheres.
walk::CellRequest request_for(const walk::CellRequest& base, const Prepared& p) {
    walk::CellRequest r = base;
    r.wi = direction_from_deg(p.cell.theta_i, p.cell.phi_i);
    r.cell = p.cell.index;
    r.brdf.transmission = walk::transmits(p.material);
    return r;
}

std::string toml_string(const std::string& s) { return toml::format(toml::value(s)); }

std::string toml_list(const std::vector<double>& v) {
    std::string out = "[";
    for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + format_shortest(v[i]);
    return out + "]";
}

}  // namespace

std::string format_trace_scene(const TraceScene& s) {
    std::ostringstream t;
    t << "title = " << toml_string(s.title) << "\nmaterials = [";
    for (std::size_t i = 0; i < s.materials.size(); ++i) t << (i ? ", " : "") << toml_string(s.materials[i]);
    t << "]\n\n[walks]\nn = " << s.walks << "\nseed = " << s.seed << "\nmax_order = " << s.max_order
      << "\ndownward = " << toml_string(s.downward) << "\nhit_normal = " << toml_string(s.hit_normal)
      << "\n\n[grid]\ntheta_i = " << toml_list(s.theta_i)
      << "\nphi_i = " << toml_list(s.phi_i) << "\n";
    for (const SceneNdf& n : s.ndfs) t << "\n[[ndf]]\nspec = " << toml_string(n.spec) << "\n";
    if (!s.brdf.empty()) t << "\n[brdf]\ntheta_bins = " << s.brdf.n_theta << "\nphi_bins = " << s.brdf.n_phi << "\n";
    return t.str();
}

RunSummary run_scene(const TraceScene& s, const std::string& source, const NdfRegistry& registry, const fs::path& out,
                     unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    const walk::MicrosurfaceOptions opts = parse_walk_options(s.downward, s.hit_normal, source + ": walks.");
    // Check everything first: every spec, and every microsurface once (a D-only NDF's table may refuse it).
    std::map<std::string, AnyNdf> ndfs;
    for (const SceneNdf& n : s.ndfs)
        if (!ndfs.count(n.spec)) {
            const AnyNdf& ndf = ndfs.emplace(n.spec, n.make(registry)).first->second;
            if (!ndf.note().empty() && mpi::rank() == 0) std::fprintf(stderr, "trace: note: %s\n", ndf.note().c_str());
            make_surface(ndf, opts);
        }
    std::map<std::string, walk::Material> materials;
    for (const std::string& spec : s.materials) materials.emplace(spec, walk::parse_material(spec));
    std::vector<Prepared> prepared;
    for (const TraceCell& c : cells(s)) {
        const AnyNdf& ndf = ndfs.at(c.ndf);
        const walk::Material& m = materials.at(c.material);
        if (c.theta_i > 90.0 && !walk::transmits(m))
            throw input_error(source + ": theta_i = " + format_shortest(c.theta_i) + " is light from below the surface, which '" +
                              walk::format_material(m) + "' facets never see (only a dielectric takes it; theta_i < 90 for the others)");
        prepared.push_back({c, ndf, m, cell_key(s, c, ndf, m)});
    }

    walk::CellRequest r;
    r.seed = s.seed;
    r.walks = s.walks;
    r.limits.max_order = s.max_order;
    r.brdf = s.brdf;
    std::vector<CellJob> jobs;
    for (const Prepared& p : prepared)
        jobs.push_back({p.ndf, p.material, request_for(r, p),
                        "cell " + std::to_string(p.cell.index) + " (" + p.ndf.spec() + ", " +
                            walk::format_material(p.material) + ", theta_i " + format_shortest(p.cell.theta_i) +
                            ", phi_i " + format_shortest(p.cell.phi_i) + ")"});
    // Under MPI with more than one rank, every rank has checked the scene alike; from here rank 0 alone owns OUT and
    // the others trace what it hands out (cluster/block_jobs.hpp).
    const bool distributed = mpi::size() > 1;
    if (distributed) mpi::set_talking();
    RunSummary sum;
    sum.cells = static_cast<std::int64_t>(prepared.size());
    std::vector<std::optional<CellRows>> done(prepared.size());
    std::optional<output::StagedDirectory> stage;
    if (mpi::rank() == 0) {
        stage.emplace(out, "trace");  // refuses a bad OUT before any work
        fs::create_directories(out / "cells");
        for (std::size_t i = 0; i < prepared.size(); ++i) {
            done[i] = read_cell(cell_path(out, prepared[i].cell.index), prepared[i], s);
            jobs[i].needed = !done[i];
            if (done[i]) ++sum.reused;
        }
        if (sum.reused)
            std::fprintf(stderr, "trace: %lld of %lld cells reused from %s\n", static_cast<long long>(sum.reused),
                         static_cast<long long>(sum.cells), (out / "cells").string().c_str());
    }
    const std::int64_t to_trace = sum.cells - sum.reused;
    std::atomic<std::int64_t> traced{0};  // finish runs beside the progress line (cluster/block_jobs.hpp)
    CellJobs plan(std::move(jobs), opts, [&](std::size_t i, walk::CellPartial&& total) {
        done[i] = rows_of(prepared[i], s, walk::CellResult{std::move(total.albedo), std::move(total.brdf)});
        write_cell(cell_path(out, prepared[i].cell.index), prepared[i], *done[i]);
        ++traced;
    });
    output::ProgressLine progress;
    const cluster::Traffic traffic = cluster::run_jobs(plan, threads, [&](std::uint64_t merged, std::uint64_t all) {
        progress(static_cast<double>(merged) / static_cast<double>(all), [&] {
            char line[128];
            std::snprintf(line, sizeof line, "trace: %lld of %lld cells done%s, %.0f%% of the walks",
                          static_cast<long long>(traced.load()), static_cast<long long>(to_trace),
                          distributed ? (" on " + std::to_string(mpi::size()) + " ranks").c_str() : "",
                          100.0 * static_cast<double>(merged) / static_cast<double>(all));
            return std::string(line);
        });
    });
    sum.traced = traced;
    if (mpi::rank() != 0) return sum;

    nlohmann::ordered_json cell_list = nlohmann::ordered_json::array();
    {
        std::ofstream albedo(stage->path() / "albedo.csv", std::ios::binary);
        albedo << albedo_header << "\n";
        std::optional<std::ofstream> brdf;
        if (!s.brdf.empty()) brdf.emplace(stage->path() / "brdf.csv", std::ios::binary) << brdf_header << "\n";
        for (std::size_t i = 0; i < prepared.size(); ++i) {
            const CellRows& rows = *done[i];
            for (const std::string& a : rows.albedo) albedo << a << "\n";
            if (brdf)
                for (const std::string& b : rows.brdf) *brdf << b << "\n";
            sum.bounces += rows.bounces;
            cell_list.push_back({{"cell", prepared[i].cell.index},
                                 {"ndf", prepared[i].ndf.spec()},
                                 {"material", walk::format_material(prepared[i].material)},
                                 {"theta_i", prepared[i].cell.theta_i},
                                 {"phi_i", prepared[i].cell.phi_i},
                                 {"bounces", rows.bounces},
                                 {"capped_walks", rows.capped}});
            sum.total.push_back(rows.total);
        }
        albedo.close();
        if (!albedo || (brdf && !brdf->flush())) throw std::runtime_error("trace: could not write the outputs (disk full?)");
    }
    sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::ordered_json meta = {{"title", s.title},
                                 {"source", source},
                                 {"scene", format_trace_scene(s)},
                                 {"version", SMITHLAB_VERSION},
                                 {"seed", s.seed},
                                 {"walks", s.walks},
                                 {"max_order", s.max_order},
                                 {"downward", s.downward},
                                 {"hit_normal", s.hit_normal},
                                 {"cells", cell_list},
                                 {"cells_traced", sum.traced},
                                 {"cells_reused", sum.reused},
                                 {"bounces", sum.bounces},
                                 {"seconds", sum.seconds},
                                 {"threads", util::thread_count(threads)}};
    if (distributed) meta["mpi"] = cluster::traffic_json(traffic);  // threads is then per rank
    std::ofstream(stage->path() / "meta.json") << meta.dump(2) << "\n";
    stage->publish();
    return sum;
}

}  // namespace smithlab::trace
