#include "smithlab/compensation/compensation_formats.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "smithlab/compensation/compensation.hpp"
#include "smithlab/compensation/scattering_orders.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::compensation {

namespace {

constexpr std::string_view height_correlated = "height-correlated", separable = "separable";

// The rules every lookup follows (albedo_grid.hpp, AlbedoTable::lookup), as each file's comment and the axes state
// them.
constexpr std::string_view rule_warp = "sqrt((1 + c) mu / (mu + c)), c = the warp's scale at the asked alpha";
constexpr std::string_view rule_lookup =
    "bilinear in (sqrt(alpha), x): j = min(int(x (n_x - 1)), n_x - 2), linear in x between x_j and x_(j+1); the alpha "
    "cell found in sqrt(alpha) among the nodes' sqrt(alpha), linear in sqrt(alpha)";
constexpr std::string_view rule_below = "the first row, in the x of the asked alpha";
constexpr std::string_view rule_above = "the last row, in the x of the asked alpha (no error is measured there)";
constexpr std::string_view rule_mu = "clamped to [0, 1] (a renderer's cosines overshoot by a rounding); NaN reads as 0";
constexpr std::string_view rule_alpha = "finite and > 0, not checked";
// lookup_power_law's rule (albedo_grid.hpp), for the warp's scale c and for m = 1 - E_avg.
constexpr std::string_view rule_power_law =
    "ln of it linear in ln(alpha) between the nodes; below the first alpha the first interval's power of alpha "
    "continued, above the last alpha the last value";

// compensation_header_name's rule without its "smithlab_" prefix ("" when the text has no letter or digit).
std::string identifier_part(std::string_view text) {
    const std::string name = compensation_header_name(text);
    constexpr std::size_t prefix = std::string_view("smithlab_").size();
    return name.size() > prefix ? name.substr(prefix) : std::string();
}

bool fits_float(double v) { return std::isfinite(v) && std::abs(v) <= std::numeric_limits<float>::max(); }

// The float nearest v as a literal of 9 significant digits (every float reads back exactly), with a '.' or an
// exponent so that it is a floating literal, then `suffix` ("f" in C and HLSL).
std::string float_literal(double v, std::string_view suffix) {
    std::string s = format_printf("%.9g", static_cast<double>(static_cast<float>(v)));
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s + std::string(suffix);
}

std::string short_g(double v) { return format_printf("%.3g", v); }

bool logs(const AlbedoTable& t) { return t.stored == Stored::log; }

// The axis x(mu) in words: the warp, with the cluster's share where the grid has one (albedo_grid.hpp).
std::string rule_x(const AlbedoGrid& g) {
    std::string s = "x = ";
    const NodeCluster& k = g.cluster;
    if (k.weight == 0.0) {
        s += rule_warp;
    } else {
        s += format_shortest(1.0 - k.weight) + " " + std::string(rule_warp.substr(0, rule_warp.find(','))) + " + " +
            format_shortest(k.weight) + " (asinh((mu - " + format_shortest(k.mu) + ") / " + format_shortest(k.width) +
            ") + asinh(" + format_shortest(k.mu) + " / " + format_shortest(k.width) + ")) / (asinh(" +
            format_shortest(1.0 - k.mu) + " / " + format_shortest(k.width) + ") + asinh(" + format_shortest(k.mu) +
            " / " + format_shortest(k.width) +
            ")), c = the warp's scale at the asked alpha (nodes clustered about mu = " + format_shortest(k.mu) + ")";
    }
    return s + ", nodes x_j = j / (n_x - 1)";
}

// The cosine of node x at scale c in words.
std::string rule_mu_of_x(const AlbedoGrid& g) {
    return g.cluster.weight == 0.0 ? "c x^2 / (1 + c - x^2)" : "the inverse of x(mu), which increases";
}

// The table's values in words.
std::string rule_value(const AlbedoTable& t) { return logs(t) ? "ln E" : "E"; }

// The suffix of the table's array: "_E_table", or "_log_E_table" for ln E.
std::string table_name(const AlbedoTable& t) { return logs(t) ? "_log_E_table" : "_E_table"; }

// The PNG's scale K of -ln E (a table of ln E): the largest -ln E, so that the pixels span [0, 65535]; 1 when E is 1
// everywhere, and for a table of E.
double png_log_scale(const AlbedoTable& t) {
    double K = 0.0;
    if (logs(t))
        for (const double v : t.values) K = std::max(K, -v);
    return K > 0.0 ? K : 1.0;
}

// A pixel's value in words.
std::string png_rule(const AlbedoTable& t) {
    return logs(t) ? "E = exp(-K pixel / 65535), pixel = round(-ln(E) / K * 65535), K = log_scale: ln E within 0.5 K / "
                     "65535"
                   : "E = pixel / 65535, pixel = round(E * 65535): within 0.5 / 65535 of E";
}

// Where value k of the table `name` is, for the messages.
std::string table_item(const AlbedoTable& t, std::size_t k, std::string_view name = "E") {
    const std::size_t nx = static_cast<std::size_t>(t.grid.n_x);
    return std::string(name) + " at alpha " + format_shortest(t.grid.alphas[k / nx]) + ", x_" + std::to_string(k % nx) +
        " = " + format_shortest(t.grid.x(static_cast<int>(k % nx)));
}

// "smithlab_" + the family as an identifier + "_hc" or "_sep" (compensation_identifier's prefix); `what` names the
// export in the messages.
std::string family_identifier(const std::string& family, const std::string& g2, std::string_view what) {
    const std::string name = identifier_part(family);
    if (name.empty())
        throw input_error(std::string(what) + ": the NDF family '" + family + "' has no letter or digit to name it");
    if (g2 != height_correlated && g2 != separable)
        throw input_error(std::string(what) + ": G2 '" + g2 + "', known: height-correlated, separable");
    return "smithlab_" + name + (g2 == height_correlated ? "_hc" : "_sep");
}

// A grid the lookups in float follow (compensation_formats.hpp), input_error after `what`: valid, the warp's scales
// normal floats (their logarithms in float are the doubles'), the alphas' square roots distinct as floats.
void check_grid(const AlbedoGrid& g, std::string_view what) {
    g.check();
    const std::vector<double>& a = g.alphas;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (!(g.scales[i] >= static_cast<double>(std::numeric_limits<float>::min()) && fits_float(g.scales[i])))
            throw input_error(std::string(what) + ": the warp's scale at alpha " + format_shortest(a[i]) + " is " +
                              format_g17(g.scales[i]) + ", not a normal float");
    for (std::size_t i = 1; i < a.size(); ++i)
        if (!(static_cast<float>(std::sqrt(a[i])) > static_cast<float>(std::sqrt(a[i - 1]))))
            throw input_error(std::string(what) + ": alphas " + format_shortest(a[i - 1]) + " and " +
                              format_shortest(a[i]) + " have the same sqrt(alpha) as floats");
}

// One value a node, each a finite float; input_error after `what`, naming the table `name`.
void check_values(const AlbedoTable& t, std::string_view what, std::string_view name) {
    const std::size_t na = t.grid.alphas.size(), nx = static_cast<std::size_t>(t.grid.n_x);
    if (t.values.size() != na * nx)
        throw input_error(std::string(what) + ": " + std::string(name) + " has " + std::to_string(t.values.size()) +
                          " values for " + std::to_string(na) + " alphas x " + std::to_string(nx) + " cosines");
    for (std::size_t k = 0; k < t.values.size(); ++k)
        if (!fits_float(t.values[k]))
            throw input_error(std::string(what) + ": " + table_item(t, k, name) +
                              " is not a finite float: " + format_g17(t.values[k]));
}

// compensation_formats.hpp's checks, input_error naming the item.
void check(const CompensationExport& e) {
    (void)compensation_identifier(e);
    if (!e.E) throw input_error("compensation export: no table (E is null)");
    const AlbedoTable& t = *e.E;
    check_grid(t.grid, "compensation export");
    check_values(t, "compensation export", "E");
    const std::vector<double>& a = t.grid.alphas;
    const std::size_t na = a.size();
    if (!e.missing.empty() && e.missing.size() != na)
        throw input_error("compensation export: " + std::to_string(e.missing.size()) + " values of 1 - E_avg for " +
                          std::to_string(na) + " alphas");
    for (std::size_t i = 0; i < e.missing.size(); ++i) {
        const double m = e.missing[i];
        if (!(m >= static_cast<double>(std::numeric_limits<float>::min()) && m <= 1.0))
            throw input_error("compensation export: 1 - E_avg at alpha " + format_shortest(a[i]) + " is " +
                              format_g17(m) + ", not finite, > 0 and <= 1 as a normal float");
    }
    require(std::isfinite(e.max_interp_error) && e.max_interp_error >= 0.0,
            "compensation export: the measured max interpolation error", "finite and >= 0", e.max_interp_error);
    require(std::isfinite(e.below_grid_error) && e.below_grid_error >= 0.0,
            "compensation export: the measured below-grid error", "finite and >= 0", e.below_grid_error);
    require(std::isfinite(e.grazing_error) && e.grazing_error >= 0.0, "compensation export: the measured grazing error",
            "finite and >= 0", e.grazing_error);
}

// Text for a block comment in C, GLSL or HLSL: printable ASCII (GLSL's character set), anything else '?', and a space
// in each "*" "/" and "/" "*" (the end of the comment, and a nested start, which C compilers warn of).
std::string comment_text(std::string_view text) {
    std::string s;
    for (const char c : text) {
        if (!s.empty() && ((s.back() == '*' && c == '/') || (s.back() == '/' && c == '*'))) s += ' ';
        s += c >= ' ' && c <= '~' ? c : '?';
    }
    return s;
}

// A /* */ comment of paragraphs, each broken at spaces into lines of at most 116 characters, continued lines indented
// two more than the paragraph's first.
std::string comment_block(const std::vector<std::string>& paragraphs) {
    constexpr std::size_t width = 116;
    std::string s;
    for (const std::string& p : paragraphs) {
        const std::size_t indent = std::min(p.find_first_not_of(' '), p.size());
        std::string line = " * ";
        line.append(indent, ' ');
        std::size_t words = 0;
        for (std::size_t b = indent; b < p.size();) {
            const std::size_t e = std::min(p.find(' ', b), p.size());
            const std::string_view word = std::string_view(p).substr(b, e - b);
            if (words > 0 && line.size() + 1 + word.size() > width) {
                s += line + "\n";
                line.assign(" * ").append(indent + 2, ' ');
                words = 0;
            }
            line.append(words++ ? " " : "").append(word);
            b = e + 1;
        }
        s += line + "\n";
    }
    s.replace(0, 3, "/* ");
    s.insert(s.size() - 1, " */");
    return s;
}

// The G2 in words, with its sources.
std::string g2_text(const std::string& g2) {
    return g2 == height_correlated ? "height-correlated Smith G2 (Walter et al. 2007, eq. 20; Heitz 2014, eq. 99)"
                                   : "separable Smith G2 = G1(wi) G1(wo) (Heitz 2014, eq. 98)";
}

// The grid in words, `values` saying which arrays hold what at (alphas[i], x_j).
std::string grid_paragraph(const AlbedoGrid& g, const std::string& id, const std::string& values) {
    const std::vector<double>& a = g.alphas;
    std::string alphas;
    for (std::size_t i = 0; i < a.size(); ++i) alphas += (i ? ", " : "") + format_shortest(a[i]);
    return "Grid: n_alpha x n_x = " + std::to_string(a.size()) + " x " + std::to_string(g.n_x) + ", alpha in [" +
        format_shortest(a.front()) + ", " + format_shortest(a.back()) + "]: alphas " + alphas + "; " + rule_x(g) +
        "; " + values + ", at mu = " + rule_mu_of_x(g) + " at x_j and c_i = exp(" + id +
        "_log_scale[i]), the warp's scale at alphas[i] (6 cos(theta) where the NDF's Lambda = 0.3: its rows' dip)";
}

// The rules of every lookup on the grid in words, after the lookups' names; `then` follows the bilinear rule (", of
// ln E, then exp").
std::vector<std::string> lookup_paragraphs(const std::string& lookups, std::string_view then = "") {
    return {"The warp's scale c at any alpha: " + std::string(rule_power_law) + ".",
            lookups + ": " + std::string(rule_lookup) + std::string(then) + ".",
            "Outside the grid, nothing is clamped silently:",
            "  below the first alpha: " + std::string(rule_below) + ";",
            "  above the last alpha: " + std::string(rule_above) + ";",
            "  mu " + std::string(rule_mu) + ";",
            "  alpha must be " + std::string(rule_alpha) + "."};
}

constexpr std::string_view float_values =
    "The values are the floats nearest the computed doubles (9 significant digits).";

// The top comment of the three text formats. It names this header fit/compensation_formats.hpp and the orders'
// fit/scattering_orders.hpp, as the files have always said: their text stays byte for byte what earlier versions wrote.
std::string top_comment(const CompensationExport& e, const std::string& id, std::string_view language) {
    std::vector<std::string> p = {
        id + ": energy compensation of specular multiple scattering, " + std::string(language) +
            ". Generated by smithlab (fit/compensation_formats.hpp).",
        "NDF family: " + comment_text(e.family) + ". G2: " + g2_text(e.g2) + ". Quantity: " + comment_text(e.quantity) +
            (e.quantity == "E" ? " (the directional albedo of single scattering off mirror facets, F = 1)" : "") +
            ", tabulated as E(alpha, mu), mu = cos(theta); E_avg(alpha) = 2 int_0^1 E(alpha, mu) mu dmu.",
        "Kulla and Conty 2017 (\"Revisiting Physically Based Shading at Imageworks\"): f_ms(wi, wo) = (1 - E(mu_i)) "
        "(1 - E(mu_o)) / (pi (1 - E_avg))" +
            (e.missing.empty() ? std::string() : ", (1 - E_avg) = " + id + "_missing(alpha)") +
            ", times F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) for coloured facets; Turquin 2019 (\"Practical multiple "
            "scattering compensation for microfacet models\"): f = f_ss (1 + F0 (1 - E(mu_v)) / E(mu_v)), mu_v the "
            "view's cosine.",
        grid_paragraph(e.E->grid, id,
                       id + table_name(*e.E) + "[i * n_x + j] = " + rule_value(*e.E) + "(alphas[i], x_j)") +
            (logs(*e.E) ? "; the table holds ln E so that its lookup's error is relative, as a division by E needs."
                        : ".")};
    const std::vector<std::string> lookups =
        lookup_paragraphs(id + "_E(alpha, mu)", logs(*e.E) ? ", of ln E, then exp" : "");
    p.insert(p.end(), lookups.begin(), lookups.end());
    p.push_back(e.missing.empty() ? "No E_avg is given with this table."
                                  : id + "_missing(alpha) = 1 - E_avg(alpha): " + std::string(rule_power_law) + "; " +
                        id + "_log_missing_table[i] = ln(1 - E_avg(alphas[i])). " + id + "_E_avg(alpha) = 1 - " + id +
                        "_missing(alpha). Kulla and Conty's lobe should divide by " + id +
                        "_missing(alpha), not by 1 - " + id +
                        "_E_avg(alpha): 1 - E_avg falls like alpha^2 at small alpha, and 1 - E_avg taken from a "
                        "float E_avg loses its relative precision (a float E_avg = 1 - 1e-8 is 1).");
    p.push_back("Measured: the lookup is within " + short_g(e.max_interp_error) +
                " of the exact values inside the grid at mu >= " + format_shortest(grazing_mu) + ", within " +
                short_g(e.grazing_error) + " at grazing mu < " + format_shortest(grazing_mu) +
                " (theta > 89.885 degrees), within " + short_g(e.below_grid_error) +
                " below the first alpha (mu >= " + format_shortest(grazing_mu) + ").");
    p.push_back(std::string(float_values));
    return comment_block(p);
}

// What differs between C, GLSL and HLSL in the arrays and lookups; the code is the same.
struct Dialect {
    std::string_view array;     // before a constant array's name
    bool constructor;           // GLSL's initializer float[N](...), else {...}
    std::string_view function;  // before a function
    std::string_view suffix;    // of float literals
    std::string_view sqrt, log, exp;
    bool c_cast;                // (int)(x), else int(x)
    std::string_view language;  // for the top comment
    std::string cast(std::string_view type, std::string_view x) const {
        std::string s(c_cast ? "(" : "");
        s.append(type).append(c_cast ? ")(" : "(").append(x);
        return s + ")";
    }
};
// Each dialect's name in the top comment.
constexpr std::string_view c_language = "self-contained C99 (or C++)",
                           glsl_language = "GLSL 3.30 (no #version line: it goes after the includer's)";
constexpr Dialect c_dialect{
    "static const float ", false, "static inline ", "f", "sqrtf", "logf", "expf", true, c_language};
constexpr Dialect glsl_dialect{"const float ", true, "", "", "sqrt", "log", "exp", false, glsl_language};
constexpr Dialect hlsl_dialect{"static const float ", false, "", "f", "sqrt", "log", "exp", true, "HLSL"};

// A constant array, `row` values a row, each row after its label when labels are given.
std::string array(const Dialect& d, const std::string& name, const std::vector<double>& v, std::size_t row,
                  const std::vector<std::string>& labels = {}) {
    const std::string n = std::to_string(v.size());
    std::string s = std::string(d.array) + name + "[" + n + "] = " + (d.constructor ? "float[" + n + "](" : "{");
    for (std::size_t k = 0; k < v.size(); ++k) {
        if (k % row == 0 && !labels.empty()) s += "\n    /* " + labels[k / row] + " */";
        s += k % row % 8 == 0 ? "\n    " : " ";
        s += float_literal(v[k], d.suffix) + (k + 1 < v.size() ? "," : "");
    }
    return s + (d.constructor ? "\n);\n" : "\n};\n");
}

// The grid's arrays: sqrt(alpha) and ln c at each alpha.
std::string grid_arrays(const Dialect& d, const std::string& id, const AlbedoGrid& g) {
    std::vector<double> sqrt_alpha, log_scale;
    for (const double a : g.alphas) sqrt_alpha.push_back(std::sqrt(a));
    for (const double c : g.scales) log_scale.push_back(std::log(c));
    return array(d, id + "_sqrt_alpha", sqrt_alpha, 8) + array(d, id + "_log_scale", log_scale, 8);
}

// A table's values as the array `name`, a row per alpha after its label.
std::string table_array(const Dialect& d, const std::string& name, const AlbedoTable& t) {
    std::vector<std::string> labels;
    for (const double a : t.grid.alphas) labels.push_back("alpha = " + format_shortest(a));
    return array(d, name, t.values, static_cast<std::size_t>(t.grid.n_x), labels);
}

// The functions every lookup on the grid calls: the alpha cell, the weights in it in sqrt(alpha) and in ln(alpha),
// and asinh where the grid has a node cluster.
std::string grid_functions(const Dialect& d, const std::string& id, const AlbedoGrid& g) {
    const std::string f(d.function), one = float_literal(1.0, d.suffix), zero = float_literal(0.0, d.suffix);
    const std::string last = std::to_string(g.alphas.size() - 1);
    std::string s =
        "\n/* The lower node i of sqrt(alpha)'s cell: 0 below the first node, n_alpha - 2 above the last. */\n" + f +
        "int " + id + "_alpha_cell(float s) {\n    int i = 0;\n    for (int k = 1; k < " + last +
        "; ++k) {\n        if (" + id +
        "_sqrt_alpha[k] <= s) i = k;\n    }\n    return i;\n}\n\n"
        "/* The weight of node i + 1 in cell i: 0 below the first node, 1 above the last. */\n" +
        f + "float " + id + "_alpha_weight(float s, int i) {\n    if (!(s > " + id + "_sqrt_alpha[0])) return " + zero +
        ";\n    if (!(s < " + id + "_sqrt_alpha[" + last + "])) return " + one + ";\n    return (s - " + id +
        "_sqrt_alpha[i]) / (" + id + "_sqrt_alpha[i + 1] - " + id +
        "_sqrt_alpha[i]);\n}\n\n"
        "/* The weight of node i + 1 in ln(alpha) (the same in ln(sqrt(alpha))): below the first node the first cell's "
        "line\n   continued, 1 above the last. */\n" +
        f + "float " + id + "_log_weight(float s, int i) {\n    return s < " + id + "_sqrt_alpha[" + last + "] ? " +
        std::string(d.log) + "(s / " + id + "_sqrt_alpha[i]) / " + std::string(d.log) + "(" + id +
        "_sqrt_alpha[i + 1] / " + id + "_sqrt_alpha[i]) : " + one + ";\n}\n\n";
    if (g.cluster.weight != 0.0)
        s += "/* asinh(z), odd. */\n" + f + "float " + id + "_asinh(float z) {\n    float a = z < " + zero +
            " ? -z : z;\n    float y = " + std::string(d.log) + "(a + " + std::string(d.sqrt) + "(a * a + " + one +
            "));\n    return z < " + zero + " ? -y : y;\n}\n\n";
    return s;
}

// x(mu) at the scale c, m the clamped cosine, as an expression.
std::string x_expression(const Dialect& d, const std::string& id, const AlbedoGrid& g) {
    const std::string one = float_literal(1.0, d.suffix);
    const std::string warp = std::string(d.sqrt) + "((" + one + " + c) * m / (m + c))";
    const NodeCluster& k = g.cluster;
    if (k.weight == 0.0) return warp;
    // x = (1 - b) warp + b (asinh((m - mu_k) / w) + lo) / (lo + hi), asinh odd: sign(z) ln(|z| + sqrt(z^2 + 1)).
    const double lo = std::asinh(k.mu / k.width), hi = std::asinh((1.0 - k.mu) / k.width);
    return float_literal(1.0 - k.weight, d.suffix) + " * " + warp + " + " +
        float_literal(k.weight / (lo + hi), d.suffix) + " * (" + id + "_asinh((m - " + float_literal(k.mu, d.suffix) +
        ") / " + float_literal(k.width, d.suffix) + ") + " + float_literal(lo, d.suffix) + ")";
}

// float FUNCTION(float alpha, float mu): AlbedoTable::lookup of t, whose values are the array T, in float; `what`
// names the value in the comment.
std::string table_lookup(const Dialect& d, const std::string& id, const std::string& function, std::string_view what,
                         const std::string& T, const AlbedoTable& t) {
    const std::string one = float_literal(1.0, d.suffix), zero = float_literal(0.0, d.suffix);
    const std::string nx = std::to_string(t.grid.n_x), C = id + "_log_scale", ex(d.exp);
    return "/* " + std::string(what) + "(alpha, mu), alpha > 0: bilinear in (sqrt(alpha), x)" +
        (logs(t) ? " of ln E, then exp" : "") +
        ", x = " + (t.grid.cluster.weight == 0.0 ? "sqrt((1 + c) mu / (mu + c))" : "the warp and the cluster's share") +
        ", c the\n   warp's scale at alpha, mu clamped to [0, 1]. */\n" + std::string(d.function) + "float " +
        function + "(float alpha, float mu) {\n    float m = mu > " + zero + " ? (mu < " + one + " ? mu : " + one +
        ") : " + zero + ";\n    float s = " + std::string(d.sqrt) + "(alpha);\n    int i = " + id +
        "_alpha_cell(s);\n    float ta = " + id + "_alpha_weight(s, i);\n    float u = " + id +
        "_log_weight(s, i);\n    float c = " + ex + "(" + C + "[i] + u * (" + C + "[i + 1] - " + C +
        "[i]));\n    float x = (" + x_expression(d, id, t.grid) + ") * " + float_literal(t.grid.n_x - 1, d.suffix) +
        ";\n    int j = " + d.cast("int", "x") + ";\n    if (j > " + std::to_string(t.grid.n_x - 2) +
        ") j = " + std::to_string(t.grid.n_x - 2) + ";\n    float tx = x - " + d.cast("float", "j") +
        ";\n    int a = i * " + nx + " + j;\n    int b = a + " + nx + ";\n    float lo = " + T + "[a] + tx * (" + T +
        "[a + 1] - " + T + "[a]);\n    float hi = " + T + "[b] + tx * (" + T + "[b + 1] - " + T + "[b]);\n    return " +
        (logs(t) ? ex + "(lo + ta * (hi - lo))" : std::string("lo + ta * (hi - lo)")) + ";\n}\n";
}

// float NAME_missing(float alpha) and NAME_E_avg(alpha): 1 - E_avg by lookup_power_law of the array
// NAME_log_missing_table, in float.
std::string missing_lookup(const Dialect& d, const std::string& id) {
    const std::string f = std::string(d.function), one = float_literal(1.0, d.suffix);
    const std::string L = id + "_log_missing_table", ex(d.exp);
    return "\n/* 1 - E_avg(alpha), alpha > 0: ln(1 - E_avg) linear in ln(alpha) between the nodes; below the first "
           "node the\n   first interval's power of alpha continued, above the last node the last value. Divide "
           "Kulla and Conty's\n   lobe by this, not by 1 - " +
        id + "_E_avg(alpha) (no cancellation). */\n" + f + "float " + id +
        "_missing(float alpha) {\n    float s = " + std::string(d.sqrt) + "(alpha);\n    int i = " + id +
        "_alpha_cell(s);\n    float u = " + id + "_log_weight(s, i);\n    return " + ex + "(" + L + "[i] + u * (" + L +
        "[i + 1] - " + L +
        "[i]));\n}\n\n"
        "/* E_avg(alpha) = 1 - " +
        id + "_missing(alpha), alpha > 0. */\n" + f + "float " + id + "_E_avg(float alpha) { return " + one + " - " +
        id + "_missing(alpha); }\n";
}

// The arrays and lookups, after the top comment.
std::string arrays_and_lookups(const CompensationExport& e, const std::string& id, const Dialect& d) {
    const AlbedoTable& t = *e.E;
    std::string s = "\n" + grid_arrays(d, id, t.grid) + table_array(d, id + table_name(t), t);
    if (!e.missing.empty()) {
        std::vector<double> log_missing;
        for (const double m : e.missing) log_missing.push_back(std::log(m));
        s += array(d, id + "_log_missing_table", log_missing, 8);
    }
    s += grid_functions(d, id, t.grid) + table_lookup(d, id, id + "_E", "E", id + table_name(t), t);
    return e.missing.empty() ? s : s + missing_lookup(d, id);
}

// An order table with its name in the text ("q_2") and in the identifiers ("q2").
struct OrderTable {
    std::string_view label, name;
    const AlbedoTable* table;
};

// q_2, q_3, p, and q_1 where it has values (the separable G2's).
std::vector<OrderTable> order_tables(const OrderTables& o) {
    std::vector<OrderTable> v{{"q_2", "q2", &o.q2}, {"q_3", "q3", &o.q3}, {"p", "p", &o.p}};
    if (!o.q1.values.empty()) v.push_back({"q_1", "q1", &o.q1});
    return v;
}

bool same_grid(const AlbedoGrid& a, const AlbedoGrid& b) {
    return a.alphas == b.alphas && a.scales == b.scales && a.n_x == b.n_x && a.cluster.mu == b.cluster.mu &&
        a.cluster.width == b.cluster.width && a.cluster.weight == b.cluster.weight;
}

// compensation_formats.hpp's checks of the orders, input_error naming the item.
void check(const OrderExport& e) {
    constexpr std::string_view what = "order export";
    (void)order_identifier(e);
    if (!e.orders) throw input_error("order export: no tables (orders is null)");
    const std::vector<OrderTable> tables = order_tables(*e.orders);
    // q_1 is the separable G2's alone: the walk's single scattering is the height-correlated G2's.
    if (e.g2 == separable && tables.size() < 4)
        throw input_error(
            "order export: no q_1 table with the separable G2 (its single scattering misses E_hc - E_sep)");
    if (e.g2 == height_correlated && tables.size() == 4)
        throw input_error("order export: a q_1 table with the height-correlated G2 (its q_1 is 0)");
    const AlbedoGrid& g = e.orders->q2.grid;
    check_grid(g, what);
    for (const OrderTable& t : tables) {
        const std::string label(t.label);
        if (!same_grid(t.table->grid, g))
            throw input_error("order export: " + label + "'s grid is not q_2's (alphas, warp scales, n_x, cluster)");
        if (t.table->stored != Stored::value)
            throw input_error("order export: " + label + " is stored as ln; the order tables hold values");
        check_values(*t.table, what, t.label);
        // p > 0 as a float: the tail's series divides by it at F_avg = 1.
        const bool p = t.label == "p";
        const double least = p ? static_cast<double>(std::numeric_limits<float>::min()) : 0.0;
        for (std::size_t k = 0; k < t.table->values.size(); ++k)
            if (!(t.table->values[k] >= least && t.table->values[k] <= 1.0))
                throw input_error("order export: " + table_item(*t.table, k, t.label) + " is " +
                                  format_g17(t.table->values[k]) + ", outside " +
                                  (p ? "(0, 1] (as a normal float)" : "[0, 1]"));
    }
    require(std::isfinite(e.max_stderr) && e.max_stderr >= 0.0, "order export: the worst standard error",
            "finite and >= 0", e.max_stderr);
}

// The array of an order table.
std::string order_array(const std::string& id, const OrderTable& t) {
    return id + "_" + std::string(t.name) + "_table";
}

// The items in words: "a, b and c".
std::string listed(const std::vector<std::string>& items) {
    std::string s;
    for (std::size_t i = 0; i < items.size(); ++i)
        s += (i == 0 ? "" : i + 1 < items.size() ? ", " : " and ") + items[i];
    return s;
}

// A_ms by the orders: multiple_scattering_albedo's formula (compensation/scattering_orders.hpp).
constexpr std::string_view ms_formula =
    "A_ms(mu) = (1 - E(mu)) (q_1 F_avg + (1 - q_1) (q_2 F_avg^2 + q_3 F_avg^3 + (1 - q_2 - q_3) F_avg^4 p / (1 - F_avg "
    "(1 - p))))";

// q_1 in words: the separable G2's table, or 0.
std::string q1_rule(bool table) {
    return table ? "q_1 = (E_hc - E_sep) / (1 - E_sep): single scattering with the separable G2 misses E_hc - E_sep "
                   "of light that leaves the walk's microsurface (the height-correlated G2's) after one hit, with one "
                   "factor F_avg"
                 : "q_1 = 0 (no q_1 table): the walk's single scattering is this G2's";
}

// The top comment of the orders' three text formats.
std::string top_comment(const OrderExport& e, const std::string& id, std::string_view language) {
    const std::vector<OrderTable> tables = order_tables(*e.orders);
    std::vector<std::string> arrays, labels, lookups;
    for (const OrderTable& t : tables) {
        arrays.push_back(order_array(id, t));
        labels.push_back(std::string(t.label));
        lookups.push_back(id + "_" + std::string(t.name));
    }
    const std::string E = family_identifier(e.family, e.g2, "order export") + "_E";
    std::vector<std::string> p = {
        id + ": conductor compensation from the random walk's scattering orders, " + std::string(language) +
            ". Generated by smithlab (fit/compensation_formats.hpp, fit/scattering_orders.hpp).",
        "NDF family: " + comment_text(e.family) + ". G2: " + g2_text(e.g2) + ".",
        "Kulla-Conty-like conductor compensation: the directional albedo of conductor facets is E_F(mu) + A_ms(mu), "
        "single scattering E_F(mu) (with the facets' Fresnel F) exact, plus " +
            std::string(ms_formula) + " = " + id +
            "_ms(alpha, mu, E, F_avg), smithlab's multiple_scattering_albedo (fit/scattering_orders.hpp); E(mu) the "
            "directional albedo of mirror facets (F = 1) with this G2 (" +
            E +
            "(alpha, mu)), F_avg = 2 int_0^1 F(mu) mu dmu, per colour channel. Of the light single scattering "
            "misses, 1 - E(mu), a share q_k leaves after k hits of mirror facets, each hit with one factor F_avg: q_2 "
            "and q_3 the walk's own (Heitz et al. 2016's random walk on the Smith microsurface), the orders k >= 4 a "
            "geometric series q_k = (1 - q_2 - q_3) p (1 - p)^(k - 4), 1 / p the mean number of hits past the third. "
            "At F_avg = 1, A_ms = 1 - E(mu): a white furnace. Kulla and Conty 2017's series gives every hit the same "
            "escape chance E_avg: too many hits, an A_ms too low.",
        q1_rule(tables.size() == 4) + ".",
        "Monte Carlo: the tables are the walk's estimates at the nodes; the worst standard error of q_2 and q_3 is " +
            short_g(e.max_stderr) + ". Their interpolation error is not measured.",
        grid_paragraph(e.orders->q2.grid, id,
                       listed(arrays) + "[i * n_x + j] = " + listed(labels) + " at (alphas[i], x_j)") +
            "."};
    const std::vector<std::string> rules = lookup_paragraphs(listed(lookups) + "(alpha, mu)");
    p.insert(p.end(), rules.begin(), rules.end());
    p.push_back(std::string(float_values));
    return comment_block(p);
}

// float NAME_ms(float alpha, float mu, float E, float F_avg): multiple_scattering_albedo in float.
std::string ms_function(const Dialect& d, const std::string& id, bool q1) {
    const std::string one = float_literal(1.0, d.suffix), zero = float_literal(0.0, d.suffix);
    std::string s =
        "/* A_ms(alpha, mu) = (1 - E) (q_1 F + (1 - q_1) (q_2 F^2 + q_3 F^3 + (1 - q_2 - q_3) F^4 p / (1 - F (1 - p))))"
        ", F =\n   F_avg: multiple_scattering_albedo (fit/scattering_orders.hpp) in float. E = E(alpha, mu) of mirror "
        "facets with\n   this G2 and F_avg in [0, 1], not checked; E above 1 reads as 1. 1 - F (1 - p) is written "
        "(1 - F) + F p:\n   no cancellation as F -> 1 and p -> 0. */\n" +
        std::string(d.function) + "float " + id + "_ms(float alpha, float mu, float E, float F_avg) {\n";
    for (const std::string q : {"q2", "q3", "p", "q1"})
        if (q != "q1" || q1) s += "    float " + q + " = " + id + "_" + q + "(alpha, mu);\n";
    s += "    float F2 = F_avg * F_avg;\n    float tail = (" + one + " - q2 - q3) * F2 * F2 * p / ((" + one +
        " - F_avg) + F_avg * p);\n    float multiple = F2 * q2 + F2 * F_avg * q3 + tail;\n    float missed = E < " +
        one + " ? " + one + " - E : " + zero + ";\n    return missed * " +
        (q1 ? "(q1 * F_avg + (" + one + " - q1) * multiple)" : std::string("multiple")) + ";\n}\n";
    return s;
}

// The orders' arrays and lookups, after the top comment.
std::string arrays_and_lookups(const OrderExport& e, const std::string& id, const Dialect& d) {
    const std::vector<OrderTable> tables = order_tables(*e.orders);
    const AlbedoGrid& g = e.orders->q2.grid;
    std::string s = "\n" + grid_arrays(d, id, g);
    for (const OrderTable& t : tables) s += table_array(d, order_array(id, t), *t.table);
    s += grid_functions(d, id, g);
    for (const OrderTable& t : tables)
        s += table_lookup(d, id, id + "_" + std::string(t.name), t.label, order_array(id, t), *t.table) + "\n";
    return s + ms_function(d, id, tables.size() == 4);
}

// A file of an export in dialect d: its top comment, then its arrays and lookups.
template <class Export>
std::string text_in(const Export& e, const std::string& id, const Dialect& d) {
    return top_comment(e, id, d.language) + arrays_and_lookups(e, id, d);
}

// A C header: the arrays and lookups inside the include guard `guard` (upper-cased).
template <class Export>
std::string c_header(const Export& e, const std::string& id, std::string guard) {
    for (char& c : guard) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    return top_comment(e, id, c_dialect.language) + "#ifndef " + guard + "\n#define " + guard +
        "\n\n#include <math.h>\n" + arrays_and_lookups(e, id, c_dialect) + "\n#endif /* " + guard + " */\n";
}

// Each export's identifier and its C header's include guard (compensation_formats.hpp).
std::string identifier_of(const CompensationExport& e) { return compensation_identifier(e); }
std::string identifier_of(const OrderExport& e) { return order_identifier(e); }
std::string guard_of(const CompensationExport&, const std::string& id) { return id + "_compensation_h"; }
std::string guard_of(const OrderExport&, const std::string& id) { return id + "_h"; }

// An export in `language`, after its checks: a C header, or the GLSL or HLSL text.
template <class Export>
void write_source_of(std::ostream& out, const Export& e, Language language) {
    check(e);
    const std::string id = identifier_of(e);
    if (language == Language::c) out << c_header(e, id, guard_of(e, id));
    else out << text_in(e, id, language == Language::glsl ? glsl_dialect : hlsl_dialect);
}

// A JSON string: quotes, backslashes and control characters escaped (RFC 8259, section 7).
std::string json_string(std::string_view text) {
    std::string s = "\"";
    for (const char c : text) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            s += '\\';
            s += c;
        } else if (u < 0x20) {
            s += format_printf("\\u%04x", static_cast<unsigned>(u));
        } else {
            s += c;
        }
    }
    return s + '"';
}

