#include "compensation/table_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "smithlab/compensation/furnace.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::compensation {

namespace {

std::string e3(double v) { return format_printf("%.1e", v); }
std::string g4(double v) { return format_printf("%.4g", v); }

// The grid and every table's errors.
void table_errors(std::ostringstream& md, const std::vector<FamilyTables>& all, const Settings& c) {
    md << "\n## Energy compensation (Kulla and Conty 2017, Turquin 2019)\n\n"
       << "Tables of the single-scattering albedo over " << c.alpha.size() << " alphas (" << g4(c.alpha.front())
       << " to " << g4(c.alpha.back()) << ", linear in sqrt(alpha)) x " << c.cosines
       << " warped cosines x = sqrt((1 + c) mu / (mu + c)) (c the NDF's warp scale, compensation_avg.csv); the "
       << "dielectrics' ln(E_R + E_T) over " << c.dielectric_cosines << " cosines, from inside with nodes clustered "
       << "about the critical angle. Each is measured against the exact values on the grid " << c.refine
       << "x finer in both (compensation_error.csv), at grazing incidence (mu < " << compensation::grazing_mu
       << ") apart; the renderer formats are in compensation/. The furnace by the tables: |compensated albedo - 1| "
       << "at theta_i <= " << furnace_theta_max
       << " degrees, mirror facets with Kulla and Conty's lobe, dielectrics divided by E_R + E_T.\n\n"
       << "| NDF | G2 | table | interpolation error (alpha, mu) | grazing | below the grid | furnace |\n"
       << "|---|---|---|---:|---:|---:|---:|\n";
    for (const FamilyTables& t : all)
        for_each_table(t, [&](const MeasuredTable& m) {
            const compensation::InterpolationError w = compensation::worst_of(m.furnace);
            md << "| " << family_label(*t.family) << " | " << g2_name(t.g2) << " | " << m.name << " | "
               << e3(m.table.error.max) << " (" << g4(m.table.error.alpha) << ", " << g4(m.table.error.mu) << ") | "
               << e3(m.table.grazing.max) << " | " << e3(m.below.max) << " | " << e3(w.max) << " |\n";
        });
    for (const FamilyTables& t : all)
        for_each_alone(t, [&](const std::string& name, const compensation::CheckedTable& table) {
            md << "| " << family_label(*t.family) << " | " << g2_name(t.g2) << " | " << name << " (alone) | "
               << e3(table.error.max) << " (" << g4(table.error.alpha) << ", " << g4(table.error.mu) << ") | "
               << e3(table.grazing.max) << " | - | - |\n";
        });
}

// The walk's scattering orders: their grid, their form and the walks' worst standard error in A_ms.
void order_errors(std::ostringstream& md, const std::vector<FamilyTables>& all, const Settings& c) {
    // The walks' standard error in A_ms: (1 - E) times that of q_2 or q_3, the larger, at each node.
    double worst = 0.0;
    for (const FamilyTables& t : all) {
        const compensation::AlbedoGrid& g = t.orders->q2.grid;
        for (std::size_t i = 0; i < g.alphas.size(); ++i)
            for (int j = 0; j < g.n_x; ++j) {
                const std::size_t k = i * static_cast<std::size_t>(g.n_x) + static_cast<std::size_t>(j);
                const double missed = 1.0 - t.E.table.table.lookup(g.alphas[i], g.mu(i, j));
                worst = std::max(worst, missed * std::max(t.orders->q2_stderr[k], t.orders->q3_stderr[k]));
            }
    }
    md << "\nConductors (form walk-orders): the walk's scattering orders of mirror facets over " << c.order_alpha.size()
       << " alphas x " << c.order_cosines << " warped cosines, " << c.order_walks
       << " walks a node (compensation_orders.csv): of the light single scattering misses, 1 - E, the shares q_2 "
          "and q_3 that leave after 2 and 3 hits and the escape chance p of each later hit (q_1: the separable "
          "G2's share that leaves after one), read as E_F + (1 - E) (q_1 F_avg + (1 - q_1) (q_2 F_avg^2 + q_3 "
          "F_avg^3 + q_4+ F_avg^4 p / (1 - F_avg (1 - p)))). The walks' worst standard error, (1 - E) times that "
          "of q_2 or q_3: "
       << e3(worst) << ".\n";
}

// The furnace against the walk: the worst difference per NDF, G2, material, part and form.
void furnace_errors(std::ostringstream& md, const Settings& c, const std::vector<FurnaceRow>& rows) {
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
        md << "| " << w->ndf << " | " << w->g2 << " | " << w->material << " | " << w->part << " | " << w->form << " | "
           << e3(d) << " | (" << g4(w->alpha) << ", " << g4(w->theta) << ") | "
           << (w->traced_stderr > 0.0 ? g4(std::abs(d) / w->traced_stderr) : std::string("exact")) << " |\n";
    }
}

}  // namespace

std::string tables_markdown(const std::vector<FamilyTables>& all, const Settings& c,
                            const std::vector<FurnaceRow>& furnace) {
    std::ostringstream md;
    table_errors(md, all, c);
    if (c.order_walks > 0) order_errors(md, all, c);
    if (!furnace.empty()) furnace_errors(md, c, furnace);
    return md.str();
}

}  // namespace smithlab::compensation
