#include "scene.hpp"

#include <cmath>
#include <cstdint>
#include <sstream>
#include <toml.hpp>

#include "smithlab/errors.hpp"
#include "strict_table.hpp"

namespace smithlab::report {

namespace {

// The most points one axis may hold: a scene's size is bounded by the work limit (work_estimate.hpp), but an axis
// is made before the work is estimated, so it has its own bound (80 MB of doubles, made in ~0.1 s).
constexpr std::int64_t max_axis_points = 10'000'000;

std::vector<double> spaced(double lo, double hi, std::int64_t n, bool log) {
    std::vector<double> out;
    for (std::int64_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(n - 1);
        out.push_back(log ? lo * std::pow(hi / lo, t) : lo + t * (hi - lo));
    }
    out.back() = hi;
    return out;
}

// A list of numbers, or {log = [lo, hi], n = N}, or {lin = [lo, hi], n = N}.
std::vector<double> axis(StrictTable& t, const std::string& key) {
    const toml::value& v = t.value(key);
    if (v.is_array()) {
        std::vector<double> out = t.reals(key);
        if (out.empty()) t.fail(key, "is an empty list");
        return out;
    }
    if (!v.is_table()) t.fail(key, "must be a list of numbers, {log = [lo, hi], n = N} or {lin = [lo, hi], n = N}, got " + describe_toml(v));
    StrictTable spacing = t.table(key, {"log", "lin", "n"});
    const bool log = spacing.has("log");
    if (log == spacing.has("lin")) t.fail(key, "must hold exactly one of log = [lo, hi] and lin = [lo, hi]");
    const std::string range_key = log ? "log" : "lin";
    const std::vector<double> range = spacing.reals(range_key);
    const std::int64_t n = spacing.integer("n", 2, max_axis_points);
    spacing.done();
    if (range.size() != 2 || !std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[0] < range[1]) || (log && !(range[0] > 0)))
        spacing.fail(range_key, "must be [lo, hi], finite, with lo < hi (and lo > 0 for log)");
    return spaced(range[0], range[1], n, log);
}

NdfFamily ndf_family(StrictTable& t) {
    NdfFamily f{t.text("family"), {}};
    if (t.has("gamma")) f.gammas = axis(t, "gamma");
    t.done();
    return f;
}

void read_grid(StrictTable& doc, Scene& s) {
    StrictTable grid = doc.table("grid", {"alpha", "mu"});
    s.alphas = axis(grid, "alpha");
    s.mus = axis(grid, "mu");
    grid.done();
    for (StrictTable& n : doc.tables("ndf", {"family", "gamma"})) s.ndfs.push_back(ndf_family(n));
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
    s.g2.mus = axis(*g2, "mu");
    g2->done();
}

void read_sampling(StrictTable& doc, Scene& s) {
    auto sm = doc.optional_table("sampling", {"families", "alpha", "theta_o", "samples", "seed"});
    if (!sm) return;
    s.sampling.families = sm->texts("families");
    if (s.sampling.families.empty()) sm->fail("families", "is an empty list");
    s.sampling.alphas = axis(*sm, "alpha");
    s.sampling.theta_o = sm->real("theta_o", s.sampling.theta_o);
    s.sampling.samples = static_cast<std::size_t>(sm->integer("samples", 100, 100'000'000, 100'000));
    s.sampling.seed = static_cast<unsigned long long>(sm->integer("seed", 0, INT64_MAX, 1));
    sm->done();
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

Scene parse_scene(const std::string& text, const std::string& source) {
    toml::value data;
    try {
        std::istringstream in(text);
        data = toml::parse(in, source);
    } catch (const std::exception& e) {  // toml11's syntax errors carry the line
        throw input_error("malformed scene " + source + ":\n" + e.what());
    }
    StrictTable doc(data, source, "", {"title", "grid", "ndf", "variants", "timing", "g2", "sampling", "figures"});
    Scene s;
    s.title = doc.text("title", "smithlab report");
    read_grid(doc, s);
    read_variants(doc, s);
    read_timing(doc, s);
    read_g2(doc, s);
    read_sampling(doc, s);
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
