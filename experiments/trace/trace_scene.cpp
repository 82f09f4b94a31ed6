#include "trace/trace_scene.hpp"

#include <cmath>
#include <limits>

#include "scene/scene_ndf.hpp"
#include "scene/strict_table.hpp"
#include "scene/walk_options.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/spec.hpp"

namespace smithlab::trace {

namespace {

using scene::StrictTable;

// The NDFs an entry makes (its axes' points, over grid.alpha unless it gives its roughness), as a double: no overflow.
double ndf_count(const scene::NdfEntry& e, std::size_t alphas) {
    double n = e.roughness_given ? 1.0 : static_cast<double>(alphas);
    for (const auto& axis : e.axes) n *= static_cast<double>(axis.second.size());
    return n;
}

// Refuses, at the [[ndf]] entry that brings the NDFs to `ndfs`, a scene of more cells or walks than the limits allow.
void check_size(const scene::StrictTable& n, const std::string& key, double ndfs, const TraceScene& s,
                const scene::SizeLimits& limits) {
    const double cells = ndfs * static_cast<double>(s.materials.size()) * static_cast<double>(s.theta_i.size()) *
        static_cast<double>(s.phi_i.size());
    const double bins = s.brdf.empty() ? 0.0 : static_cast<double>(s.brdf.n_theta) * s.brdf.n_phi;
    const std::string sweep = format_shortest(ndfs) + " NDFs x " + std::to_string(s.materials.size()) +
        " materials x " + std::to_string(s.theta_i.size()) + " grid.theta_i x " + std::to_string(s.phi_i.size()) +
        " grid.phi_i";
    if (cells * (1.0 + bins) > limits.max_cells)
        n.fail(key,
               "makes the scene " + format_shortest(cells * (1.0 + bins)) + " cells (" + sweep +
                   (bins > 0 ? ", each with " + format_shortest(bins) + " brdf bins counted as cells" : "") +
                   "), more than --max-cells " + format_shortest(limits.max_cells) + " (raise it with --max-cells N)");
    if (cells * static_cast<double>(s.walks) > limits.max_walks)
        n.fail(key,
               "makes the scene " + format_shortest(cells * static_cast<double>(s.walks)) + " walks (" + sweep +
                   " x walks.n " + std::to_string(s.walks) + "), more than --max-walks " +
                   format_shortest(limits.max_walks) + " (raise it with --max-walks N)");
}

void read_ndfs(scene::StrictTable& doc, const std::vector<double>& alphas, const NdfRegistry& registry,
               const scene::SizeLimits& limits, TraceScene& s) {
    const std::vector<std::string> keys = scene::ndf_table_keys(registry, {"spec"});
    double ndfs = 0.0;
    for (scene::StrictTable& n : doc.tables("ndf", keys)) {
        if (n.has("spec") == n.has("family")) n.fail("spec", "or family: give exactly one of them");
        if (n.has("spec")) {
            for (const std::string& k : keys)
                if (k != "spec" && n.has(k)) n.fail(k, "goes with family, not with a fixed spec");
            check_size(n, "spec", ndfs += 1.0, s, limits);
            s.ndfs.push_back({n.text("spec"), std::nullopt});
        } else {
            const scene::NdfEntry e = scene::read_ndf_entry(n, registry);
            if (!e.roughness_given && alphas.empty()) n.fail("family", "is swept over grid.alpha, which is missing");
            check_size(n, "family", ndfs += ndf_count(e, alphas.size()), s, limits);
            auto add = [&](const scene::ParamPoint& point, std::optional<double> alpha) {
                const AnyNdf ndf = scene::make_entry_ndf(e, registry, point, alpha);
                s.ndfs.push_back({ndf.spec(), ndf.parts()});
            };
            if (e.roughness_given)
                for (const scene::ParamPoint& p : e.points()) add(p, std::nullopt);
            else
                for (double a : alphas)
                    for (const scene::ParamPoint& p : e.points()) add(p, a);
        }
        n.done();
    }
    if (s.ndfs.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF");
}

}  // namespace

TraceScene parse_trace_scene(const std::string& text, const std::string& source, const NdfRegistry& registry,
                             const scene::SizeLimits& limits) {
    const toml::value data = scene::parse_toml(text, source);
    scene::StrictTable doc(data, source, "", {"title", "materials", "walks", "grid", "ndf", "brdf"});
    TraceScene s;
    s.title = doc.text("title", s.title);
    s.materials = doc.texts("materials");
    if (s.materials.empty()) doc.fail("materials", "is an empty list");

    if (auto w = doc.optional_table("walks", {"n", "seed", "max_order", "downward", "hit_normal"})) {
        s.walks = w->integer("n", 1, 1'000'000'000'000, s.walks);
        s.seed = static_cast<std::uint64_t>(w->integer("seed", 0, std::numeric_limits<std::int64_t>::max(), 1));
        s.max_order = static_cast<int>(w->integer("max_order", 0, 1'000'000, 0));
        s.downward = w->text("downward", s.downward);
        if (!find_named(downward_names, s.downward))
            w->fail("downward", "must be " + scene::quoted_names(downward_names) + ", got \"" + s.downward + "\"");
        s.hit_normal = w->text("hit_normal", s.hit_normal);
        if (!find_named(scene::hit_normal_names, s.hit_normal))
            w->fail("hit_normal",
                    "must be " + scene::quoted_names(scene::hit_normal_names) + ", got \"" + s.hit_normal + "\"");
        w->done();
    }
    s.walks = scene::scaled_count(s.walks, limits.scale, 1);

    scene::StrictTable grid = doc.table("grid", {"alpha", "theta_i", "phi_i"});
    const std::vector<double> alphas = grid.has("alpha") ? scene::read_axis(grid, "alpha") : std::vector<double>{};
    s.theta_i = scene::read_axis(grid, "theta_i");
    for (double t : s.theta_i)
        if (!(t >= 0.0 && t <= 180.0 && t != 90.0))
            grid.fail("theta_i",
                      "must be in [0, 90) degrees (light from above), or (90, 180] for light from below into a "
                      "dielectric, got " +
                          format_shortest(t));
    s.phi_i = grid.has("phi_i") ? scene::read_axis(grid, "phi_i") : std::vector<double>{0.0};
    for (double p : s.phi_i)
        if (!std::isfinite(p)) grid.fail("phi_i", "must be finite");
    if (auto b = doc.optional_table("brdf", {"theta_bins", "phi_bins"})) {  // before the NDFs: it sizes each cell
        s.brdf.n_theta = static_cast<int>(b->integer("theta_bins", 1, 10'000));
        s.brdf.n_phi = static_cast<int>(b->integer("phi_bins", 1, 10'000));
        b->done();
    }
    read_ndfs(doc, alphas, registry, limits, s);
    grid.done();
    doc.done();
    return s;
}

std::vector<TraceCell> cells(const TraceScene& s) {
    std::vector<TraceCell> out;
    for (const SceneNdf& ndf : s.ndfs)
        for (const std::string& material : s.materials)
            for (double t : s.theta_i)
                for (double p : s.phi_i) out.push_back({out.size(), ndf.spec, material, t, p});
    return out;
}

}  // namespace smithlab::trace
