#include "fit/fit_scene.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <utility>
#include <variant>

#include "scene/strict_table.hpp"
#include "scene/value_checks.hpp"
#include "scene/walk_options.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/material_registry.hpp"
#include "smithlab/spec.hpp"

namespace smithlab::fit {

namespace {

using scene::read_bounded;
using scene::refuse_repeats;
using scene::StrictTable;

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
    const auto albedo =
        std::find_if(parts.params.begin(), parts.params.end(), [](const auto& p) { return p.first == "albedo"; });
    if (!m->has_diffuse() && (albedo == parts.params.end() || albedo->second != 0.0))
        doc.fail("material", "must be lambert or fresnel-diffuse facets (a diffuse material), got '" + spec + "'");
    if (albedo == parts.params.end() || albedo->second != 1.0)
        doc.fail("material",
                 "is traced at albedo 1 (every albedo comes from that one trace: set albedos), got '" + spec + "'");
}

void read_models(StrictTable& doc, FitScene& s, const fit::DiffuseRegistry& models) {
    const std::vector<std::string> names = doc.texts("models", {});
    scene::refuse_repeats(doc, "models", names, [](const std::string& m) { return "'" + m + "'"; });
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
void check_size(const StrictTable& n, double ndfs, PerNdf each, const scene::SizeLimits& limits) {
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

FitScene::Training read_training(StrictTable& doc, FitScene::Training t, double scale, std::size_t& pairs) {
    StrictTable table = doc.table("training", {"alpha", "theta", "phi", "walks"});
    t.alpha = read_bounded(table, "alpha", 0.0, 1.0, true, false, "(0, 1]");
    t.theta = read_bounded(table, "theta", 0.0, 90.0, false, true, "[0, 90) degrees");
    t.phi = read_bounded(table, "phi", 0.0, 180.0, false, false, "[0, 180] degrees");
    t.walks = scene::scaled_count(table.integer("walks", 100, 1'000'000'000, t.walks), scale, 100);
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
    v.walks = scene::scaled_count(v.walks, scale, 100);
    v.albedo_walks = scene::scaled_count(v.albedo_walks, scale, 100);
    return v;
}

FitScene::Pictures read_pictures(StrictTable& doc, FitScene::Pictures p, double scale) {
    if (auto t = doc.optional_table("pictures", {"sphere_alpha", "pixels", "walks", "slice_alpha", "slice_n"})) {
        p.enabled = true;
        if (t->has("sphere_alpha")) p.sphere_alpha = read_bounded(*t, "sphere_alpha", 0.0, 1.0, true, false, "(0, 1]");
        p.pixels = t->integer("pixels", 4, 1024, p.pixels);
        p.walks = scene::scaled_count(t->integer("walks", 100, 1'000'000'000, p.walks), scale, 100);
        if (t->has("slice_alpha")) p.slice_alpha = read_bounded(*t, "slice_alpha", 0.0, 1.0, true, false, "(0, 1]");
        p.slice_n = t->integer("slice_n", 2, 1024, p.slice_n);
        t->done();
    }
    return p;
}

}  // namespace

FitScene parse_fit_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                         const scene::SizeLimits& limits) {
    const toml::value data = scene::parse_toml(text, source);
    StrictTable doc(data, source, "",
                    {"title", "material", "albedos", "models", "floor", "energy_bound", "seed", "estimator", "ndf",
                     "training", "validation", "compensation", "pictures"});
    FitScene s;
    s.title = doc.text("title", s.title);
    s.material = doc.text("material", s.material);
    check_material(doc, s.material, registry.materials());
    // Below 1e-100 a point's variance (albedo^2 times its variance at albedo 1) nears underflow: no fit could weigh it.
    if (doc.has("albedos")) s.albedos = read_bounded(doc, "albedos", 1e-100, 1.0, false, false, "[1e-100, 1]");
    read_models(doc, s, registry.diffuse_models());
    s.floor = doc.real("floor", s.floor);
    if (!(s.floor >= 0.0 && s.floor < 1.0)) doc.fail("floor", "must be in [0, 1), got " + format_shortest(s.floor));
    s.energy_bound = doc.flag("energy_bound", s.energy_bound);
    s.seed = static_cast<std::uint64_t>(doc.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));
    const std::string estimator = doc.text("estimator", walk::name(s.estimator));
    const Named<walk::EvalEstimator>* e = find_named(walk::eval_estimator_names, estimator);
    if (!e)
        doc.fail("estimator",
                 "must be " + scene::quoted_names(walk::eval_estimator_names) + ", got '" + estimator + "'");
    s.estimator = e->value;
    std::size_t pairs = 0;
    s.training = read_training(doc, s.training, limits.scale, pairs);  // before the NDFs: they size each NDF's work
    s.validation = read_validation(doc, s.validation, limits.scale);
    const PerNdf each = per_ndf(s, pairs);
    s.ndfs = scene::read_alpha_families(doc, registry, "the fit sweeps alpha over training.alpha",
                                        [&](const StrictTable& n, double ndfs) { check_size(n, ndfs, each, limits); });
    const double ndfs = static_cast<double>(s.ndfs.size());
    s.compensation = compensation::read_settings(doc, s.ndfs, ndfs * each.walks, registry, limits);
    s.pictures = read_pictures(doc, s.pictures, limits.scale);
    doc.done();
    return s;
}

}  // namespace smithlab::fit
