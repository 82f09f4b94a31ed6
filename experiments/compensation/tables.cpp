#include "compensation/tables.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <mutex>
#include <numbers>

#include "output/progress.hpp"
#include "smithlab/compensation/furnace.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/surface.hpp"

namespace smithlab::compensation {

using scene::AlphaFamily;

std::string DielectricTables::name(const std::string& what) const {
    return what + " eta=" + format_shortest(eta) + (inside ? " inside" : " outside");
}

std::string g2_name(G2Form form) { return form == G2Form::uncorrelated ? "separable" : "height-correlated"; }

compensation::AlbedoOptions table_options(G2Form form) {
    compensation::AlbedoOptions o;
    o.tolerance = compensation::table_tolerance;
    o.g2 = form;
    return o;
}

namespace {

const double furnace_mu_min = std::cos(furnace_theta_max * std::numbers::pi / 180.0);
const std::vector<double> below_factors{0.5, 0.1, 0.01};

using Albedo = compensation::SingleScatteringAlbedo<AnyNdf>;

// The exact albedos of one family and G2 form, one object per alpha (an NDF without a closed-form Lambda builds its
// table in it). Those asked for again are kept: the node alphas (their 1 - E_avg is taken after the tables) and the
// alphas below the grid (every table's below-grid error visits them). Safe from several threads at once.
class AlbedoCache {
public:
    AlbedoCache(const NdfRegistry& registry, const AlphaFamily& f, G2Form form, const std::vector<double>& nodes)
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
    const AlphaFamily& family_;
    G2Form form_;
    const std::vector<double>& nodes_;
    std::mutex mutex_;
    std::map<double, std::shared_ptr<const Albedo>> kept_;
};

// Counts the exact values a table takes on its check grid, from every thread, and says on stderr how far it has come
// (output/progress.hpp: a line every 2 s after the first 3, with an ETA).
class TableProgress {
public:
    TableProgress(std::string what, const compensation::AlbedoGrid& grid, int refine)
        : what_(std::move(what)), total_((static_cast<double>(grid.alphas.size()) - 1.0) * refine + 1.0) {
        total_ *= static_cast<double>(grid.n_x - 1) * refine + 1.0;
    }
    void count() {
        const std::int64_t done = ++done_;
        const std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock) return;  // another thread is saying it
        line_(static_cast<double>(done) / total_,
              [&] { return what_ + ": " + std::to_string(done) + " of " + format_shortest(total_) + " values"; });
    }

private:
    std::string what_;
    double total_;
    std::atomic<std::int64_t> done_{0};
    std::mutex mutex_;
    output::ProgressLine line_;
};

MeasuredTable measured(std::string name, compensation::CheckedTable t, const compensation::AlbedoRow& row,
                       unsigned threads) {
    MeasuredTable m{std::move(name), std::move(t), {}, {}};
    m.below = compensation::below_grid_error(m.table, row, below_factors, threads);
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

// Mirror facets' E at an alpha, one albedo object per alpha, each value counted when `progress` is given.
compensation::AlbedoRow mirror_row(AlbedoCache& albedos, TableProgress* progress) {
    return [&albedos, progress](double alpha) -> std::function<double(double)> {
        return [E = albedos.at(alpha), progress](double mu) {
            if (progress) progress->count();
            return (*E)(mu);
        };
    };
}

// One dielectric side's albedos at an alpha, one albedo object per alpha: E_R, E_T and E_R + E_T, each evaluation
// counted when `progress` is given.
compensation::AlbedoRows side_rows(AlbedoCache& albedos, double rel, TableProgress* progress) {
    return [&albedos, rel, progress](double alpha) -> std::function<void(double, double*)> {
        return [E = albedos.at(alpha), rel, progress](double mu, double* v) {
            if (progress) progress->count();
            const auto e = E->dielectric(mu, rel);
            v[0] = e.R;
            v[1] = e.T;
            v[2] = e.R + e.T;
        };
    };
}

// "COMMAND: compensation tables: FAMILY, G2 G2", the start of a table's lines on stderr.
std::string table_line(const StageRun& run, const AlphaFamily& f, G2Form form) {
    return run.command + ": compensation tables: " + family_label(f) + ", " + g2_name(form) + " G2";
}

// One dielectric side on E's grid, its own cosines and node cluster (compensation::dielectric_grid): E_R, E_T and
// ln(E_R + E_T) in one pass over the check grid; the sum alone below the grid.
void tabulate_side(DielectricTables& d, const compensation::AlbedoGrid& grid, AlbedoCache& albedos,
                   const std::string& line, const Settings& c, unsigned threads) {
    const double rel = d.relative_eta();
    const std::string what =
        line + ", dielectric eta " + format_shortest(d.eta) + " from " + (d.inside ? "inside" : "outside");
    std::fprintf(stderr, "%s, %zu alphas x %lld cosines\n", what.c_str(), c.alpha.size(),
                 static_cast<long long>(c.dielectric_cosines));
    const int refine = static_cast<int>(c.refine);
    const compensation::AlbedoGrid side =
        compensation::dielectric_grid(grid, static_cast<int>(c.dielectric_cosines), rel);
    TableProgress progress(what, side, refine);
    using compensation::Stored;
    std::vector<compensation::CheckedTable> t = compensation::tabulate(
        side, refine, {Stored::value, Stored::value, Stored::log}, side_rows(albedos, rel, &progress), threads);
    const compensation::AlbedoRows rows = side_rows(albedos, rel, nullptr);
    const compensation::AlbedoRow sum = [&](double alpha) -> std::function<double(double)> {
        return [f = rows(alpha)](double mu) {
            double v[3];
            f(mu, v);
            return v[2];
        };
    };
    d.R = std::move(t[0]);
    d.T = std::move(t[1]);
    d.sum = measured(d.name("E_R+E_T"), std::move(t[2]), sum, threads);
    d.sum.furnace = compensation::turquin_furnace(d.sum.table, furnace_mu_min);
}

FamilyTables family_tables(const AlphaFamily& f, G2Form form, const Settings& c, const NdfRegistry& registry,
                           const StageRun& run) {
    const std::string line = table_line(run, f, form);
    std::fprintf(stderr, "%s, %zu alphas x %lld cosines (%lldx finer check)\n", line.c_str(), c.alpha.size(),
                 static_cast<long long>(c.cosines), static_cast<long long>(c.refine));
    const int refine = static_cast<int>(c.refine);
    AlbedoCache albedos(registry, f, form, c.alpha);
    compensation::AlbedoGrid grid{c.alpha, {}, static_cast<int>(c.cosines), {}};
    for (double a : c.alpha) grid.scales.push_back(albedos.at(a)->warp_scale());
    FamilyTables out;
    out.family = &f;
    out.g2 = form;
    out.dielectrics = dielectric_sides(c.eta);
    TableProgress progress(line + ", E", grid, refine);
    out.E = measured("E", compensation::tabulate(grid, refine, mirror_row(albedos, &progress), run.threads),
                     mirror_row(albedos, nullptr), run.threads);
    for (double a : c.alpha) out.exact_missing.push_back(albedos.at(a)->missing());
    out.missing = compensation::table_missing(out.E.table.table);
    out.E.furnace = compensation::kulla_conty_furnace(out.E.table, out.missing, furnace_mu_min);
    for (DielectricTables& d : out.dielectrics) tabulate_side(d, grid, albedos, line, c, run.threads);
    return out;
}

// The first cell of the scattering orders' walks: past every furnace cell (trace_furnace numbers them from 0), so that
// the furnace's walks and the tables it reads draw from different streams.
constexpr std::uint64_t order_cells = std::uint64_t{1} << 40;

// The walk's scattering orders of mirror facets over the order grid (compensation/scattering_orders.hpp) for one
// family, from order_walks walks a node. Node k of family n draws from cells order_cells + n * 2^32 + k.
std::shared_ptr<const compensation::OrderTables> make_orders(const AlphaFamily& f, std::size_t n, const Settings& c,
                                                             const NdfRegistry& registry, const StageRun& run) {
    std::fprintf(stderr, "%s: scattering orders: %s, %zu alphas x %lld cosines, %lld walks a node\n",
                 run.command.c_str(), family_label(f).c_str(), c.order_alpha.size(),
                 static_cast<long long>(c.order_cosines), static_cast<long long>(c.order_walks));
    compensation::AlbedoGrid grid{c.order_alpha, {}, static_cast<int>(c.order_cosines), {}};
    std::vector<std::shared_ptr<const AnySurface>> surfaces;
    for (double a : c.order_alpha) {
        const AnyNdf ndf = make_ndf(registry, f, a);
        grid.scales.push_back(Albedo(ndf, table_options(G2Form::height_correlated)).warp_scale());
        surfaces.push_back(make_surface(ndf));
    }
    const std::uint64_t first = order_cells + (static_cast<std::uint64_t>(n) << 32);
    const compensation::OrderCell trace = [&](std::size_t node, double, double mu) {
        const AnySurface& s = *surfaces[node / static_cast<std::size_t>(grid.n_x)];
        walk::CellRequest r;
        r.wi = {std::sqrt((1.0 - mu) * (1.0 + mu)), 0.0, mu};
        r.seed = run.seed;
        r.cell = first + node;
        r.walks = c.order_walks;
        walk::AlbedoTally total;
        for (std::uint64_t b = 0; b < walk::block_count(r.walks, r.block); ++b)
            total.merge(s.trace_block(walk::Mirror{}, r, b).albedo);
        return total;
    };
    return std::make_shared<const compensation::OrderTables>(compensation::tabulate_orders(grid, trace, run.threads));
}

// The orders for a renderer of the separable G2: q_1 = (E_hc - E_sep) / (1 - E_sep) at each node, the share of the
// light its single scattering misses that the walk scatters once (compensation/scattering_orders.hpp); 0 where 1 -
// E_sep < 1e-12.
std::shared_ptr<const compensation::OrderTables> with_single_share(const compensation::OrderTables& walk,
                                                                   const AlphaFamily& f, const NdfRegistry& registry) {
    auto t = std::make_shared<compensation::OrderTables>(walk);
    const compensation::AlbedoGrid& g = walk.q2.grid;
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

}  // namespace

std::vector<FamilyTables> make_tables(const std::vector<AlphaFamily>& families, const Settings& c,
                                      const NdfRegistry& registry, const StageRun& run) {
    std::vector<FamilyTables> all;
    for (std::size_t n = 0; n < families.size(); ++n) {
        const AlphaFamily& f = families[n];
        const auto orders = c.order_walks > 0 ? make_orders(f, n, c, registry, run) : nullptr;
        for (G2Form form : c.g2) {
            all.push_back(family_tables(f, form, c, registry, run));
            all.back().orders =
                orders && form == G2Form::uncorrelated ? with_single_share(*orders, f, registry) : orders;
        }
    }
    return all;
}

}  // namespace smithlab::compensation
