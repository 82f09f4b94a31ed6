#include "fit/fit_furnace.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "fit/fit_data.hpp"
#include "smithlab/fresnel.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::fitrun {

namespace {

// Every walk of one cell from wi, over threads in the trace's fixed blocks.
walk::AlbedoTally trace(const AnySurface& s, const walk::Material& m, const Vec3& wi, std::uint64_t seed,
                        std::uint64_t cell, std::int64_t walks, unsigned threads) {
    walk::CellRequest r;
    r.wi = wi;
    r.seed = seed;
    r.cell = cell;
    r.walks = walks;
    return util::reduce_blocks(
               walk::block_count(r.walks, r.block), threads, walk::empty_partial(r),
               [&](std::uint64_t b) { return s.trace_block(m, r, b); }, walk::merge_partial, [](std::uint64_t) {})
        .albedo;
}

// The cells of the furnace in order: cell k's walks draw from (seed, k).
struct FurnaceCells {
    std::uint64_t seed, next = 0;
    std::int64_t walks;
    unsigned threads;

    walk::AlbedoTally tally(const AnySurface& s, const walk::Material& m, const Vec3& wi) {
        return trace(s, m, wi, seed, next++, walks, threads);
    }
};

// Each G2 form's exact single-scattering albedos of one family (its tables from index first on) at one NDF.
using ExactAlbedos = std::vector<std::pair<const FamilyTables*, fit::SingleScatteringAlbedo<AnyNdf>>>;

ExactAlbedos exact_albedos(const std::vector<FamilyTables>& tables, std::size_t first, const AnyNdf& ndf) {
    ExactAlbedos exact;
    for (std::size_t g = first; g < tables.size() && tables[g].family == tables[first].family; ++g)
        exact.emplace_back(&tables[g], fit::SingleScatteringAlbedo<AnyNdf>(ndf, table_options(tables[g].g2)));
    return exact;
}

// One point of the furnace: a family's surface at alpha, lit at theta from above or below; the rows it adds.
struct FurnacePoint {
    const FitFamily& family;
    const AnySurface& surface;
    const ExactAlbedos& exact;
    double alpha, theta, mu;
    Vec3 above, below;
    std::vector<FurnaceRow>& rows;

    void add(const FamilyTables& ft, const std::string& material, const char* part, const char* form, double value,
             const walk::Estimate& traced) const {
        rows.push_back({family_label(family), g2_name(ft.g2), material, part, form, alpha, theta, value, traced.value,
                        traced.stderr_});
    }
};

// Mirror facets and conductors: single scattering exact, the compensation from the table of E.
void metal_rows(const FurnacePoint& p, const walk::Material& m, const walk::Estimate& total) {
    const std::string name = walk::format_material(m);
    const auto* conductor = std::get_if<walk::Conductor>(&m);
    auto F = [&](double cos_m) { return conductor ? fresnel_conductor(cos_m, conductor->eta, conductor->k) : 1.0; };
    const double F_avg = conductor ? fit::average_fresnel(F) : 1.0;
    const double alpha = p.alpha, mu = p.mu;
    for (const auto& [ft, E] : p.exact) {
        const fit::AlbedoTable& table = ft->E.table.table;
        if (!conductor) {
            p.add(*ft, name, "total", "kulla-conty", E(mu) + fit::kulla_conty_albedo(table, ft->missing, alpha, mu),
                  total);
            continue;
        }
        const double E_F = E(mu, F), E_mu = table.lookup(alpha, mu);
        p.add(*ft, name, "total", "kulla-conty", E_F + fit::kulla_conty_albedo(table, ft->missing, alpha, mu, F_avg),
              total);
        p.add(*ft, name, "total", "turquin", E_F * fit::turquin_scale(E_mu, F(1.0)), total);
        p.add(*ft, name, "total", "fdez-aguera", fit::fdez_aguera_albedo(E_F, E_mu, F_avg), total);
        if (ft->orders)
            p.add(*ft, name, "total", "walk-orders",
                  E_F + fit::multiple_scattering_albedo(E_mu, ft->orders->lookup(alpha, mu), F_avg), total);
    }
}

// Dielectric d of the tables from one side: single scattering over the table of E_R + E_T.
void dielectric_rows(const FurnacePoint& p, std::size_t d, const walk::AlbedoTally& tally) {
    const DielectricTables& dt = p.exact.front().first->dielectrics[d];
    // The tally's reflection hemisphere is wo.z > 0: from inside, that is the transmitted light.
    const walk::Hemisphere same = dt.inside ? walk::Hemisphere::transmission : walk::Hemisphere::reflection;
    const walk::Hemisphere other = dt.inside ? walk::Hemisphere::reflection : walk::Hemisphere::transmission;
    const std::string material = walk::format_material(walk::Dielectric{dt.eta}) + (dt.inside ? " inside" : " outside");
    for (const auto& [ft, E] : p.exact) {
        const auto single = E.dielectric(p.mu, dt.relative_eta());
        const double table = ft->dielectrics[d].sum.table.table.lookup(p.alpha, p.mu);
        p.add(*ft, material, "total", "turquin", (single.R + single.T) / table,
              tally.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all));
        p.add(*ft, material, "R", "turquin", single.R / table,
              tally.albedo(same, walk::all_orders, walk::Component::all));
        p.add(*ft, material, "T", "turquin", single.T / table,
              tally.albedo(other, walk::all_orders, walk::Component::all));
    }
}

