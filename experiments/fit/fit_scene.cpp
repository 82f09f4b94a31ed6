#include "fit/fit_scene.hpp"

#include <cmath>
#include <limits>
#include <variant>

#include "smithlab/csv.hpp"
#include "smithlab/fit/diffuse_models.hpp"
#include "smithlab/spec.hpp"
#include "smithlab/walk/facets.hpp"
#include "scene/strict_table.hpp"

namespace smithlab::fitrun {

namespace {

using report::StrictTable;

constexpr std::size_t max_points = 65535;  // per group: fit_data.hpp's streams give a point 16 bits

// lambert(albedo=1) or fresnel-diffuse(f0=, albedo=1): the facets whose albedo enters only through the diffuse
// events, traced at albedo 1 (the split by events then gives every albedo).
void check_material(StrictTable& doc, const std::string& spec) {
    walk::Material m;
    try {
        m = walk::parse_material(spec);
    } catch (const input_error& e) {
        doc.fail("material", e.what());
    }
    const double albedo = std::visit(
        [](const auto& f) {
            if constexpr (requires { f.albedo; }) return f.albedo;
            else return -1.0;
        },
        m);
    if (albedo < 0.0)
        doc.fail("material", "must be lambert or fresnel-diffuse facets (a diffuse material), got '" + spec + "'");
    if (albedo != 1.0)
        doc.fail("material", "is traced at albedo 1 (every albedo comes from that one trace: set albedos), got '" + spec + "'");
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

FitScene parse_fit_scene(const std::string& text, const std::string& source, const NdfRegistry& registry) {
    const toml::value data = report::parse_toml(text, source);
    StrictTable doc(data, source, "",
                    {"title", "material", "albedos", "models", "floor", "energy_bound", "seed", "ndf", "training", "validation",
                     "compensation", "pictures"});
    FitScene s;
    s.title = doc.text("title", s.title);
    s.material = doc.text("material", s.material);
    check_material(doc, s.material);
    if (doc.has("albedos")) s.albedos = read_bounded(doc, "albedos", 0.0, 1.0, true, false, "(0, 1]");
    s.models = doc.texts("models", {});
    for (const std::string& m : s.models) {
        try {
            fit::find_diffuse_model(m);
        } catch (const input_error& e) {
            doc.fail("models", e.what());
        }
    }
    s.floor = doc.real("floor", s.floor);
    if (!(s.floor >= 0.0 && s.floor < 1.0)) doc.fail("floor", "must be in [0, 1), got " + format_shortest(s.floor));
    s.energy_bound = doc.flag("energy_bound", s.energy_bound);
    s.seed = static_cast<std::uint64_t>(doc.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));

    for (StrictTable& n : doc.tables("ndf", report::ndf_table_keys(registry))) {
        const report::NdfEntry e = report::read_ndf_entry(n, registry);
        if (!e.takes_alpha)
            n.fail("family", "'" + e.family + "' has no parameter alpha and declares no roughness mapping to one: the "
                             "fit sweeps alpha over training.alpha");
        if (e.roughness_given)
            n.fail("family", "'" + e.family + "' is given its roughness here: the fit sweeps alpha over training.alpha");
        for (const report::ParamPoint& p : e.points()) s.ndfs.push_back({e, p});
        n.done();
    }
    if (s.ndfs.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF family");

    StrictTable t = doc.table("training", {"alpha", "theta", "phi", "walks"});
    s.training.alpha = read_bounded(t, "alpha", 0.0, 1.0, true, false, "(0, 1]");
    s.training.theta = read_bounded(t, "theta", 0.0, 90.0, false, true, "[0, 90) degrees");
    s.training.phi = read_bounded(t, "phi", 0.0, 180.0, false, false, "[0, 180] degrees");
    s.training.walks = t.integer("walks", 100, 1'000'000'000, s.training.walks);
    // A point's random stream holds its index in 16 bits (fit_data.hpp).
    std::size_t pairs = 0;
    for (std::size_t i = 0; i < s.training.theta.size(); ++i)
        for (std::size_t o = i; o < s.training.theta.size(); ++o)
            pairs += s.training.theta[i] == 0.0 || s.training.theta[o] == 0.0 ? 1 : s.training.phi.size();
    if (pairs > max_points)
        t.fail("theta", "and phi make " + std::to_string(pairs) + " direction pairs per alpha; at most " +
                            std::to_string(max_points) + " (each point's random stream holds its index in 16 bits)");
    if (s.training.alpha.size() > max_points) t.fail("alpha", "has more than " + std::to_string(max_points) + " values");
    t.done();

    if (auto v = doc.optional_table("validation", {"points", "walks", "albedo_theta", "albedo_walks"})) {
        s.validation.points = v->integer("points", 1, max_points - 1, s.validation.points);
        s.validation.walks = v->integer("walks", 100, 1'000'000'000, s.validation.walks);
        if (v->has("albedo_theta"))
            s.validation.albedo_theta = read_bounded(*v, "albedo_theta", 0.0, 90.0, false, true, "[0, 90) degrees");
        s.validation.albedo_walks = v->integer("albedo_walks", 100, 1'000'000'000, s.validation.albedo_walks);
        v->done();
    }
    if (auto c = doc.optional_table("compensation", {"alpha", "mu"})) {
        s.compensation.alpha = read_bounded(*c, "alpha", 0.0, 1.0, true, false, "(0, 1]");
        s.compensation.mu = c->integer("mu", 2, 4096, s.compensation.mu);
        c->done();
    }
    if (auto p = doc.optional_table("pictures", {"sphere_alpha", "pixels", "walks", "slice_alpha", "slice_n"})) {
        s.pictures.enabled = true;
        if (p->has("sphere_alpha")) s.pictures.sphere_alpha = read_bounded(*p, "sphere_alpha", 0.0, 1.0, true, false, "(0, 1]");
        s.pictures.pixels = p->integer("pixels", 4, 1024, s.pictures.pixels);
        s.pictures.walks = p->integer("walks", 100, 1'000'000'000, s.pictures.walks);
        if (p->has("slice_alpha")) s.pictures.slice_alpha = read_bounded(*p, "slice_alpha", 0.0, 1.0, true, false, "(0, 1]");
        s.pictures.slice_n = p->integer("slice_n", 2, 1024, s.pictures.slice_n);
        p->done();
    }
    doc.done();
    return s;
}

}  // namespace smithlab::fitrun
