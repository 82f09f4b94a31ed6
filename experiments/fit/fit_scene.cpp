#include "fit/fit_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <variant>

#include "scene/spaced.hpp"
#include "scene/strict_table.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/material_registry.hpp"

namespace smithlab::fitrun {

namespace {

using report::StrictTable;

constexpr std::size_t max_points = 65535;  // per group: fit/data_sets.hpp's streams give a point 16 bits

// A material with diffuse events and a parameter `albedo` (lambert, fresnel-diffuse, or a registered one): the
// facets whose albedo enters only through the diffuse events, traced at albedo 1 (the split by events then gives
// every albedo).
void check_material(StrictTable& doc, const std::string& spec, const MaterialRegistry& materials) {
    std::optional<walk::Material> m;
    try {
        m = materials.make(spec);
    } catch (const input_error& e) {
        doc.fail("material", e.what());
    }
    const NdfSpec parts = parse_spec(m->spec(), "material spec");
    const auto albedo = std::find_if(parts.params.begin(), parts.params.end(),
                                     [](const auto& p) { return p.first == "albedo"; });
    if (!m->has_diffuse() && (albedo == parts.params.end() || albedo->second != 0.0))
        doc.fail("material", "must be lambert or fresnel-diffuse facets (a diffuse material), got '" + spec + "'");
    if (albedo == parts.params.end() || albedo->second != 1.0)
        doc.fail("material",
                 "is traced at albedo 1 (every albedo comes from that one trace: set albedos), got '" + spec + "'");
}

// Refuses a list that names one thing twice (equal as values: 1.5 and 1.50, or one conductor spelled two ways).
template <class T, class Describe>
void refuse_repeats(const StrictTable& t, const std::string& key, const std::vector<T>& v, Describe describe) {
    for (std::size_t i = 0; i < v.size(); ++i)
        if (std::find(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(i), v[i]) !=
            v.begin() + static_cast<std::ptrdiff_t>(i))
            t.fail(key, "names " + describe(v[i]) + " twice");
}

std::vector<double> read_bounded(StrictTable& t, const std::string& key, double lo, double hi, bool open_lo,
                                 bool open_hi, const std::string& range) {
    const std::vector<double> v = report::read_axis(t, key);
    for (double x : v)
        if (!((open_lo ? x > lo : x >= lo) && (open_hi ? x < hi : x <= hi)))
            t.fail(key, "values must be in " + range + ", got " + format_shortest(x));
    return v;
}

}  // namespace

std::string family_label(const FitFamily& f) {
    return f.params.empty() && f.entry.texts.empty() ? f.family() : format_spec({f.family(), f.params, f.entry.texts});
}

namespace {

void read_models(StrictTable& doc, FitScene& s, const fit::DiffuseRegistry& models) {
    const std::vector<std::string> names = doc.texts("models", {});
    refuse_repeats(doc, "models", names, [](const std::string& m) { return "'" + m + "'"; });
    for (const std::string& m : names) {
        try {
            s.models.push_back(&models.at(m));
        } catch (const input_error& e) {
            doc.fail("models", e.what());
        }
    }
    if (names.empty())
        for (const fit::DiffuseModel& m : models.list()) s.models.push_back(&m);
}

// The points and walks one fitted NDF traces (fit/data_sets.cpp): the training directions at every training alpha,
// the validation points and albedo directions at every validation alpha (the midpoints of the training alphas).
struct PerNdf {
    double cells = 0.0, walks = 0.0;
};
PerNdf per_ndf(const FitScene& s, std::size_t pairs) {
    const double alphas = static_cast<double>(s.training.alpha.size());
    const double validation_alphas = alphas < 2 ? alphas : alphas - 1;
    const double points = static_cast<double>(s.validation.points);
    const double albedo_dirs = static_cast<double>(s.validation.albedo_theta.size());
    const double train = alphas * static_cast<double>(pairs);
    return {train + validation_alphas * (points + albedo_dirs),
            train * static_cast<double>(s.training.walks) +
                validation_alphas *
                    (points * static_cast<double>(s.validation.walks) +
                     albedo_dirs * static_cast<double>(s.validation.albedo_walks))};
}

// Refuses, at the [[ndf]] entry that brings the fitted NDFs to `ndfs`, a fit of more points or walks than allowed.
void check_size(const StrictTable& n, double ndfs, PerNdf each, const report::SizeLimits& limits) {
    const std::string sweep = format_shortest(ndfs) + " NDFs x ";
    if (ndfs * each.cells > limits.max_cells)
        n.fail("family",
               "makes the fit " + format_shortest(ndfs * each.cells) + " points (" + sweep +
                   format_shortest(each.cells) + " training and validation points), more than --max-cells " +
                   format_shortest(limits.max_cells) + " (raise it with --max-cells N)");
    if (ndfs * each.walks > limits.max_walks)
        n.fail("family",
               "makes the fit " + format_shortest(ndfs * each.walks) + " walks (" + sweep +
                   format_shortest(each.walks) + " walks of training and validation), more than --max-walks " +
                   format_shortest(limits.max_walks) + " (raise it with --max-walks N)");
}

// The [[ndf]] tables, each expanded over its axes: one FitFamily per point, the size checked before.
std::vector<FitFamily> read_ndfs(StrictTable& doc, const NdfRegistry& registry, PerNdf each,
                                 const report::SizeLimits& limits) {
    std::vector<FitFamily> out;
    double ndfs = 0.0;
    for (StrictTable& n : doc.tables("ndf", report::ndf_table_keys(registry))) {
        const report::NdfEntry e = report::read_ndf_entry(n, registry);
        if (!e.takes_alpha)
            n.fail("family",
                   "'" + e.family +
                       "' has no parameter alpha and declares no roughness mapping to one: the "
                       "fit sweeps alpha over training.alpha");
        if (e.roughness_given)
            n.fail("family",
                   "'" + e.family + "' is given its roughness here: the fit sweeps alpha over training.alpha");
        double points = 1.0;
        for (const auto& axis : e.axes) points *= static_cast<double>(axis.second.size());
        check_size(n, ndfs += points, each, limits);
        for (const report::ParamPoint& p : e.points()) out.push_back({e, p});
        n.done();
    }
    if (out.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF family");
    return out;
}

FitScene::Training read_training(StrictTable& doc, FitScene::Training t, double scale, std::size_t& pairs) {
    StrictTable table = doc.table("training", {"alpha", "theta", "phi", "walks"});
    t.alpha = read_bounded(table, "alpha", 0.0, 1.0, true, false, "(0, 1]");
    t.theta = read_bounded(table, "theta", 0.0, 90.0, false, true, "[0, 90) degrees");
    t.phi = read_bounded(table, "phi", 0.0, 180.0, false, false, "[0, 180] degrees");
    t.walks = report::scaled_count(table.integer("walks", 100, 1'000'000'000, t.walks), scale, 100);
    // A point's random stream holds its index in 16 bits (fit/data_sets.hpp).
    pairs = 0;
    for (std::size_t i = 0; i < t.theta.size(); ++i)
        for (std::size_t o = i; o < t.theta.size(); ++o)
            pairs += t.theta[i] == 0.0 || t.theta[o] == 0.0 ? 1 : t.phi.size();
    if (pairs > max_points)
        table.fail("theta",
                   "and phi make " + std::to_string(pairs) + " direction pairs per alpha; at most " +
                       std::to_string(max_points) + " (each point's random stream holds its index in 16 bits)");
    if (t.alpha.size() > max_points) table.fail("alpha", "has more than " + std::to_string(max_points) + " values");
    table.done();
    return t;
}

FitScene::Validation read_validation(StrictTable& doc, FitScene::Validation v, double scale) {
    if (auto t = doc.optional_table("validation", {"points", "walks", "albedo_theta", "albedo_walks"})) {
        v.points = t->integer("points", 1, max_points - 1, v.points);
        v.walks = t->integer("walks", 100, 1'000'000'000, v.walks);
        if (t->has("albedo_theta"))
            v.albedo_theta = read_bounded(*t, "albedo_theta", 0.0, 90.0, false, true, "[0, 90) degrees");
        v.albedo_walks = t->integer("albedo_walks", 100, 1'000'000'000, v.albedo_walks);
        t->done();
    }
    v.walks = report::scaled_count(v.walks, scale, 100);
    v.albedo_walks = report::scaled_count(v.albedo_walks, scale, 100);
    return v;
}

}  // namespace

std::vector<double> FitScene::Compensation::default_alphas() {
    return report::spaced(1e-4, 1.0, 64, report::Spacing::cbrt);
}

std::vector<double> FitScene::Compensation::default_order_alphas() {
    return report::spaced(0.01, 1.0, 16, report::Spacing::cbrt);
}

namespace {

// The tables' work (fit_compensation.cpp) counted in walks, the unit of --max-walks: each family and G2 form tabulates
// E, and E_R and E_T per eta and side, on its check grid, refine x finer in sqrt(alpha) and in x. Measured
// (CPU time of one core, GGX at 16 alphas cube-root spaced from 1e-4 to 1, 48 warped cosines each, at the tables'
// tolerance): 0.25 ms a value of E, ~1000 walks of ~0.3 us (docs/performance.md), and 1.4 ms a value of a
// dielectric's E_R and E_T (eta 1.5 and 1 / 1.5), 6x a value of E.
constexpr double walks_per_value = 1000.0;
constexpr double dielectric_cost = 6.0;

// What the fit's other work adds to the tables': the fitted NDFs and their walks.
struct FitWork {
    double ndfs = 0.0, walks = 0.0;
};

// Refuses [compensation] when its tables' work (in values of E, as walks) and its furnace's walks, with the fit's,
// pass --max-walks.
void check_compensation_size(const StrictTable& t, const FitScene::Compensation& c, FitWork fit,
                             const report::SizeLimits& limits) {
    const double alphas = (static_cast<double>(c.alpha.size()) - 1.0) * static_cast<double>(c.refine) + 1.0;
    auto fine = [&](std::int64_t n) { return (static_cast<double>(n) - 1.0) * static_cast<double>(c.refine) + 1.0; };
    const double cosines = fine(c.cosines), dielectric_cosines = fine(c.dielectric_cosines);
    const double sides = 2.0 * static_cast<double>(c.eta.size());
    const double tables = fit.ndfs * static_cast<double>(c.g2.size());
    const double values = tables * alphas * (cosines + dielectric_cost * sides * dielectric_cosines);
    const double furnace = fit.ndfs * static_cast<double>(c.furnace_alpha.size() * c.furnace_theta.size()) *
        (1.0 + static_cast<double>(c.conductors.size()) + sides) * static_cast<double>(c.furnace_walks);
    const double orders = fit.ndfs * static_cast<double>(c.order_alpha.size()) * static_cast<double>(c.order_cosines) *
        static_cast<double>(c.order_walks);
    const double walks = values * walks_per_value + furnace + orders + fit.walks;
    if (!(walks > limits.max_walks)) return;
    t.fail("refine",
           "with alpha, cosines, dielectric_cosines, g2 and eta makes the tables " + format_shortest(values) +
               " values of E (" + format_shortest(alphas) + " x (" + format_shortest(cosines) + " + " +
               format_shortest(dielectric_cost) + " x " + format_shortest(sides) + " dielectric sides x " +
               format_shortest(dielectric_cosines) + ") check-grid points x " + format_shortest(tables) +
               " NDFs and G2 forms), the work of " + format_shortest(values * walks_per_value) +
               " walks; with the furnace's " + format_shortest(furnace) + ", the scattering orders' " +
               format_shortest(orders) + " and the fit's " + format_shortest(fit.walks) + ", more than --max-walks " +
               format_shortest(limits.max_walks) + " (raise it with --max-walks N)");
}

// A table's alphas in (0, 1]: two at least, ascending (the tables interpolate between them, fit/albedo_grid.hpp).
std::vector<double> table_alphas(StrictTable& t, const char* key) {
    std::vector<double> a = read_bounded(t, key, 0.0, 1.0, true, false, "(0, 1]");
    if (a.size() < 2) t.fail(key, "needs 2 values or more (the tables interpolate between them)");
    for (std::size_t i = 1; i < a.size(); ++i)
        if (!(a[i] > a[i - 1])) t.fail(key, "values must ascend");
    return a;
}

// Refuses, naming the key, an alpha of the tables or the furnace at which a fitted NDF cannot be made (below GGX's
// 1e-50, say): the tables make every NDF at every alpha.
void require_ndfs_at(const StrictTable& t, const std::string& key, const std::vector<double>& alphas,
                     const std::vector<FitFamily>& ndfs, const NdfRegistry& registry) {
    for (const FitFamily& f : ndfs)
        if (f.entry.takes_alpha && !f.entry.roughness_given)
            for (double a : alphas) try {
                    registry.make_at_alpha(f.family(), a, f.params, f.entry.texts);
                } catch (const input_error& e) {
                    t.fail(key, "alpha = " + format_shortest(a) + " for " + family_label(f) + ": " + e.what());
                }
}

FitScene::Compensation read_compensation(StrictTable& doc, FitScene::Compensation c, FitWork fit,
                                         const report::SizeLimits& limits, const std::vector<FitFamily>& ndfs,
                                         const NdfRegistry& registry) {
    auto t = doc.optional_table(
        "compensation",
        {"alpha", "cosines", "dielectric_cosines", "refine", "g2", "eta", "conductors", "furnace_alpha",
         "furnace_theta", "furnace_walks", "order_walks", "order_alpha", "order_cosines"});
    if (!t) return c;
    c.enabled = true;
    if (t->has("alpha")) c.alpha = table_alphas(*t, "alpha");
    require_ndfs_at(*t, "alpha", c.alpha, ndfs, registry);
    c.cosines = t->integer("cosines", 2, 4096, c.cosines);
    c.dielectric_cosines = t->integer("dielectric_cosines", 2, 4096, c.dielectric_cosines);
    c.refine = t->integer("refine", 1, 100, c.refine);
    c.refine = report::scaled_count(c.refine, limits.scale, std::min<std::int64_t>(c.refine, 2));
    if (t->has("g2")) {
        const std::vector<std::string> names = t->texts("g2");
        if (names.empty()) t->fail("g2", "is an empty list");
        refuse_repeats(*t, "g2", names, [](const std::string& g) { return "'" + g + "'"; });
        c.g2.clear();
        for (const std::string& g : names) {
            if (g != "height-correlated" && g != "separable")
                t->fail("g2", "must name height-correlated or separable, got '" + g + "'");
            c.g2.push_back(g == "separable" ? G2Form::uncorrelated : G2Form::height_correlated);
        }
    }
    // eta in [1.01, 100]: a relative index of 1 is no interface; both sides of each are tabulated
    // (eta = [] as the default scene writes it: no dielectric tables)
    if (t->has("eta") && !(t->value("eta").is_array() && t->value("eta").as_array().empty()))
        c.eta = read_bounded(*t, "eta", 1.01, 100.0, false, false, "[1.01, 100]");
    refuse_repeats(*t, "eta", c.eta, [](double e) { return format_shortest(e); });
    c.conductors = t->texts("conductors", {});
    std::vector<std::pair<double, double>> conductors;  // (eta, k): one conductor however it is spelled
    for (const std::string& m : c.conductors) {
        std::optional<walk::Material> material;
        try {
            material = MaterialRegistry().make(m);  // the built-in materials: only a conductor will do
        } catch (const input_error& e) {
            t->fail("conductors", e.what());
        }
        const auto* conductor = material->get_if<walk::Conductor>();
        if (!conductor) t->fail("conductors", "must name conductor(eta=, k=) facets, got '" + m + "'");
        conductors.emplace_back(conductor->eta, conductor->k);
    }
    refuse_repeats(*t, "conductors", conductors, [](const std::pair<double, double>& c) {
        return "conductor(eta=" + format_shortest(c.first) + ", k=" + format_shortest(c.second) + ")";
    });
    if (t->has("furnace_alpha")) c.furnace_alpha = read_bounded(*t, "furnace_alpha", 0.0, 1.0, true, false, "(0, 1]");
    require_ndfs_at(*t, "furnace_alpha", c.furnace_alpha, ndfs, registry);
    if (t->has("furnace_theta"))
        c.furnace_theta = read_bounded(*t, "furnace_theta", 0.0, 90.0, false, true, "[0, 90) degrees");
    c.furnace_walks =
        report::scaled_count(t->integer("furnace_walks", 100, 1'000'000'000, c.furnace_walks), limits.scale, 100);
    c.order_walks = t->integer("order_walks", 0, 1'000'000'000, c.order_walks);
    c.order_walks = report::scaled_count(c.order_walks, limits.scale, std::min<std::int64_t>(c.order_walks, 100));
    if (t->has("order_alpha")) c.order_alpha = table_alphas(*t, "order_alpha");
    require_ndfs_at(*t, "order_alpha", c.order_alpha, ndfs, registry);
    c.order_cosines = t->integer("order_cosines", 2, 4096, c.order_cosines);
    check_compensation_size(*t, c, fit, limits);
    t->done();
    return c;
}

FitScene::Pictures read_pictures(StrictTable& doc, FitScene::Pictures p, double scale) {
    if (auto t = doc.optional_table("pictures", {"sphere_alpha", "pixels", "walks", "slice_alpha", "slice_n"})) {
        p.enabled = true;
        if (t->has("sphere_alpha")) p.sphere_alpha = read_bounded(*t, "sphere_alpha", 0.0, 1.0, true, false, "(0, 1]");
        p.pixels = t->integer("pixels", 4, 1024, p.pixels);
        p.walks = report::scaled_count(t->integer("walks", 100, 1'000'000'000, p.walks), scale, 100);
        if (t->has("slice_alpha")) p.slice_alpha = read_bounded(*t, "slice_alpha", 0.0, 1.0, true, false, "(0, 1]");
        p.slice_n = t->integer("slice_n", 2, 1024, p.slice_n);
        t->done();
    }
    return p;
}

}  // namespace

FitScene parse_fit_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                         const fit::DiffuseRegistry& models, const report::SizeLimits& limits) {
    const toml::value data = report::parse_toml(text, source);
    StrictTable doc(data, source, "",
                    {"title", "material", "albedos", "models", "floor", "energy_bound", "seed", "ndf", "training",
                     "validation", "compensation", "pictures"});
    FitScene s;
    s.title = doc.text("title", s.title);
    s.material = doc.text("material", s.material);
    check_material(doc, s.material, registry.materials());
    // Below 1e-100 a point's variance (albedo^2 times its variance at albedo 1) nears underflow: no fit could weigh it.
    if (doc.has("albedos")) s.albedos = read_bounded(doc, "albedos", 1e-100, 1.0, false, false, "[1e-100, 1]");
    read_models(doc, s, models);
    s.floor = doc.real("floor", s.floor);
    if (!(s.floor >= 0.0 && s.floor < 1.0)) doc.fail("floor", "must be in [0, 1), got " + format_shortest(s.floor));
    s.energy_bound = doc.flag("energy_bound", s.energy_bound);
    s.seed = static_cast<std::uint64_t>(doc.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));
    std::size_t pairs = 0;
    s.training = read_training(doc, s.training, limits.scale, pairs);  // before the NDFs: they size each NDF's work
    s.validation = read_validation(doc, s.validation, limits.scale);
    const PerNdf each = per_ndf(s, pairs);
    s.ndfs = read_ndfs(doc, registry, each, limits);
    const double ndfs = static_cast<double>(s.ndfs.size());
    s.compensation = read_compensation(doc, s.compensation, {ndfs, ndfs * each.walks}, limits, s.ndfs, registry);
    s.pictures = read_pictures(doc, s.pictures, limits.scale);
    doc.done();
    return s;
}

}  // namespace smithlab::fitrun