// Every material at one point: the mirror, the conductors, then the dielectrics, a cell each.
void trace_point(const FurnacePoint& p, const FitScene::Compensation& c, FurnaceCells& cells) {
    std::vector<walk::Material> metals{walk::Mirror{}};
    for (const std::string& spec : c.conductors) metals.push_back(walk::parse_material(spec));
    for (const walk::Material& m : metals)
        metal_rows(
            p, m,
            cells.tally(p.surface, m, p.above).albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all));
    for (std::size_t d = 0; d < p.exact.front().first->dielectrics.size(); ++d) {
        const DielectricTables& dt = p.exact.front().first->dielectrics[d];
        dielectric_rows(p, d, cells.tally(p.surface, walk::Dielectric{dt.eta}, dt.inside ? p.below : p.above));
    }
}

}  // namespace

std::vector<FurnaceRow> trace_furnace(const std::vector<FamilyTables>& tables, const FitScene::Compensation& c,
                                      const NdfRegistry& registry, std::uint64_t seed, unsigned threads) {
    std::vector<FurnaceRow> rows;
    FurnaceCells cells{seed, 0, c.furnace_walks, threads};
    for (std::size_t n = 0; n < tables.size(); ++n) {
        if (n > 0 && tables[n].family == tables[n - 1].family) continue;  // one trace per family: each G2 reads it
        const FitFamily& family = *tables[n].family;
        std::fprintf(stderr, "fit: compensation furnace: %s, %zu alphas x %zu angles\n", family_label(family).c_str(),
                     c.furnace_alpha.size(), c.furnace_theta.size());
        for (double alpha : c.furnace_alpha) {
            const AnyNdf ndf = make_ndf(registry, family, alpha);
            const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
            // Each G2 form's exact albedos at this alpha (one Lambda table each for an NDF without a closed form).
            const ExactAlbedos exact = exact_albedos(tables, n, ndf);
            for (double theta : c.furnace_theta) {
                const double t = theta * std::numbers::pi / 180.0, mu = std::cos(t), s = std::sin(t);
                const FurnacePoint p{family, *surface, exact, alpha, theta, mu, {s, 0.0, mu}, {s, 0.0, -mu}, rows};
                trace_point(p, c, cells);
            }
        }
    }
    return rows;
}

}  // namespace smithlab::fitrun