// Numbers as the shortest text that reads back as each double.
std::string json_numbers(const std::vector<double>& v) {
    std::string s = "[";
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + format_shortest(v[i]);
    return s + "]";
}

// The grid's entries of the axes, each line ending in ",\n": the alphas, the warp's scales, the axis x and the lookup
// rules, `lookup` the bilinear one.
std::string json_grid(const AlbedoGrid& g, const std::string& lookup) {
    std::string s = "  \"alphas\": " + json_numbers(g.alphas) + ",\n  \"warp_scales\": " + json_numbers(g.scales) +
        ",\n  \"warp_scale_lookup\": " + json_string(rule_power_law) + ",\n  \"n_x\": " + std::to_string(g.n_x) +
        ",\n  \"x\": " + json_string(rule_x(g));
    if (g.cluster.weight != 0.0)
        s += ",\n  \"cluster\": {\"mu\": " + format_shortest(g.cluster.mu) +
            ", \"width\": " + format_shortest(g.cluster.width) + ", \"weight\": " + format_shortest(g.cluster.weight) +
            "}";
    return s + ",\n  \"mu_of_x\": " + json_string(rule_mu_of_x(g)) + ",\n  \"lookup\": " + json_string(lookup) +
        ",\n  \"below_first_alpha\": " + json_string(rule_below) +
        ",\n  \"above_last_alpha\": " + json_string(rule_above) + ",\n  \"mu\": " + json_string(rule_mu) +
        ",\n  \"alpha\": " + json_string(rule_alpha) + ",\n";
}

}  // namespace

