#include "report/scene.hpp"

#include <algorithm>
#include <cmath>
#include <toml.hpp>

#include "report/sections.hpp"
#include "scene/nearest_name.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

void read_grid(scene::StrictTable& doc, Settings& s) {
    scene::StrictTable grid = doc.table("grid", {"alpha", "mu"});
    s.alphas = scene::read_axis(grid, "alpha");
    s.mus = scene::read_axis(grid, "mu");
    require_positive_mus(grid, "mu", s.mus);
    grid.done();
}

void read_timing(scene::StrictTable& doc, Settings& s) {
    auto timing = doc.optional_table("timing", {"min_time"});
    if (!timing) return;
    s.min_time = timing->real("min_time", s.min_time);
    if (!(s.min_time > 0.0 && s.min_time <= 10.0)) timing->fail("min_time", "must be in (0, 10] seconds");
    timing->done();
}

void read_figures(scene::StrictTable& doc, Settings::Figures& fig) {
    auto f = doc.optional_table(
        "figures", {"pareto", "error_maps", "dimov_heightfields", "dimov_spline_mean", "dimov_gamma4_vs_10"});
    if (!f) return;
    fig.pareto = f->flag("pareto", false);
    fig.error_maps = f->flag("error_maps", false);
    fig.dimov_heightfields = f->flag("dimov_heightfields", false);
    fig.dimov_spline_mean = f->flag("dimov_spline_mean", false);
    fig.dimov_gamma4_vs_10 = f->flag("dimov_gamma4_vs_10", false);
    f->done();
}

// The document's top-level keys, as a message lists them: the title and the grid, every section's, then the timing
// and the figures.
std::vector<std::string> known_keys(const Sections& sections) {
    std::vector<std::string> keys = {"title", "grid"};
    for (const auto& section : sections)
        for (const std::string& k : section->keys()) keys.push_back(k);
    keys.push_back("timing");
    keys.push_back("figures");
    return keys;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry, double scale) {
    return parse_scene(text, source, registry, builtin_sections(), scale);
}

Scene parse_scene(const std::string& text, const std::string& source, const NdfRegistry& registry, Sections sections,
                  double scale) {
    const toml::value data = scene::parse_toml(text, source);
    scene::StrictTable doc(data, source, "", known_keys(sections));
    Scene s{.settings = {}, .sections = std::move(sections)};
    s.settings.scale = scale;
    s.settings.title = doc.text("title", "smithlab report");
    read_grid(doc, s.settings);
    read_timing(doc, s.settings);
    s.settings.min_time *= scale;
    read_figures(doc, s.settings.figures);
    for (const auto& section : s.sections) section->read(doc, s.settings, registry);
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

void require_positive_mus(const scene::StrictTable& t, const std::string& key, const std::vector<double>& mus) {
    for (double mu : mus)
        if (!(mu > 0.0 && std::isfinite(mu)))
            t.fail(key,
                   "values must be finite and > 0 (mu = cot theta, above the surface), got " + format_shortest(mu));
}

void require_matches(const std::vector<std::string>& patterns, const std::vector<std::string>& names,
                     const std::string& where) {
    for (const std::string& p : patterns) {
        if (std::any_of(names.begin(), names.end(), [&](const std::string& n) { return glob_match(p, n); })) continue;
        const std::string near = scene::nearest_name(p, names);
        throw input_error(where + " pattern '" + p + "' matches no name" +
                          (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
}

}  // namespace smithlab::report
