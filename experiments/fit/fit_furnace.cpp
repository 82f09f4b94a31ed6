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

}  // namespace

std::vector<FurnaceRow> trace_furnace(const std::vector<FamilyTables>& tables, const FitScene::Compensation& c,
                                      const NdfRegistry& registry, std::uint64_t seed, unsigned threads) {
    std::vector<FurnaceRow> rows;
    std::uint64_t cell = 0;
    for (std::size_t n = 0; n < tables.size(); ++n) {
        if (n > 0 && tables[n].family == tables[n - 1].family) continue;  // one trace per family: each G2 reads it
        const FitFamily& family = *tables[n].family;
        std::fprintf(stderr, "fit: compensation furnace: %s, %zu alphas x %zu angles\n", family_label(family).c_str(),
                     c.furnace_alpha.size(), c.furnace_theta.size());
        for (double alpha : c.furnace_alpha) {
            const AnyNdf ndf = make_ndf(registry, family, alpha);
            const std::shared_ptr<const AnySurface> surface = make_surface(ndf);
            // Each G2 form's exact albedos at this alpha (one Lambda table each for an NDF without a closed form).
            std::vector<std::pair<const FamilyTables*, fit::SingleScatteringAlbedo<AnyNdf>>> exact;
            for (std::size_t g = n; g < tables.size() && tables[g].family == &family; ++g)
                exact.emplace_back(&tables[g], fit::SingleScatteringAlbedo<AnyNdf>(ndf, table_options(tables[g].g2)));
            for (double theta : c.furnace_theta) {
                const double t = theta * std::numbers::pi / 180.0, mu = std::cos(t), s = std::sin(t);
                const Vec3 above{s, 0.0, mu}, below{s, 0.0, -mu};
                auto add = [&](const FamilyTables& ft, const std::string& material, const char* part, const char* form,
                               double value, const walk::Estimate& traced) {
                    rows.push_back({family_label(family), g2_name(ft.g2), material, part, form, alpha, theta, value,
                                    traced.value, traced.stderr_});
                };
                // Mirror facets and conductors: single scattering exact, the compensation from the table of E.
                std::vector<walk::Material> metals{walk::Mirror{}};
                for (const std::string& spec : c.conductors) metals.push_back(registry.materials().make(spec));
                for (const walk::Material& m : metals) {
                    const walk::Estimate total =
                        trace(*surface, m, above, seed, cell++, c.furnace_walks, threads)
                            .albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
                    const std::string name = m.spec();
                    const auto* conductor = m.get_if<walk::Conductor>();
                    auto F = [&](double cos_m) {
                        return conductor ? fresnel_conductor(cos_m, conductor->eta, conductor->k) : 1.0;
                    };
                    const double F_avg = conductor ? fit::average_fresnel(F) : 1.0;
                    for (const auto& [ft, E] : exact) {
                        const fit::AlbedoTable& table = ft->E.table.table;
                        if (!conductor) {
                            add(*ft, name, "total", "kulla-conty",
                                E(mu) + fit::kulla_conty_albedo(table, ft->missing, alpha, mu), total);
                            continue;
                        }
                        const double E_F = E(mu, F), E_mu = table.lookup(alpha, mu);
                        add(*ft, name, "total", "kulla-conty",
                            E_F + fit::kulla_conty_albedo(table, ft->missing, alpha, mu, F_avg), total);
                        add(*ft, name, "total", "turquin", E_F * fit::turquin_scale(E_mu, F(1.0)), total);
                        add(*ft, name, "total", "fdez-aguera", fit::fdez_aguera_albedo(E_F, E_mu, F_avg), total);
                        if (ft->orders)
                            add(*ft, name, "total", "walk-orders",
                                E_F + fit::multiple_scattering_albedo(E_mu, ft->orders->lookup(alpha, mu), F_avg),
                                total);
                    }
                }
                // Dielectrics from each side: single scattering over the table of E_R + E_T.
                for (std::size_t d = 0; d < exact.front().first->dielectrics.size(); ++d) {
                    const DielectricTables& dt = exact.front().first->dielectrics[d];
                    const walk::Material m = walk::Dielectric{dt.eta};
                    const walk::AlbedoTally tally =
                        trace(*surface, m, dt.inside ? below : above, seed, cell++, c.furnace_walks, threads);
                    // The tally's reflection hemisphere is wo.z > 0: from inside, that is the transmitted light.
                    const walk::Hemisphere same =
                        dt.inside ? walk::Hemisphere::transmission : walk::Hemisphere::reflection;
                    const walk::Hemisphere other =
                        dt.inside ? walk::Hemisphere::reflection : walk::Hemisphere::transmission;
                    const std::string material = m.spec() + (dt.inside ? " inside" : " outside");
                    for (const auto& [ft, E] : exact) {
                        const auto single = E.dielectric(mu, dt.relative_eta());
                        const double table = ft->dielectrics[d].sum.table.table.lookup(alpha, mu);
                        add(*ft, material, "total", "turquin", (single.R + single.T) / table,
                            tally.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all));
                        add(*ft, material, "R", "turquin", single.R / table,
                            tally.albedo(same, walk::all_orders, walk::Component::all));
                        add(*ft, material, "T", "turquin", single.T / table,
                            tally.albedo(other, walk::all_orders, walk::Component::all));
                    }
                }
            }
        }
    }
    return rows;
}

}  // namespace smithlab::fitrun
