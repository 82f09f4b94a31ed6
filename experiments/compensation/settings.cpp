#include "compensation/settings.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <variant>

#include "scene/spaced.hpp"
#include "scene/value_checks.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/material_registry.hpp"

namespace smithlab::compensation {

using scene::StrictTable;

std::vector<double> Settings::default_alphas() { return scene::spaced(1e-4, 1.0, 64, scene::Spacing::cbrt); }

std::vector<double> Settings::default_order_alphas() { return scene::spaced(0.01, 1.0, 16, scene::Spacing::cbrt); }

namespace {

// The tables' work (compensation/tables.cpp) counted in walks, the unit of --max-walks: each family and G2 form
// tabulates E, and E_R and E_T per eta and side, on its check grid, refine x finer in sqrt(alpha) and in x. Measured
// (CPU time of one core, GGX at 16 alphas cube-root spaced from 1e-4 to 1, 48 warped cosines each, at the tables'
// tolerance): 0.25 ms a value of E, ~1000 walks of ~0.3 us (docs/performance.md), and 1.4 ms a value of a
// dielectric's E_R and E_T (eta 1.5 and 1 / 1.5), 6x a value of E.
constexpr double walks_per_value = 1000.0;
constexpr double dielectric_cost = 6.0;

// Refuses [compensation] when its tables' work (in values of E, as walks) and its furnace's and orders' walks, with
// the rest of the run's (a fit's), pass --max-walks.
void check_size(const StrictTable& t, const Settings& c, double families, double other_walks,
                const scene::SizeLimits& limits) {
    const double alphas = (static_cast<double>(c.alpha.size()) - 1.0) * static_cast<double>(c.refine) + 1.0;
    auto fine = [&](std::int64_t n) { return (static_cast<double>(n) - 1.0) * static_cast<double>(c.refine) + 1.0; };
    const double cosines = fine(c.cosines), dielectric_cosines = fine(c.dielectric_cosines);
    const double sides = 2.0 * static_cast<double>(c.eta.size());
    const double tables = families * static_cast<double>(c.g2.size());
    const double values = tables * alphas * (cosines + dielectric_cost * sides * dielectric_cosines);
    const double furnace = families * static_cast<double>(c.furnace_alpha.size() * c.furnace_theta.size()) *
        (1.0 + static_cast<double>(c.conductors.size()) + sides) * static_cast<double>(c.furnace_walks);
    const double orders = families * static_cast<double>(c.order_alpha.size()) * static_cast<double>(c.order_cosines) *
        static_cast<double>(c.order_walks);
    const double walks = values * walks_per_value + furnace + orders + other_walks;
    if (!(walks > limits.max_walks)) return;
    const std::string with = other_walks > 0.0
        ? ", the scattering orders' " + format_shortest(orders) + " and the fit's " + format_shortest(other_walks)
        : " and the scattering orders' " + format_shortest(orders);
    t.fail("refine",
           "with alpha, cosines, dielectric_cosines, g2 and eta makes the tables " + format_shortest(values) +
               " values of E (" + format_shortest(alphas) + " x (" + format_shortest(cosines) + " + " +
               format_shortest(dielectric_cost) + " x " + format_shortest(sides) + " dielectric sides x " +
               format_shortest(dielectric_cosines) + ") check-grid points x " + format_shortest(tables) +
               " NDFs and G2 forms), the work of " + format_shortest(values * walks_per_value) +
               " walks; with the furnace's " + format_shortest(furnace) + with + ", more than --max-walks " +
               format_shortest(limits.max_walks) + " (raise it with --max-walks N)");
}

// A table's alphas in (0, 1]: two at least, ascending (the tables interpolate between them,
// compensation/albedo_grid.hpp).
std::vector<double> table_alphas(StrictTable& t, const char* key) {
    std::vector<double> a = scene::read_bounded(t, key, 0.0, 1.0, true, false, "(0, 1]");
    if (a.size() < 2) t.fail(key, "needs 2 values or more (the tables interpolate between them)");
    for (std::size_t i = 1; i < a.size(); ++i)
        if (!(a[i] > a[i - 1])) t.fail(key, "values must ascend");
    return a;
}

// Refuses, naming the key, an alpha of the tables or the furnace at which a family cannot be made (below GGX's
// 1e-50, say): the tables make every NDF at every alpha.
void require_ndfs_at(const StrictTable& t, const std::string& key, const std::vector<double>& alphas,
                     const std::vector<scene::AlphaFamily>& families, const NdfRegistry& registry) {
    for (const scene::AlphaFamily& f : families)
        if (f.entry.takes_alpha && !f.entry.roughness_given)
            for (double a : alphas) try {
                    registry.make_at_alpha(f.family(), a, f.params, f.entry.texts);
                } catch (const input_error& e) {
                    t.fail(key, "alpha = " + format_shortest(a) + " for " + family_label(f) + ": " + e.what());
                }
}

// g2: a list of height-correlated and separable, each once.
std::vector<G2Form> read_g2(StrictTable& t) {
    const std::vector<std::string> names = t.texts("g2");
    if (names.empty()) t.fail("g2", "is an empty list");
    scene::refuse_repeats(t, "g2", names, [](const std::string& g) { return "'" + g + "'"; });
    std::vector<G2Form> forms;
    for (const std::string& g : names) {
        if (g != "height-correlated" && g != "separable")
            t.fail("g2", "must name height-correlated or separable, got '" + g + "'");
        forms.push_back(g == "separable" ? G2Form::uncorrelated : G2Form::height_correlated);
    }
    return forms;
}

// conductors: conductor(eta=, k=) facets, each conductor once however it is spelled.
std::vector<std::string> read_conductors(StrictTable& t) {
    std::vector<std::string> specs = t.texts("conductors", {});
    std::vector<std::pair<double, double>> conductors;  // (eta, k)
    for (const std::string& m : specs) {
        std::optional<walk::Material> material;
        try {
            material = MaterialRegistry().make(m);  // the built-in materials: only a conductor will do
        } catch (const input_error& e) {
            t.fail("conductors", e.what());
        }
        const auto* conductor = material->get_if<walk::Conductor>();
        if (!conductor) t.fail("conductors", "must name conductor(eta=, k=) facets, got '" + m + "'");
        conductors.emplace_back(conductor->eta, conductor->k);
    }
    scene::refuse_repeats(t, "conductors", conductors, [](const std::pair<double, double>& c) {
        return "conductor(eta=" + format_shortest(c.first) + ", k=" + format_shortest(c.second) + ")";
    });
    return specs;
}

// Below scale 1 a table's axis of n nodes keeps n sqrt(scale) of them (its nodes times scale), at least 8 or n.
std::int64_t scaled_axis(std::int64_t n, double scale) {
    return scale < 1.0 ? scene::scaled_count(n, std::sqrt(scale), std::min<std::int64_t>(n, 8)) : n;
}

// The alphas a, scaled_axis of them: evenly spaced in index, the first and the last kept.
std::vector<double> thinned(const std::vector<double>& a, double scale) {
    const auto n = static_cast<std::int64_t>(a.size()), k = scaled_axis(n, scale);
    if (k >= n) return a;
    std::vector<double> out;
    for (std::int64_t j = 0; j < k; ++j)
        out.push_back(a[static_cast<std::size_t>((j * (n - 1) + (k - 1) / 2) / (k - 1))]);
    return out;
}

// The tables' grid and G2 forms, and the dielectrics' eta; below scale 1 the grid thinned (scaled_axis).
void read_tables(StrictTable& t, Settings& c, const std::vector<scene::AlphaFamily>& families,
                 const NdfRegistry& registry, double scale) {
    if (t.has("alpha")) c.alpha = table_alphas(t, "alpha");
    require_ndfs_at(t, "alpha", c.alpha, families, registry);
    c.alpha = thinned(c.alpha, scale);
    c.cosines = scaled_axis(t.integer("cosines", 2, 4096, c.cosines), scale);
    c.dielectric_cosines = scaled_axis(t.integer("dielectric_cosines", 2, 4096, c.dielectric_cosines), scale);
    c.refine = t.integer("refine", 1, 100, c.refine);
    c.refine = scene::scaled_count(c.refine, scale, std::min<std::int64_t>(c.refine, 2));
    if (t.has("g2")) c.g2 = read_g2(t);
    // eta in [1.01, 100]: a relative index of 1 is no interface; both sides of each are tabulated
    // (eta = [] as the default scene writes it: no dielectric tables)
    if (t.has("eta") && !(t.value("eta").is_array() && t.value("eta").as_array().empty()))
        c.eta = scene::read_bounded(t, "eta", 1.01, 100.0, false, false, "[1.01, 100]");
    scene::refuse_repeats(t, "eta", c.eta, [](double e) { return format_shortest(e); });
}

// The walks: the furnace's cells and the scattering orders'.
void read_walks(StrictTable& t, Settings& c, const std::vector<scene::AlphaFamily>& families,
                const NdfRegistry& registry, double scale) {
    c.conductors = read_conductors(t);
    if (t.has("furnace_alpha"))
        c.furnace_alpha = scene::read_bounded(t, "furnace_alpha", 0.0, 1.0, true, false, "(0, 1]");
    require_ndfs_at(t, "furnace_alpha", c.furnace_alpha, families, registry);
    if (t.has("furnace_theta"))
        c.furnace_theta = scene::read_bounded(t, "furnace_theta", 0.0, 90.0, false, true, "[0, 90) degrees");
    c.furnace_walks = scene::scaled_count(t.integer("furnace_walks", 100, 1'000'000'000, c.furnace_walks), scale, 100);
    c.order_walks = t.integer("order_walks", 0, 1'000'000'000, c.order_walks);
    c.order_walks = scene::scaled_count(c.order_walks, scale, std::min<std::int64_t>(c.order_walks, 100));
    if (t.has("order_alpha")) c.order_alpha = table_alphas(t, "order_alpha");
    require_ndfs_at(t, "order_alpha", c.order_alpha, families, registry);
    c.order_cosines = t.integer("order_cosines", 2, 4096, c.order_cosines);
}

}  // namespace

Settings read_settings(StrictTable& doc, const std::vector<scene::AlphaFamily>& families, double other_walks,
                       const NdfRegistry& registry, const scene::SizeLimits& limits) {
    Settings c;
    auto t = doc.optional_table(
        "compensation",
        {"alpha", "cosines", "dielectric_cosines", "refine", "g2", "eta", "conductors", "furnace_alpha",
         "furnace_theta", "furnace_walks", "order_walks", "order_alpha", "order_cosines"});
    if (!t) return c;
    c.enabled = true;
    read_tables(*t, c, families, registry, limits.scale);
    read_walks(*t, c, families, registry, limits.scale);
    check_size(*t, c, static_cast<double>(families.size()), other_walks, limits);
    t->done();
    return c;
}

}  // namespace smithlab::compensation