std::string compensation_identifier(const CompensationExport& e) {
    const std::string id = family_identifier(e.family, e.g2, "compensation export");
    if (e.quantity == "E") return id;
    const std::string quantity = identifier_part(e.quantity);
    if (quantity.empty())
        throw input_error("compensation export: the quantity '" + e.quantity + "' has no letter or digit to name it");
    return id + "_" + quantity;
}

void write_source(std::ostream& out, const CompensationExport& e, Language language) {
    write_source_of(out, e, language);
}

void write_png16(std::ostream& out, const CompensationExport& e) {
    check(e);
    const AlbedoTable& t = *e.E;
    const double K = png_log_scale(t);
    std::vector<png_uint_16> pixels(t.values.size());
    for (std::size_t k = 0; k < t.values.size(); ++k) {
        // An albedo computed to its quadrature's tolerance may pass 1 (or 0) by a rounding (1 + 2e-16 at a node where
        // E -> 1): within 1e-9, far below a pixel's 1.5e-5, it is the end value; beyond, the table is refused.
        const double p = logs(t) ? -t.values[k] / K : t.values[k];
        const double v = std::clamp(p, 0.0, 1.0);
        if (!(std::abs(v - p) <= 1e-9))
            throw input_error("16-bit PNG: " + table_item(t, k) + " is " + format_g17(t.values[k]) + ", outside " +
                              (logs(t) ? "(-inf, 0]" : "[0, 1]") + " (" + png_rule(t) + ")");
        pixels[k] = static_cast<png_uint_16>(std::lround(v * 65535.0));
    }
    // libpng's simplified API (png.h, "SIMPLIFIED API"): a linear 16-bit grey image is written as it is (gAMA 1.0);
    // COLORSPACE_NOT_sRGB leaves out the sRGB primaries (cHRM): the pixels are data, not colour.
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(t.grid.n_x);
    image.height = static_cast<png_uint_32>(t.grid.alphas.size());
    image.format = PNG_FORMAT_LINEAR_Y;
    image.flags = PNG_IMAGE_FLAG_COLORSPACE_NOT_sRGB;
    png_alloc_size_t size = 0;
    std::vector<unsigned char> bytes;
    if (png_image_write_to_memory(&image, nullptr, &size, 0, pixels.data(), 0, nullptr)) {
        bytes.resize(size);
        if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels.data(), 0, nullptr)) bytes.clear();
    }
    if (bytes.empty()) throw std::runtime_error("16-bit PNG: libpng: " + std::string(image.message));
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(size));
}

