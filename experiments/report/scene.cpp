#include "scene.hpp"

#include <cmath>
#include <sstream>
#include <toml.hpp>

#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

// A list of numbers, or {log = [lo, hi], n = N}, or {lin = [lo, hi], n = N}.
std::vector<double> axis(const toml::value& v, const std::string& where) {
    if (v.is_array()) {
        std::vector<double> out;
        for (const auto& x : v.as_array()) {
            if (!x.is_integer() && !x.is_floating()) throw input_error(where + " must hold numbers");
            out.push_back(x.is_integer() ? double(x.as_integer()) : x.as_floating());
        }
        if (out.empty()) throw input_error(where + " is an empty list");
        return out;
    }
    const bool log = v.is_table() && v.contains("log");
    if (!log && !(v.is_table() && v.contains("lin"))) throw input_error(where + " must be a list, {log = [lo, hi], n = N} or {lin = [lo, hi], n = N}");
    const auto range = toml::find<std::vector<double>>(v, log ? "log" : "lin");
    const auto n = toml::find<int>(v, "n");
    if (range.size() != 2 || n < 2 || !(range[0] < range[1]) || (log && !(range[0] > 0)))
        throw input_error(where + ": need lo < hi (lo > 0 for log) and n >= 2");
    std::vector<double> out;
    for (int i = 0; i < n; ++i) {
        const double t = i / double(n - 1);
        out.push_back(log ? range[0] * std::pow(range[1] / range[0], t) : range[0] + t * (range[1] - range[0]));
    }
    out.back() = range[1];
    return out;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& source) {
    try {
        std::istringstream in(text);
        const toml::value data = toml::parse(in, source);
        Scene s;
        s.title = toml::find_or<std::string>(data, "title", "smithlab report");
        const auto& grid = toml::find(data, "grid");
        s.alphas = axis(toml::find(grid, "alpha"), source + ": grid.alpha");
        s.mus = axis(toml::find(grid, "mu"), source + ": grid.mu");
        for (const auto& n : toml::find<std::vector<toml::value>>(data, "ndf")) {
            NdfFamily f{toml::find<std::string>(n, "family"), {}};
            if (n.contains("gamma")) f.gammas = axis(toml::find(n, "gamma"), source + ": ndf." + f.family + ".gamma");
            s.ndfs.push_back(f);
        }
        if (s.ndfs.empty()) throw input_error(source + ": no [[ndf]] table");
        const auto& variants = toml::find(data, "variants");
        s.include = toml::find<std::vector<std::string>>(variants, "include");
        s.exclude = toml::find_or<std::vector<std::string>>(variants, "exclude", {});
        if (data.contains("timing")) s.min_time = toml::find_or<double>(toml::find(data, "timing"), "min_time", 0.05);
        if (!(s.min_time > 0.0 && s.min_time <= 10.0)) throw input_error(source + ": timing.min_time must be in (0, 10] seconds");
        if (data.contains("g2")) {
            const auto& g = toml::find(data, "g2");
            s.g2.include = toml::find<std::vector<std::string>>(g, "include");
            if (g.contains("families")) s.g2.families = toml::find<std::vector<std::string>>(g, "families");
            s.g2.mus = axis(toml::find(g, "mu"), source + ": g2.mu");
        }
        if (data.contains("sampling")) {
            const auto& sm = toml::find(data, "sampling");
            s.sampling.families = toml::find<std::vector<std::string>>(sm, "families");
            if (s.sampling.families.empty()) throw input_error(source + ": sampling.families is an empty list");
            s.sampling.alphas = axis(toml::find(sm, "alpha"), source + ": sampling.alpha");
            s.sampling.theta_o = toml::find_or<double>(sm, "theta_o", 45.0);
            const auto n = toml::find_or<long long>(sm, "samples", 100000);
            if (n < 100 || n > 100000000) throw input_error(source + ": sampling.samples must be in [100, 1e8]");
            s.sampling.samples = static_cast<std::size_t>(n);
            const auto seed = toml::find_or<long long>(sm, "seed", 1);
            if (seed < 0) throw input_error(source + ": sampling.seed must be >= 0");
            s.sampling.seed = static_cast<unsigned long long>(seed);
        }
        if (data.contains("figures")) {
            const auto& f = toml::find(data, "figures");
            for (const auto& [key, value] : f.as_table()) {
                bool* flag = key == "pareto"                ? &s.figures.pareto
                             : key == "error_maps"          ? &s.figures.error_maps
                             : key == "dimov_heightfields"  ? &s.figures.dimov_heightfields
                             : key == "dimov_spline_mean"   ? &s.figures.dimov_spline_mean
                             : key == "dimov_gamma4_vs_10"  ? &s.figures.dimov_gamma4_vs_10
                                                            : nullptr;
                if (!flag) throw input_error(source + ": unknown figure '" + key + "'");
                if (!value.is_boolean()) throw input_error(source + ": figures." + key + " must be true or false");
                *flag = value.as_boolean();
            }
        }
        return s;
    } catch (const input_error&) {
        throw;
    } catch (const std::exception& e) {  // toml11's syntax and type errors carry the line and the key
        throw input_error("malformed scene " + source + ":\n" + e.what());
    }
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
