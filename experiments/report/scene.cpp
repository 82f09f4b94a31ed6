#include "report/scene.hpp"

#include <cmath>
#include <cstdint>
#include <toml.hpp>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/walk/facets.hpp"
#include "scene/strict_table.hpp"

namespace smithlab::report {

namespace {

NdfEntry ndf_entry(StrictTable& t, const NdfRegistry& registry) {
    NdfEntry e = read_ndf_entry(t, registry);
    t.done();
    return e;
}

void read_grid(StrictTable& doc, Scene& s, const NdfRegistry& registry) {
    StrictTable grid = doc.table("grid", {"alpha", "mu"});
    s.alphas = read_axis(grid, "alpha");
    s.mus = read_axis(grid, "mu");
    grid.done();
    for (StrictTable& n : doc.tables("ndf", ndf_table_keys(registry))) s.ndfs.push_back(ndf_entry(n, registry));
    if (s.ndfs.empty()) doc.fail("ndf", "is missing: no [[ndf]] table names an NDF family");
}

void read_variants(StrictTable& doc, Scene& s) {
    StrictTable variants = doc.table("variants", {"include", "exclude"});
    s.include = variants.texts("include");
    s.exclude = variants.texts("exclude", {});
    variants.done();
}

void read_timing(StrictTable& doc, Scene& s) {
    auto timing = doc.optional_table("timing", {"min_time"});
    if (!timing) return;
    s.min_time = timing->real("min_time", s.min_time);
    if (!(s.min_time > 0.0 && s.min_time <= 10.0)) timing->fail("min_time", "must be in (0, 10] seconds");
    timing->done();
}

void read_g2(StrictTable& doc, Scene& s) {
    auto g2 = doc.optional_table("g2", {"include", "families", "mu"});
    if (!g2) return;
    s.g2.include = g2->texts("include");
    s.g2.families = g2->texts("families", s.g2.families);
    s.g2.mus = read_axis(*g2, "mu");
    g2->done();
}

void read_sampling(StrictTable& doc, Scene& s) {
    auto sm = doc.optional_table("sampling", {"families", "alpha", "theta_o", "samples", "seed"});
    if (!sm) return;
    s.sampling.families = sm->texts("families");
    if (s.sampling.families.empty()) sm->fail("families", "is an empty list");
    s.sampling.alphas = read_axis(*sm, "alpha");
    s.sampling.theta_o = sm->real("theta_o", s.sampling.theta_o);
    s.sampling.samples = static_cast<std::size_t>(sm->integer("samples", 100, 100'000'000, 100'000));
    s.sampling.seed = static_cast<unsigned long long>(sm->integer("seed", 0, INT64_MAX, 1));
    sm->done();
}

void read_walk(StrictTable& doc, Scene& s, const NdfRegistry& registry) {
    auto w = doc.optional_table("walk", {"ndf", "materials", "alpha", "theta_i", "walks", "seed"});
    if (!w) return;
    Scene::Walk& walk = s.walk;
    for (StrictTable& n : w->tables("ndf", ndf_table_keys(registry))) walk.ndfs.push_back(ndf_entry(n, registry));
    if (walk.ndfs.empty()) w->fail("ndf", "is missing: no [[walk.ndf]] table names an NDF family");
    walk.materials = w->texts("materials", walk.materials);
    if (walk.materials.empty()) w->fail("materials", "is an empty list");
    for (const std::string& m : walk.materials) try {
            walk::parse_material(m);
        } catch (const input_error& e) {
            w->fail("materials", "holds \"" + m + "\": " + e.what());
        }
    walk.alphas = read_axis(*w, "alpha");
    for (double a : walk.alphas)
        if (!std::isfinite(a)) w->fail("alpha", "must be finite, got " + format_shortest(a));
    if (w->has("theta_i")) walk.theta_i = read_axis(*w, "theta_i");
    for (double t : walk.theta_i)
        if (!(t >= 0.0 && t < 90.0)) w->fail("theta_i", "must be in [0, 90) degrees (light from above), got " + format_shortest(t));
    walk.walks = w->integer("walks", 100, 1'000'000'000, walk.walks);
    walk.seed = static_cast<unsigned long long>(w->integer("seed", 0, INT64_MAX, 1));
    w->done();
}

void read_figures(StrictTable& doc, Scene& s) {
    auto f = doc.optional_table("figures", {"pareto", "error_maps", "dimov_heightfields", "dimov_spline_mean", "dimov_gamma4_vs_10"});
    if (!f) return;
    s.figures.pareto = f->flag("pareto", false);
    s.figures.error_maps = f->flag("error_maps", false);
    s.figures.dimov_heightfields = f->flag("dimov_heightfields", false);
    s.figures.dimov_spline_mean = f->flag("dimov_spline_mean", false);
    s.figures.dimov_gamma4_vs_10 = f->flag("dimov_gamma4_vs_10", false);
    f->done();
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry) {
    const toml::value data = parse_toml(text, source);
    StrictTable doc(data, source, "", {"title", "grid", "ndf", "variants", "timing", "g2", "sampling", "walk", "figures"});
    Scene s;
    s.title = doc.text("title", "smithlab report");
    read_grid(doc, s, registry);
    read_variants(doc, s);
    read_timing(doc, s);
    read_g2(doc, s);
    read_sampling(doc, s);
    read_walk(doc, s, registry);
    read_figures(doc, s);
    doc.done();
    return s;
}

bool glob_match(const std::string& pattern, const std::string& name) {
    std::size_t p = 0, n = 0, star = std::string::npos, mark = 0;
    while (n < name.size()) {
        if (p < pattern.size() && pattern[p] == '*') {
            star = p++;
            mark = n;
        } else if (p < pattern.size() && pattern[p] == name[n]) {
            ++p;
            ++n;
        } else if (star != std::string::npos) {
            p = star + 1;
            n = ++mark;
        } else {
            return false;
        }
    }
    while (p < pattern.size() && pattern[p] == '*') ++p;
    return p == pattern.size();
}

}  // namespace smithlab::report