void write_axes_json(std::ostream& out, const CompensationExport& e) {
    check(e);
    const AlbedoGrid& g = e.E->grid;
    const std::string na = std::to_string(g.alphas.size()), nx = std::to_string(g.n_x);
    out << "{\n  \"identifier\": " << json_string(compensation_identifier(e))
        << ",\n  \"family\": " << json_string(e.family) << ",\n  \"g2\": " << json_string(e.g2)
        << ",\n  \"quantity\": " << json_string(e.quantity) << ",\n  \"image\": {\"width\": " << nx
        << ", \"height\": " << na
        << ", \"bit_depth\": 16, \"color\": \"grey\", \"rows\": \"row i (from the top) is alphas[i]\", "
           "\"columns\": \"column j is x_j = j / (n_x - 1)\"},\n  \"scale\": 65535,\n  \"stored\": "
        << json_string(rule_value(*e.E)) << ",\n";
    if (logs(*e.E)) out << "  \"log_scale\": " << format_shortest(png_log_scale(*e.E)) << ",\n";
    out << "  \"value\": " << json_string(png_rule(*e.E)) << ",\n"
        << json_grid(g, std::string(rule_lookup) + (logs(*e.E) ? ", of ln E, then exp" : ""));
    if (!e.missing.empty())
        out << "  \"one_minus_E_avg\": " << json_numbers(e.missing)
            << ",\n  \"one_minus_E_avg_lookup\": " << json_string(rule_power_law) << ",\n";
    out << "  \"max_interpolation_error\": " << format_shortest(e.max_interp_error)
        << ",\n  \"below_grid_error\": " << format_shortest(e.below_grid_error)
        << ",\n  \"grazing_error\": " << format_shortest(e.grazing_error)
        << ",\n  \"grazing_cos_theta\": " << format_shortest(grazing_mu) << "\n}\n";
}

