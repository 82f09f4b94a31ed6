#include "compensation/walk_furnace.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "smithlab/fresnel.hpp"
#include "smithlab/material_registry.hpp"
#include "smithlab/surface.hpp"
#include "smithlab/util/parallel.hpp"

namespace smithlab::compensation {

namespace {

using Albedo = compensation::SingleScatteringAlbedo<AnyNdf>;

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

// One family at one furnace alpha and theta_i: its surface, each G2 form's tables with their exact albedos at this
// alpha (one Lambda table each for an NDF without a closed form), the walks' next cell and the rows so far.
struct FurnaceCell {
    const AnySurface& surface;
    const std::vector<std::pair<const FamilyTables*, Albedo>>& exact;
    std::string ndf;
    double alpha, theta, mu;
    Vec3 above, below;
};
struct FurnaceWalks {
    const Settings& c;
    const StageRun& run;
    std::uint64_t cell = 0;
    std::vector<FurnaceRow> rows;
    // The walk of the next cell of material m from wi.
    walk::AlbedoTally next(const FurnaceCell& k, const walk::Material& m, const Vec3& wi) {
        return trace(k.surface, m, wi, run.seed, cell++, c.furnace_walks, run.threads);
    }
    void add(const FurnaceCell& k, const FamilyTables& ft, const std::string& material, const char* part,
             const char* form, double value, const walk::Estimate& traced) {
        rows.push_back(
            {k.ndf, g2_name(ft.g2), material, part, form, k.alpha, k.theta, value, traced.value, traced.stderr_});
    }
};

// Mirror facets and each conductor: single scattering exact, the compensation from the table of E, in every form.
void metal_rows(const FurnaceCell& k, FurnaceWalks& w) {
    const double alpha = k.alpha, mu = k.mu;
    std::vector<walk::Material> metals{walk::Mirror{}};
    for (const std::string& spec : w.c.conductors)
        metals.push_back(MaterialRegistry().make(spec));  // conductors, checked by the scene
    for (const walk::Material& m : metals) {
        const walk::Estimate total =
            w.next(k, m, k.above).albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
        const std::string name = m.spec();
        const auto* conductor = m.get_if<walk::Conductor>();
        auto F = [&](double cos_m) { return conductor ? fresnel_conductor(cos_m, conductor->eta, conductor->k) : 1.0; };
        const double F_avg = conductor ? compensation::average_fresnel(F) : 1.0;
        for (const auto& [ft, E] : k.exact) {
            const compensation::AlbedoTable& table = ft->E.table.table;
            if (!conductor) {
                w.add(k, *ft, name, "total", "kulla-conty",
                      E(mu) + compensation::kulla_conty_albedo(table, ft->missing, alpha, mu), total);
                continue;
            }
            const double E_F = E(mu, F), E_mu = table.lookup(alpha, mu);
            w.add(k, *ft, name, "total", "kulla-conty",
                  E_F + compensation::kulla_conty_albedo(table, ft->missing, alpha, mu, F_avg), total);
            w.add(k, *ft, name, "total", "turquin", E_F * compensation::turquin_scale(E_mu, F(1.0)), total);
            w.add(k, *ft, name, "total", "fdez-aguera", compensation::fdez_aguera_albedo(E_F, E_mu, F_avg), total);
            if (ft->orders)
                w.add(k, *ft, name, "total", "walk-orders",
                      E_F + compensation::multiple_scattering_albedo(E_mu, ft->orders->lookup(alpha, mu), F_avg),
                      total);
        }
    }
}

// Dielectrics from each side: single scattering over the table of E_R + E_T.
void dielectric_rows(const FurnaceCell& k, FurnaceWalks& w) {
    const double alpha = k.alpha, mu = k.mu;
    for (std::size_t d = 0; d < k.exact.front().first->dielectrics.size(); ++d) {
        const DielectricTables& dt = k.exact.front().first->dielectrics[d];
        const walk::Material m = walk::Dielectric{dt.eta};
        const walk::AlbedoTally tally = w.next(k, m, dt.inside ? k.below : k.above);
        // The tally's reflection hemisphere is wo.z > 0: from inside, that is the transmitted light.
        const walk::Hemisphere same = dt.inside ? walk::Hemisphere::transmission : walk::Hemisphere::reflection;
        const walk::Hemisphere other = dt.inside ? walk::Hemisphere::reflection : walk::Hemisphere::transmission;
        const std::string material = m.spec() + (dt.inside ? " inside" : " outside");
        for (const auto& [ft, E] : k.exact) {
            const auto single = E.dielectric(mu, dt.relative_eta());
            const double table = ft->dielectrics[d].sum.table.table.lookup(alpha, mu);
            w.add(k, *ft, material, "total", "turquin", (single.R + single.T) / table,
                  tally.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all));
            w.add(k, *ft, material, "R", "turquin", single.R / table,
                  tally.albedo(same, walk::all_orders, walk::Component::all));
            w.add(k, *ft, material, "T", "turquin", single.T / table,
                  tally.albedo(other, walk::all_orders, walk::Component::all));
        }
    }
}

}  // namespace

std::vector<FurnaceRow> trace_furnace(const std::vector<FamilyTables>& tables, const Settings& c,
                                      const NdfRegistry& registry, const StageRun& run) {
    FurnaceWalks w{c, run};
    for (std::size_t n = 0; n < tables.size(); ++n) {
        if (n > 0 && tables[n].family == tables[n - 1].family) continue;  // one trace per family: each G2 reads it
        const scene::AlphaFamily& family = *tables[n].family;
        std::fprintf(stderr, "%s: compensation furnace: %s, %zu alphas x %zu angles\n", run.command.c_str(),
                     family_label(family).c_str(), c.furnace_alpha.size(), c.furnace_theta.size());
        for (double alpha : c.furnace_alpha) {
            const AnyNdf ndf = make_ndf(registry, family, alpha);
            const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
            std::vector<std::pair<const FamilyTables*, Albedo>> exact;
            for (std::size_t g = n; g < tables.size() && tables[g].family == &family; ++g)
                exact.emplace_back(&tables[g], Albedo(ndf, table_options(tables[g].g2)));
            for (double theta : c.furnace_theta) {
                const double t = theta * std::numbers::pi / 180.0, mu = std::cos(t), s = std::sin(t);
                const FurnaceCell k{*surface, exact, family_label(family), alpha,
                                    theta,    mu,    {s, 0.0, mu},         {s, 0.0, -mu}};
                metal_rows(k, w);
                dielectric_rows(k, w);
            }
        }
    }
    return std::move(w.rows);
}

}  // namespace smithlab::compensation
