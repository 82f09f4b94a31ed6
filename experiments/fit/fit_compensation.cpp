#include "fit/fit_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <sstream>

#include "fit/fit_data.hpp"
#include "fit/fit_furnace.hpp"
#include "output/ndf_columns.hpp"
#include "output/plot_script.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/fit/compensation_formats.hpp"
#include "smithlab/fit/furnace.hpp"

namespace smithlab::fitrun {

namespace fs = std::filesystem;

std::string DielectricTables::name(const std::string& what) const {
    return what + " eta=" + format_shortest(eta) + (inside ? " inside" : " outside");
}

std::string g2_name(G2Form form) { return form == G2Form::uncorrelated ? "separable" : "height-correlated"; }

fit::AlbedoOptions table_options(G2Form form) {
    fit::AlbedoOptions o;
    o.tolerance = fit::table_tolerance;
    o.g2 = form;
    return o;
}

namespace {

const double furnace_mu_min = std::cos(furnace_theta_max * std::numbers::pi / 180.0);
const std::vector<double> below_factors{0.5, 0.1, 0.01};

using Albedo = fit::SingleScatteringAlbedo<AnyNdf>;

// The exact albedos of one family and G2 form, one object per alpha (an NDF without a closed-form Lambda builds its
// table in it). Those asked for again are kept: the node alphas (their 1 - E_avg is taken after the tables) and the
// alphas below the grid (every table's below-grid error visits them). Safe from several threads at once.
class AlbedoCache {
public:
    AlbedoCache(const NdfRegistry& registry, const FitFamily& f, G2Form form, const std::vector<double>& nodes)
        : registry_(registry), family_(f), form_(form), nodes_(nodes) {}
    std::shared_ptr<const Albedo> at(double alpha) {
        {
            const std::lock_guard lock(mutex_);
            if (const auto it = kept_.find(alpha); it != kept_.end()) return it->second;
        }
        auto E = std::make_shared<const Albedo>(make_ndf(registry_, family_, alpha), table_options(form_));
        if (!kept(alpha)) return E;
        const std::lock_guard lock(mutex_);
        return kept_.emplace(alpha, std::move(E)).first->second;
    }

private:
    bool kept(double alpha) const {
        return alpha < nodes_.front() || std::binary_search(nodes_.begin(), nodes_.end(), alpha);
    }
    const NdfRegistry& registry_;
    const FitFamily& family_;
    G2Form form_;
    const std::vector<double>& nodes_;
    std::mutex mutex_;
    std::map<double, std::shared_ptr<const Albedo>> kept_;
};

MeasuredTable measured(std::string name, fit::CheckedTable t, const fit::AlbedoRow& row, unsigned threads) {
    MeasuredTable m{std::move(name), std::move(t), {}, {}};
    m.below = fit::below_grid_error(m.table, row, below_factors, threads);
    return m;
}

// Each eta from outside, then from inside.
std::vector<DielectricTables> dielectric_sides(const std::vector<double>& etas) {
    std::vector<DielectricTables> sides;
    for (double eta : etas)
        for (bool inside : {false, true}) {
            sides.emplace_back();
            sides.back().eta = eta;
            sides.back().inside = inside;
        }
    return sides;
}

// One dielectric side's albedos at an alpha, one albedo object per alpha: E_R, E_T and E_R + E_T.
fit::AlbedoRows side_rows(AlbedoCache& albedos, double rel) {
    return [&albedos, rel](double alpha) -> std::function<void(double, double*)> {
        return [E = albedos.at(alpha), rel](double mu, double* v) {
            const auto e = E->dielectric(mu, rel);
            v[0] = e.R;
            v[1] = e.T;
            v[2] = e.R + e.T;
        };
    };
}

FamilyTables make_tables(const FitFamily& f, G2Form form, const FitScene::Compensation& c, const NdfRegistry& registry,
                         unsigned threads) {
    const int refine = static_cast<int>(c.refine);
    AlbedoCache albedos(registry, f, form, c.alpha);
    fit::AlbedoGrid grid{c.alpha, {}, static_cast<int>(c.cosines), {}};
    for (double a : c.alpha) grid.scales.push_back(albedos.at(a)->warp_scale());
    FamilyTables out;
    out.family = &f;
    out.g2 = form;
    out.dielectrics = dielectric_sides(c.eta);
    const fit::AlbedoRow mirror = [&](double alpha) -> std::function<double(double)> {
        return [E = albedos.at(alpha)](double mu) { return (*E)(mu); };
    };
    out.E = measured("E", fit::tabulate(grid, refine, mirror, threads), mirror, threads);
    for (double a : c.alpha) out.exact_missing.push_back(albedos.at(a)->missing());
    out.missing = fit::table_missing(out.E.table.table);
    out.E.furnace = fit::kulla_conty_furnace(out.E.table, out.missing, furnace_mu_min);
    for (DielectricTables& d : out.dielectrics) {
        const double rel = d.relative_eta();
        std::fprintf(stderr,
                     "fit: compensation tables: %s, %s G2, dielectric eta %s from %s, %zu alphas x %lld cosines\n",
                     family_label(f).c_str(), g2_name(form).c_str(), format_shortest(d.eta).c_str(),
                     d.inside ? "inside" : "outside", c.alpha.size(), static_cast<long long>(c.dielectric_cosines));
        // One pass over the side's check grid (its own cosines and node cluster, fit::dielectric_grid): E_R, E_T and
        // ln(E_R + E_T); the sum alone below the grid.
        const fit::AlbedoGrid side = fit::dielectric_grid(grid, static_cast<int>(c.dielectric_cosines), rel);
        const fit::AlbedoRows rows = side_rows(albedos, rel);
        using fit::Stored;
        std::vector<fit::CheckedTable> t =
            fit::tabulate(side, refine, {Stored::value, Stored::value, Stored::log}, rows, threads);
        const fit::AlbedoRow sum = [&](double alpha) -> std::function<double(double)> {
            return [f = rows(alpha)](double mu) {
                double v[3];
                f(mu, v);
                return v[2];
            };
        };
        d.R = std::move(t[0]);
        d.T = std::move(t[1]);
        d.sum = measured(d.name("E_R+E_T"), std::move(t[2]), sum, threads);
        d.sum.furnace = fit::turquin_furnace(d.sum.table, furnace_mu_min);
    }
    return out;
}

// The first cell of the scattering orders' walks: past every furnace cell (trace_furnace numbers them from 0), so that
// the furnace's walks and the tables it reads draw from different streams.
constexpr std::uint64_t order_cells = std::uint64_t{1} << 40;

// The walk's scattering orders of mirror facets over the order grid (fit/scattering_orders.hpp) for one family, from
// order_walks walks a node. Node k of family n draws from cells order_cells + n * 2^32 + k.
std::shared_ptr<const fit::OrderTables> make_orders(const FitFamily& f, std::size_t n, const FitScene::Compensation& c,
                                                    const NdfRegistry& registry, std::uint64_t seed, unsigned threads) {
    std::fprintf(stderr, "fit: scattering orders: %s, %zu alphas x %lld cosines, %lld walks a node\n",
                 family_label(f).c_str(), c.order_alpha.size(), static_cast<long long>(c.order_cosines),
                 static_cast<long long>(c.order_walks));
    fit::AlbedoGrid grid{c.order_alpha, {}, static_cast<int>(c.order_cosines), {}};
    std::vector<std::shared_ptr<const AnySurface>> surfaces;
    for (double a : c.order_alpha) {
        const AnyNdf ndf = make_ndf(registry, f, a);
        grid.scales.push_back(Albedo(ndf, table_options(G2Form::height_correlated)).warp_scale());
        surfaces.push_back(make_surface(ndf));
    }
    const std::uint64_t first = order_cells + (static_cast<std::uint64_t>(n) << 32);
    const fit::OrderCell trace = [&](std::size_t node, double, double mu) {
        const AnySurface& s = *surfaces[node / static_cast<std::size_t>(grid.n_x)];
        walk::CellRequest r;
        r.wi = {std::sqrt((1.0 - mu) * (1.0 + mu)), 0.0, mu};
        r.seed = seed;
        r.cell = first + node;
        r.walks = c.order_walks;
        walk::AlbedoTally total;
        for (std::uint64_t b = 0; b < walk::block_count(r.walks, r.block); ++b)
            total.merge(s.trace_block(walk::Mirror{}, r, b).albedo);
        return total;
    };
    return std::make_shared<const fit::OrderTables>(fit::tabulate_orders(grid, trace, threads));
}

// The orders for a renderer of the separable G2: q_1 = (E_hc - E_sep) / (1 - E_sep) at each node, the share of the
// light its single scattering misses that the walk scatters once (fit/scattering_orders.hpp); 0 where 1 - E_sep <
// 1e-12.
std::shared_ptr<const fit::OrderTables> with_single_share(const fit::OrderTables& walk, const FitFamily& f,
                                                          const NdfRegistry& registry) {
    auto t = std::make_shared<fit::OrderTables>(walk);
    const fit::AlbedoGrid& g = walk.q2.grid;
    t->q1.grid = g;
    for (std::size_t i = 0; i < g.alphas.size(); ++i) {
        const AnyNdf ndf = make_ndf(registry, f, g.alphas[i]);
        const Albedo hc(ndf, table_options(G2Form::height_correlated)), sep(ndf, table_options(G2Form::uncorrelated));
        for (int j = 0; j < g.n_x; ++j) {
            const double mu = g.mu(i, j), E_sep = sep(mu), missed = 1.0 - E_sep;
            t->q1.values.push_back(missed > 1e-12 ? std::clamp((hc(mu) - E_sep) / missed, 0.0, 1.0) : 0.0);
        }
    }
    return t;
}

// The NDF at each alpha of the tables, for the CSVs' ndf and parameter columns.
struct NdfRows {
    std::vector<AnyNdf> ndfs;  // family-major, alpha-minor, one family per FamilyTables entry
    output::NdfColumns columns;
};

NdfRows ndf_rows(const std::vector<FamilyTables>& all, const std::vector<double>& alphas, const NdfRegistry& registry) {
    NdfRows r;
    for (const FamilyTables& t : all)
        for (double a : alphas) r.ndfs.push_back(make_ndf(registry, *t.family, a));
    r.columns = output::ndf_columns(r.ndfs, {"alpha"});
    return r;
}

// "ndf,alpha,PARAMETERS,REST": the NDF's spec, its alpha and its other parameters, then the table's own columns.
std::string header_of(const output::NdfColumns& columns, const std::vector<std::string>& rest) {
    std::string h = "ndf,alpha,";
    for (const std::string& s : columns.names) h += csv_field(s) + ",";
    for (std::size_t i = 0; i < rest.size(); ++i) h += rest[i] + (i + 1 < rest.size() ? "," : "\n");
    return h;
}

std::string ndf_cells(const NdfRows& r, std::size_t k, double alpha) {
    std::string s = csv_field(r.ndfs[k].spec()) + "," + format_g17(alpha) + ",";
    for (const std::string& c : r.columns.cells(r.ndfs[k])) s += csv_field(c) + ",";
    return s;
}

// compensation_orders.csv: each family's scattering orders at their nodes.
void write_orders(const fs::path& dir, const std::vector<FamilyTables>& all, const FitScene::Compensation& c,
                  const NdfRegistry& registry) {
    if (c.order_walks == 0) return;
    const NdfRows nr = ndf_rows(all, c.order_alpha, registry);
    std::ostringstream o;
    o << header_of(nr.columns, {"g2", "cos_theta", "q1", "q2", "q3", "p", "q2_stderr", "q3_stderr"});
    for (std::size_t n = 0; n < all.size(); ++n) {
        const fit::OrderTables& t = *all[n].orders;
        const fit::AlbedoGrid& g = t.q2.grid;
        for (std::size_t i = 0; i < g.alphas.size(); ++i)
            for (int j = 0; j < g.n_x; ++j) {
                const std::size_t k = i * static_cast<std::size_t>(g.n_x) + static_cast<std::size_t>(j);
                o << ndf_cells(nr, n * g.alphas.size() + i, g.alphas[i]) << g2_name(all[n].g2) << ","
                  << format_g17(g.mu(i, j)) << "," << format_g17(t.q1.values.empty() ? 0.0 : t.q1.values[k]) << ","
                  << format_g17(t.q2.values[k]) << "," << format_g17(t.q3.values[k]) << "," << format_g17(t.p.values[k])
                  << "," << format_g17(t.q2_stderr[k]) << "," << format_g17(t.q3_stderr[k]) << "\n";
            }
    }
    output::write_file(dir / "compensation_orders.csv", o.str());
}

void write_csvs(const fs::path& dir, const std::vector<FamilyTables>& all, const FitScene::Compensation& c,
                const NdfRegistry& registry) {
    const NdfRows nr = ndf_rows(all, c.alpha, registry);
    std::ostringstream E, avg, diel;
    E << header_of(nr.columns, {"g2", "cos_theta", "E"});
    avg << header_of(nr.columns, {"g2", "warp_scale", "E_avg", "one_minus_E_avg", "table_one_minus_E_avg"});
    diel << header_of(nr.columns, {"g2", "eta", "side", "cos_theta", "E_R", "E_T"});
    for (std::size_t n = 0; n < all.size(); ++n) {
        const FamilyTables& t = all[n];
        const fit::AlbedoGrid& g = t.E.table.table.grid;
        for (std::size_t i = 0; i < g.alphas.size(); ++i) {
            const std::size_t k = n * g.alphas.size() + i;
            const std::string lead = ndf_cells(nr, k, g.alphas[i]) + g2_name(t.g2) + ",";
            for (int j = 0; j < g.n_x; ++j)
                E << lead << format_g17(g.mu(i, j)) << "," << format_g17(t.E.table.table.at(i, j)) << "\n";
            avg << lead << format_g17(g.scales[i]) << "," << format_g17(1.0 - t.exact_missing[i]) << ","
                << format_g17(t.exact_missing[i]) << "," << format_g17(t.missing[i]) << "\n";
            for (const DielectricTables& d : t.dielectrics) {
                const fit::AlbedoGrid& dg = d.R.table.grid;
                for (int j = 0; j < dg.n_x; ++j)
                    diel << lead << format_g17(d.eta) << "," << (d.inside ? "inside" : "outside") << ","
                         << format_g17(dg.mu(i, j)) << "," << format_g17(d.R.table.at(i, j)) << ","
                         << format_g17(d.T.table.at(i, j)) << "\n";
            }
        }
    }
    write_orders(dir, all, c, registry);
    output::write_file(dir / "compensation.csv", E.str());
    output::write_file(dir / "compensation_avg.csv", avg.str());
    if (!c.eta.empty()) output::write_file(dir / "compensation_dielectric.csv", diel.str());
}

// Every measured table of a family and G2 form: E, then each dielectric's sum.
template <class F>
void for_each_table(const FamilyTables& t, const F& f) {
    f(t.E);
    for (const DielectricTables& d : t.dielectrics) f(d.sum);
}

// Each dielectric side's E_R and E_T alone (compensation_dielectric.csv's columns, on the sum's axis), with its name.
template <class F>
void for_each_alone(const FamilyTables& t, const F& f) {
    for (const DielectricTables& d : t.dielectrics) {
        f(d.name("E_R"), d.R);
        f(d.name("E_T"), d.T);
    }
}

void write_errors(const fs::path& dir, const std::vector<FamilyTables>& all) {
    std::ostringstream err, furnace;
    err << "ndf,g2,table,max_interp_error,alpha,cos_theta,grazing_error,grazing_alpha,grazing_cos_theta,"
           "below_grid_error,below_alpha,below_cos_theta,furnace_error,furnace_alpha,furnace_cos_theta\n";
    furnace << "ndf,g2,table,alpha,furnace_error,cos_theta\n";
    for (const FamilyTables& t : all)
        for_each_table(t, [&](const MeasuredTable& m) {
            const std::string lead =
                csv_field(family_label(*t.family)) + "," + g2_name(t.g2) + "," + csv_field(m.name) + ",";
            err << lead;
            const char* sep = "";
            for (const fit::InterpolationError& e :
                 {m.table.error, m.table.grazing, m.below, fit::worst_of(m.furnace)}) {
                err << sep << format_g17(e.max) << "," << format_g17(e.alpha) << "," << format_g17(e.mu);
                sep = ",";
            }
            err << "\n";
            for (const fit::InterpolationError& f : m.furnace)
                furnace << lead << format_g17(f.alpha) << "," << format_g17(f.max) << "," << format_g17(f.mu) << "\n";
        });
    // E_R and E_T alone: their interpolation and grazing errors; no below-grid or furnace error (no renderer format
    // divides by them).
    for (const FamilyTables& t : all)
        for_each_alone(t, [&](const std::string& name, const fit::CheckedTable& table) {
            err << csv_field(family_label(*t.family)) << "," << g2_name(t.g2) << "," << csv_field(name);
            for (const fit::InterpolationError& e : {table.error, table.grazing})
                err << "," << format_g17(e.max) << "," << format_g17(e.alpha) << "," << format_g17(e.mu);
            err << ",,,,,,\n";
        });
    output::write_file(dir / "compensation_error.csv", err.str());
    output::write_file(dir / "furnace_tables.csv", furnace.str());
}

// Each table in every renderer format, into dir/compensation/, and each family and G2's scattering orders.
void write_formats(const fs::path& dir, const std::vector<FamilyTables>& all) {
    const fs::path sub = dir / "compensation";
    fs::create_directories(sub);
    const auto text = [&]<class Export>(const std::string& name, const Export& e,
                                        void (*write)(std::ostream&, const Export&)) {
        std::ostringstream s;
        write(s, e);
        output::write_file(sub / name, s.str());
    };
    for (const FamilyTables& t : all) {
        for_each_table(t, [&](const MeasuredTable& m) {
            const fit::CompensationExport e{family_label(*t.family),
                                            g2_name(t.g2),
                                            m.name,
                                            &m.table.table,
                                            &m == &t.E ? t.missing : std::vector<double>{},
                                            m.table.error.max,
                                            m.below.max,
                                            m.table.grazing.max};
            const std::string id = fit::compensation_identifier(e);
            text(id + ".h", e, fit::write_c_header);
            text(id + ".glsl", e, fit::write_glsl);
            text(id + ".hlsl", e, fit::write_hlsl);
            text(id + ".json", e, fit::write_axes_json);
            text(id + ".png", e, fit::write_png16);
        });
        if (!t.orders) continue;
        double worst = 0.0;
        for (const std::vector<double>* v : {&t.orders->q2_stderr, &t.orders->q3_stderr})
            for (const double s : *v) worst = std::max(worst, s);
        const fit::OrderExport o{family_label(*t.family), g2_name(t.g2), t.orders.get(), worst};
        const std::string id = fit::order_identifier(o);
        text(id + ".h", o, fit::write_orders_c_header);
        text(id + ".glsl", o, fit::write_orders_glsl);
        text(id + ".hlsl", o, fit::write_orders_hlsl);
        text(id + ".json", o, fit::write_orders_axes_json);
    }
}

void write_furnace(const fs::path& dir, const std::vector<FurnaceRow>& rows) {
    std::ostringstream f;
    f << "ndf,g2,material,part,form,alpha,theta_i,compensated,traced,traced_stderr\n";
    for (const FurnaceRow& r : rows)
        f << csv_field(r.ndf) << "," << r.g2 << "," << csv_field(r.material) << "," << r.part << "," << r.form << ","
          << format_g17(r.alpha) << "," << format_g17(r.theta) << "," << format_g17(r.compensated) << ","
          << format_g17(r.traced) << "," << format_g17(r.traced_stderr) << "\n";
    output::write_file(dir / "furnace.csv", f.str());
}

std::string e3(double v) { return format_printf("%.1e", v); }
std::string g4(double v) { return format_printf("%.4g", v); }

std::string markdown(const std::vector<FamilyTables>& all, const FitScene::Compensation& c,
                     const std::vector<FurnaceRow>& rows) {
    std::ostringstream md;
    md << "\n## Energy compensation (Kulla and Conty 2017, Turquin 2019)\n\n"
       << "Tables of the single-scattering albedo over " << c.alpha.size() << " alphas (" << g4(c.alpha.front())
       << " to " << g4(c.alpha.back()) << ", linear in sqrt(alpha)) x " << c.cosines
       << " warped cosines x = sqrt((1 + c) mu / (mu + c)) (c the NDF's warp scale, compensation_avg.csv); the "
       << "dielectrics' ln(E_R + E_T) over " << c.dielectric_cosines << " cosines, from inside with nodes clustered "
       << "about the critical angle. Each is measured against the exact values on the grid " << c.refine
       << "x finer in both (compensation_error.csv), at grazing incidence (mu < " << fit::grazing_mu
       << ") apart; the renderer formats are in compensation/. The furnace by the tables: |compensated albedo - 1| "
       << "at theta_i <= " << furnace_theta_max
       << " degrees, mirror facets with Kulla and Conty's lobe, dielectrics divided by E_R + E_T.\n\n"
       << "| NDF | G2 | table | interpolation error (alpha, mu) | grazing | below the grid | furnace |\n"
       << "|---|---|---|---:|---:|---:|---:|\n";
    for (const FamilyTables& t : all)
        for_each_table(t, [&](const MeasuredTable& m) {
            const fit::InterpolationError w = fit::worst_of(m.furnace);
            md << "| " << family_label(*t.family) << " | " << g2_name(t.g2) << " | " << m.name << " | "
               << e3(m.table.error.max) << " (" << g4(m.table.error.alpha) << ", " << g4(m.table.error.mu) << ") | "
               << e3(m.table.grazing.max) << " | " << e3(m.below.max) << " | " << e3(w.max) << " |\n";
        });
    for (const FamilyTables& t : all)
        for_each_alone(t, [&](const std::string& name, const fit::CheckedTable& table) {
            md << "| " << family_label(*t.family) << " | " << g2_name(t.g2) << " | " << name << " (alone) | "
               << e3(table.error.max) << " (" << g4(table.error.alpha) << ", " << g4(table.error.mu) << ") | "
               << e3(table.grazing.max) << " | - | - |\n";
        });
    if (c.order_walks > 0) {
        // The walks' standard error in A_ms: (1 - E) times that of q_2 or q_3, the larger, at each node.
        double worst = 0.0;
        for (const FamilyTables& t : all) {
            const fit::AlbedoGrid& g = t.orders->q2.grid;
            for (std::size_t i = 0; i < g.alphas.size(); ++i)
                for (int j = 0; j < g.n_x; ++j) {
                    const std::size_t k = i * static_cast<std::size_t>(g.n_x) + static_cast<std::size_t>(j);
                    const double missed = 1.0 - t.E.table.table.lookup(g.alphas[i], g.mu(i, j));
                    worst = std::max(worst, missed * std::max(t.orders->q2_stderr[k], t.orders->q3_stderr[k]));
                }
        }
        md << "\nConductors (form walk-orders): the walk's scattering orders of mirror facets over "
           << c.order_alpha.size() << " alphas x " << c.order_cosines << " warped cosines, " << c.order_walks
           << " walks a node (compensation_orders.csv): of the light single scattering misses, 1 - E, the shares q_2 "
              "and q_3 that leave after 2 and 3 hits and the escape chance p of each later hit (q_1: the separable "
              "G2's share that leaves after one), read as E_F + (1 - E) (q_1 F_avg + (1 - q_1) (q_2 F_avg^2 + q_3 "
              "F_avg^3 + q_4+ F_avg^4 p / (1 - F_avg (1 - p)))). The walks' worst standard error, (1 - E) times that "
              "of q_2 or q_3: "
           << e3(worst) << ".\n";
    }
    if (!rows.empty()) {
        md << "\nAgainst the walk (furnace.csv: " << c.furnace_walks
           << " walks a cell): the worst |compensated - traced| per material, part and form, and in standard errors of "
           << "the walk.\n\n| NDF | G2 | material | part | form | worst difference | (alpha, theta_i) | in standard "
           << "errors |\n|---|---|---|---|---|---:|---|---:|\n";
        std::vector<const FurnaceRow*> worst;
        for (const FurnaceRow& r : rows) {
            const FurnaceRow* same = nullptr;
            for (const FurnaceRow*& w : worst)
                if (w->ndf == r.ndf && w->g2 == r.g2 && w->material == r.material && w->part == r.part &&
                    w->form == r.form) {
                    same = w;
                    if (std::abs(r.compensated - r.traced) > std::abs(w->compensated - w->traced)) w = &r;
                }
            if (!same) worst.push_back(&r);
        }
        for (const FurnaceRow* w : worst) {
            const double d = w->compensated - w->traced;
            md << "| " << w->ndf << " | " << w->g2 << " | " << w->material << " | " << w->part << " | " << w->form
               << " | " << e3(d) << " | (" << g4(w->alpha) << ", " << g4(w->theta) << ") | "
               << (w->traced_stderr > 0.0 ? g4(std::abs(d) / w->traced_stderr) : std::string("exact")) << " |\n";
        }
    }
    return md.str();
}

}  // namespace

std::string write_compensation(const fs::path& dir, const std::vector<FitFamily>& families,
                               const FitScene::Compensation& c, const NdfRegistry& registry, std::uint64_t seed,
                               unsigned threads) {
    if (!c.enabled) return "";
    std::vector<FamilyTables> all;
    for (std::size_t n = 0; n < families.size(); ++n) {
        const FitFamily& f = families[n];
        const auto orders = c.order_walks > 0 ? make_orders(f, n, c, registry, seed, threads) : nullptr;
        for (G2Form form : c.g2) {
            std::fprintf(stderr, "fit: compensation tables: %s, %s G2, %zu alphas x %lld cosines (%lldx finer check)\n",
                         family_label(f).c_str(), g2_name(form).c_str(), c.alpha.size(),
                         static_cast<long long>(c.cosines), static_cast<long long>(c.refine));
            all.push_back(make_tables(f, form, c, registry, threads));
            all.back().orders =
                orders && form == G2Form::uncorrelated ? with_single_share(*orders, f, registry) : orders;
        }
    }
    const std::vector<FurnaceRow> rows = trace_furnace(all, c, registry, seed, threads);
    write_csvs(dir, all, c, registry);
    write_errors(dir, all);
    write_formats(dir, all);
    write_furnace(dir, rows);
    const bool drawn = output::run_plot_script("compensation_plots.py", SMITHLAB_COMPENSATION_PLOT_SCRIPT, dir,
                                               "fit: compensation", {"furnace.png"});
    return markdown(all, c, rows) + (drawn ? "\n![The furnace of the tables and against the walk](furnace.png)\n" : "");
}

}  // namespace smithlab::fitrun