std::string order_identifier(const OrderExport& e) {
    return family_identifier(e.family, e.g2, "order export") + "_orders";
}

void write_source(std::ostream& out, const OrderExport& e, Language language) { write_source_of(out, e, language); }

void write_orders_axes_json(std::ostream& out, const OrderExport& e) {
    check(e);
    const std::vector<OrderTable> tables = order_tables(*e.orders);
    out << "{\n  \"identifier\": " << json_string(order_identifier(e)) << ",\n  \"family\": " << json_string(e.family)
        << ",\n  \"g2\": " << json_string(e.g2) << ",\n  \"multiple_scattering_albedo\": " << json_string(ms_formula)
        << ",\n  \"q1_rule\": " << json_string(q1_rule(tables.size() == 4)) << ",\n  \"tables\": {";
    for (std::size_t k = 0; k < tables.size(); ++k)
        out << (k ? ",\n    " : "\n    ") << json_string(tables[k].name) << ": "
            << json_numbers(tables[k].table->values);
    out << "\n  },\n  \"layout\": \"tables[name][i * n_x + j] at (alphas[i], x_j)\",\n"
        << json_grid(e.orders->q2.grid, std::string(rule_lookup))
        << "  \"max_standard_error_q2_q3\": " << format_shortest(e.max_stderr) << "\n}\n";
}

}  // namespace smithlab::compensation
