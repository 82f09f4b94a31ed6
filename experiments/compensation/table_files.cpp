#include "compensation/table_files.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>

#include "output/ndf_columns.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/compensation/compensation_formats.hpp"
#include "smithlab/compensation/furnace.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::compensation {

namespace fs = std::filesystem;

namespace {

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
void write_orders(const fs::path& dir, const std::vector<FamilyTables>& all, const Settings& c,
                  const NdfRegistry& registry) {
    if (c.order_walks == 0) return;
    const NdfRows nr = ndf_rows(all, c.order_alpha, registry);
    std::ostringstream o;
    o << header_of(nr.columns, {"g2", "cos_theta", "q1", "q2", "q3", "p", "q2_stderr", "q3_stderr"});
    for (std::size_t n = 0; n < all.size(); ++n) {
        const compensation::OrderTables& t = *all[n].orders;
        const compensation::AlbedoGrid& g = t.q2.grid;
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

void write_csvs(const fs::path& dir, const std::vector<FamilyTables>& all, const Settings& c,
                const NdfRegistry& registry) {
    const NdfRows nr = ndf_rows(all, c.alpha, registry);
    std::ostringstream E, avg, diel;
    E << header_of(nr.columns, {"g2", "cos_theta", "E"});
    avg << header_of(nr.columns, {"g2", "warp_scale", "E_avg", "one_minus_E_avg", "table_one_minus_E_avg"});
    diel << header_of(nr.columns, {"g2", "eta", "side", "cos_theta", "E_R", "E_T"});
    for (std::size_t n = 0; n < all.size(); ++n) {
        const FamilyTables& t = all[n];
        const compensation::AlbedoGrid& g = t.E.table.table.grid;
        for (std::size_t i = 0; i < g.alphas.size(); ++i) {
            const std::size_t k = n * g.alphas.size() + i;
            const std::string lead = ndf_cells(nr, k, g.alphas[i]) + g2_name(t.g2) + ",";
            for (int j = 0; j < g.n_x; ++j)
                E << lead << format_g17(g.mu(i, j)) << "," << format_g17(t.E.table.table.at(i, j)) << "\n";
            avg << lead << format_g17(g.scales[i]) << "," << format_g17(1.0 - t.exact_missing[i]) << ","
                << format_g17(t.exact_missing[i]) << "," << format_g17(t.missing[i]) << "\n";
            for (const DielectricTables& d : t.dielectrics) {
                const compensation::AlbedoGrid& dg = d.R.table.grid;
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
            for (const compensation::InterpolationError& e :
                 {m.table.error, m.table.grazing, m.below, compensation::worst_of(m.furnace)}) {
                err << sep << format_g17(e.max) << "," << format_g17(e.alpha) << "," << format_g17(e.mu);
                sep = ",";
            }
            err << "\n";
            for (const compensation::InterpolationError& f : m.furnace)
                furnace << lead << format_g17(f.alpha) << "," << format_g17(f.max) << "," << format_g17(f.mu) << "\n";
        });
    // E_R and E_T alone: their interpolation and grazing errors; no below-grid or furnace error (no renderer format
    // divides by them).
    for (const FamilyTables& t : all)
        for_each_alone(t, [&](const std::string& name, const compensation::CheckedTable& table) {
            err << csv_field(family_label(*t.family)) << "," << g2_name(t.g2) << "," << csv_field(name);
            for (const compensation::InterpolationError& e : {table.error, table.grazing})
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
    const auto file = [&](const std::string& name, const auto& write) {
        std::ostringstream s;
        write(s);
        output::write_file(sub / name, s.str());
    };
    const auto sources = [&](const std::string& id, const auto& e) {
        for (const compensation::SourceFormat& f : compensation::source_formats)
            file(id + f.extension, [&](std::ostream& s) { compensation::write_source(s, e, f.language); });
    };
    for (const FamilyTables& t : all) {
        for_each_table(t, [&](const MeasuredTable& m) {
            const compensation::CompensationExport e{family_label(*t.family),
                                                     g2_name(t.g2),
                                                     m.name,
                                                     &m.table.table,
                                                     &m == &t.E ? t.missing : std::vector<double>{},
                                                     m.table.error.max,
                                                     m.below.max,
                                                     m.table.grazing.max};
            const std::string id = compensation::compensation_identifier(e);
            sources(id, e);
            file(id + ".json", [&](std::ostream& s) { compensation::write_axes_json(s, e); });
            file(id + ".png", [&](std::ostream& s) { compensation::write_png16(s, e); });
        });
        if (!t.orders) continue;
        double worst = 0.0;
        for (const std::vector<double>* v : {&t.orders->q2_stderr, &t.orders->q3_stderr})
            for (const double s : *v) worst = std::max(worst, s);
        const compensation::OrderExport o{family_label(*t.family), g2_name(t.g2), t.orders.get(), worst};
        const std::string id = compensation::order_identifier(o);
        sources(id, o);
        file(id + ".json", [&](std::ostream& s) { compensation::write_orders_axes_json(s, o); });
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

}  // namespace

void write_table_files(const fs::path& dir, const std::vector<FamilyTables>& all, const Settings& c,
                       const NdfRegistry& registry, const std::vector<FurnaceRow>& furnace) {
    write_csvs(dir, all, c, registry);
    write_errors(dir, all);
    write_formats(dir, all);
    write_furnace(dir, furnace);
}

}  // namespace smithlab::compensation
