#include "smithlab/fit/compensation_formats.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/compensation.hpp"

namespace smithlab::fit {

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

// Where value k of the table is, for the messages.
std::string table_item(const AlbedoTable& t, std::size_t k) {
    const std::size_t nx = static_cast<std::size_t>(t.grid.n_x);
    return "E at alpha " + format_shortest(t.grid.alphas[k / nx]) + ", x_" + std::to_string(k % nx) + " = " +
        format_shortest(t.grid.x(static_cast<int>(k % nx)));
}

// compensation_formats.hpp's checks, input_error naming the item.
void check(const CompensationExport& e) {
    (void)compensation_identifier(e);
    if (!e.E) throw input_error("compensation export: no table (E is null)");
    const AlbedoTable& t = *e.E;
    t.grid.check();
    const std::vector<double>& a = t.grid.alphas;
    const std::size_t na = a.size(), nx = static_cast<std::size_t>(t.grid.n_x);
    if (t.values.size() != na * nx)
        throw input_error("compensation export: the table has " + std::to_string(t.values.size()) + " values for " +
                          std::to_string(na) + " alphas x " + std::to_string(nx) + " cosines");
    for (std::size_t k = 0; k < t.values.size(); ++k)
        if (!fits_float(t.values[k]))
            throw input_error("compensation export: " + table_item(t, k) +
                              " is not a finite float: " + format_g17(t.values[k]));
    for (std::size_t i = 0; i < na; ++i)
        if (!(t.grid.scales[i] >= static_cast<double>(std::numeric_limits<float>::min()) &&
              fits_float(t.grid.scales[i])))
            throw input_error("compensation export: the warp's scale at alpha " + format_shortest(a[i]) + " is " +
                              format_g17(t.grid.scales[i]) + ", not a normal float");
    for (std::size_t i = 1; i < na; ++i)
        if (!(static_cast<float>(std::sqrt(a[i])) > static_cast<float>(std::sqrt(a[i - 1]))))
            throw input_error("compensation export: alphas " + format_shortest(a[i - 1]) + " and " +
                              format_shortest(a[i]) + " have the same sqrt(alpha) as floats");
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

// The top comment of the three text formats.
std::string top_comment(const CompensationExport& e, const std::string& id, std::string_view language) {
    const AlbedoGrid& g = e.E->grid;
    const std::vector<double>& a = g.alphas;
    std::string alphas;
    for (std::size_t i = 0; i < a.size(); ++i) alphas += (i ? ", " : "") + format_shortest(a[i]);
    const std::vector<std::string> p = {
        id + ": energy compensation of specular multiple scattering, " + std::string(language) +
            ". Generated by smithlab (fit/compensation_formats.hpp).",
        "NDF family: " + comment_text(e.family) + ". G2: " +
            (e.g2 == height_correlated ? "height-correlated Smith G2 (Walter et al. 2007, eq. 20; Heitz 2014, eq. 99)"
                                       : "separable Smith G2 = G1(wi) G1(wo) (Heitz 2014, eq. 98)") +
            ". Quantity: " + comment_text(e.quantity) +
            (e.quantity == "E" ? " (the directional albedo of single scattering off mirror facets, F = 1)" : "") +
            ", tabulated as E(alpha, mu), mu = cos(theta); E_avg(alpha) = 2 int_0^1 E(alpha, mu) mu dmu.",
        "Kulla and Conty 2017 (\"Revisiting Physically Based Shading at Imageworks\"): f_ms(wi, wo) = (1 - E(mu_i)) "
        "(1 - E(mu_o)) / (pi (1 - E_avg))" +
            (e.missing.empty() ? std::string() : ", (1 - E_avg) = " + id + "_missing(alpha)") +
            ", times F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) for coloured facets; Turquin 2019 (\"Practical multiple "
            "scattering compensation for microfacet models\"): f = f_ss (1 + F0 (1 - E(mu_v)) / E(mu_v)), mu_v the "
            "view's cosine.",
        "Grid: n_alpha x n_x = " + std::to_string(a.size()) + " x " + std::to_string(g.n_x) + ", alpha in [" +
            format_shortest(a.front()) + ", " + format_shortest(a.back()) + "]: alphas " + alphas + "; " + rule_x(g) +
            "; " + id + table_name(*e.E) + "[i * n_x + j] = " + rule_value(*e.E) +
            "(alphas[i], x_j), at mu = " + rule_mu_of_x(g) + " at x_j and c_i = exp(" + id +
            "_log_scale[i]), the warp's scale at alphas[i] (6 cos(theta) where the NDF's Lambda = 0.3: its rows' dip)" +
            (logs(*e.E) ? "; the table holds ln E so that its lookup's error is relative, as a division by E needs."
                        : "."),
        "The warp's scale c at any alpha: " + std::string(rule_power_law) + ".",
        id + "_E(alpha, mu): " + std::string(rule_lookup) + (logs(*e.E) ? ", of ln E, then exp." : "."),
        "Outside the grid, nothing is clamped silently:",
        "  below the first alpha: " + std::string(rule_below) + ";",
        "  above the last alpha: " + std::string(rule_above) + ";",
        "  mu " + std::string(rule_mu) + ";",
        "  alpha must be " + std::string(rule_alpha) + ".",
        e.missing.empty() ? "No E_avg is given with this table."
                          : id + "_missing(alpha) = 1 - E_avg(alpha): " + std::string(rule_power_law) + "; " + id +
                "_log_missing_table[i] = ln(1 - E_avg(alphas[i])). " + id + "_E_avg(alpha) = 1 - " + id +
                "_missing(alpha). Kulla and Conty's lobe should divide by " + id + "_missing(alpha), not by 1 - " + id +
                "_E_avg(alpha): 1 - E_avg falls like alpha^2 at small alpha, and 1 - E_avg taken from a float E_avg "
                "loses its relative precision (a float E_avg = 1 - 1e-8 is 1).",
        "Measured: the lookup is within " + short_g(e.max_interp_error) +
            " of the exact values inside the grid at mu >= " + format_shortest(grazing_mu) + ", within " +
            short_g(e.grazing_error) + " at grazing mu < " + format_shortest(grazing_mu) +
            " (theta > 89.885 degrees), within " + short_g(e.below_grid_error) +
            " below the first alpha (mu >= " + format_shortest(grazing_mu) + ").",
        "The values are the floats nearest the computed doubles (9 significant digits)."};
    return comment_block(p);
}

// What differs between C, GLSL and HLSL in the arrays and lookups; the code is the same.
struct Dialect {
    std::string_view array;     // before a constant array's name
    bool constructor;           // GLSL's initializer float[N](...), else {...}
    std::string_view function;  // before a function
    std::string_view suffix;    // of float literals
    std::string_view sqrt, log, exp;
    bool c_cast;  // (int)(x), else int(x)
    std::string cast(std::string_view type, std::string_view x) const {
        std::string s(c_cast ? "(" : "");
        s.append(type).append(c_cast ? ")(" : "(").append(x);
        return s + ")";
    }
};
constexpr Dialect c_dialect{"static const float ", false, "static inline ", "f", "sqrtf", "logf", "expf", true};
constexpr Dialect glsl_dialect{"const float ", true, "", "", "sqrt", "log", "exp", false};
constexpr Dialect hlsl_dialect{"static const float ", false, "", "f", "sqrt", "log", "exp", true};

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

// The arrays and lookups, after the top comment.
std::string arrays_and_lookups(const CompensationExport& e, const std::string& id, const Dialect& d) {
    const AlbedoTable& t = *e.E;
    const std::vector<double>& a = t.grid.alphas;
    const std::string na = std::to_string(a.size()), nx = std::to_string(t.grid.n_x);
    const std::string f = std::string(d.function), one = float_literal(1.0, d.suffix),
                      zero = float_literal(0.0, d.suffix);
    std::vector<double> sqrt_alpha;
    std::vector<std::string> labels;
    for (const double v : a) {
        sqrt_alpha.push_back(std::sqrt(v));
        labels.push_back("alpha = " + format_shortest(v));
    }
    std::vector<double> log_scale;
    for (const double c : t.grid.scales) log_scale.push_back(std::log(c));
    std::string s = "\n" + array(d, id + "_sqrt_alpha", sqrt_alpha, 8) + array(d, id + "_log_scale", log_scale, 8) +
        array(d, id + table_name(t), t.values, static_cast<std::size_t>(t.grid.n_x), labels);
    if (!e.missing.empty()) {
        std::vector<double> log_missing;
        for (const double m : e.missing) log_missing.push_back(std::log(m));
        s += array(d, id + "_log_missing_table", log_missing, 8);
    }
    s += "\n/* The lower node i of sqrt(alpha)'s cell: 0 below the first node, n_alpha - 2 above the last. */\n" + f +
        "int " + id + "_alpha_cell(float s) {\n    int i = 0;\n    for (int k = 1; k < " +
        std::to_string(a.size() - 1) + "; ++k) {\n        if (" + id +
        "_sqrt_alpha[k] <= s) i = k;\n    }\n    return i;\n}\n\n"
        "/* The weight of node i + 1 in cell i: 0 below the first node, 1 above the last. */\n" +
        f + "float " + id + "_alpha_weight(float s, int i) {\n    if (!(s > " + id + "_sqrt_alpha[0])) return " + zero +
        ";\n    if (!(s < " + id + "_sqrt_alpha[" + std::to_string(a.size() - 1) + "])) return " + one +
        ";\n    return (s - " + id + "_sqrt_alpha[i]) / (" + id + "_sqrt_alpha[i + 1] - " + id +
        "_sqrt_alpha[i]);\n}\n\n"
        "/* The weight of node i + 1 in ln(alpha) (the same in ln(sqrt(alpha))): below the first node the first cell's "
        "line\n   continued, 1 above the last. */\n" +
        f + "float " + id + "_log_weight(float s, int i) {\n    return s < " + id + "_sqrt_alpha[" +
        std::to_string(a.size() - 1) + "] ? " + std::string(d.log) + "(s / " + id + "_sqrt_alpha[i]) / " +
        std::string(d.log) + "(" + id + "_sqrt_alpha[i + 1] / " + id + "_sqrt_alpha[i]) : " + one + ";\n}\n\n";
    const std::string T = id + table_name(t), C = id + "_log_scale", ex(d.exp), sq(d.sqrt);
    const NodeCluster& k = t.grid.cluster;
    std::string x = sq + "((" + one + " + c) * m / (m + c))";
    if (k.weight != 0.0) {
        // x = (1 - b) warp + b (asinh((m - mu_k) / w) + lo) / (lo + hi), asinh odd: sign(z) ln(|z| + sqrt(z^2 + 1)).
        const double lo = std::asinh(k.mu / k.width), hi = std::asinh((1.0 - k.mu) / k.width);
        s += "/* asinh(z), odd. */\n" + f + "float " + id + "_asinh(float z) {\n    float a = z < " + zero +
            " ? -z : z;\n    float y = " + std::string(d.log) + "(a + " + sq + "(a * a + " + one +
            "));\n    return z < " + zero + " ? -y : y;\n}\n\n";
        x = float_literal(1.0 - k.weight, d.suffix) + " * " + x + " + " +
            float_literal(k.weight / (lo + hi), d.suffix) + " * (" + id + "_asinh((m - " +
            float_literal(k.mu, d.suffix) + ") / " + float_literal(k.width, d.suffix) + ") + " +
            float_literal(lo, d.suffix) + ")";
    }
    s += "/* E(alpha, mu), alpha > 0: bilinear in (sqrt(alpha), x)" + std::string(logs(t) ? " of ln E, then exp" : "") +
        ", x = " + (k.weight == 0.0 ? "sqrt((1 + c) mu / (mu + c))" : "the warp and the cluster's share") +
        ", c the\n   warp's scale at alpha, mu clamped to [0, 1]. */\n" + f + "float " + id +
        "_E(float alpha, float mu) {\n    float m = mu > " + zero + " ? (mu < " + one + " ? mu : " + one +
        ") : " + zero + ";\n    float s = " + sq + "(alpha);\n    int i = " + id +
        "_alpha_cell(s);\n    float ta = " + id + "_alpha_weight(s, i);\n    float u = " + id +
        "_log_weight(s, i);\n    float c = " + ex + "(" + C + "[i] + u * (" + C + "[i + 1] - " + C +
        "[i]));\n    float x = (" + x + ") * " + float_literal(t.grid.n_x - 1, d.suffix) +
        ";\n    int j = " + d.cast("int", "x") + ";\n    if (j > " + std::to_string(t.grid.n_x - 2) +
        ") j = " + std::to_string(t.grid.n_x - 2) + ";\n    float tx = x - " + d.cast("float", "j") +
        ";\n    int a = i * " + nx + " + j;\n    int b = a + " + nx + ";\n    float lo = " + T + "[a] + tx * (" + T +
        "[a + 1] - " + T + "[a]);\n    float hi = " + T + "[b] + tx * (" + T + "[b + 1] - " + T + "[b]);\n    return " +
        (logs(t) ? ex + "(lo + ta * (hi - lo))" : std::string("lo + ta * (hi - lo)")) + ";\n}\n";
    if (!e.missing.empty()) {
        const std::string L = id + "_log_missing_table";
        s += "\n/* 1 - E_avg(alpha), alpha > 0: ln(1 - E_avg) linear in ln(alpha) between the nodes; below the first "
             "node the\n   first interval's power of alpha continued, above the last node the last value. Divide "
             "Kulla and Conty's\n   lobe by this, not by 1 - " +
            id + "_E_avg(alpha) (no cancellation). */\n" + f + "float " + id +
            "_missing(float alpha) {\n    float s = " + std::string(d.sqrt) + "(alpha);\n    int i = " + id +
            "_alpha_cell(s);\n    float u = " + id + "_log_weight(s, i);\n    return " + ex + "(" + L + "[i] + u * (" +
            L + "[i + 1] - " + L +
            "[i]));\n}\n\n"
            "/* E_avg(alpha) = 1 - " +
            id + "_missing(alpha), alpha > 0. */\n" + f + "float " + id + "_E_avg(float alpha) { return " + one +
            " - " + id + "_missing(alpha); }\n";
    }
    return s;
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

// bytes to path through path.tmp, renamed: a reader never sees a half-written file, and a failure leaves none.
void write_replacing(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    std::error_code ignored;
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw std::runtime_error("16-bit PNG: cannot open " + tmp.string() + " to write " + path.string());
        f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
        f.close();
        if (!f) {
            std::filesystem::remove(tmp, ignored);
            throw std::runtime_error("16-bit PNG: writing " + tmp.string() + " failed (for " + path.string() + ")");
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ignored);
        throw std::runtime_error("16-bit PNG: cannot rename " + tmp.string() + " to " + path.string() + ": " +
                                 ec.message());
    }
}

}  // namespace

std::string compensation_identifier(const CompensationExport& e) {
    const std::string family = identifier_part(e.family);
    if (family.empty())
        throw input_error("compensation export: the NDF family '" + e.family + "' has no letter or digit to name it");
    if (e.g2 != height_correlated && e.g2 != separable)
        throw input_error("compensation export: G2 '" + e.g2 + "', known: height-correlated, separable");
    std::string id = "smithlab_" + family + (e.g2 == height_correlated ? "_hc" : "_sep");
    if (e.quantity == "E") return id;
    const std::string quantity = identifier_part(e.quantity);
    if (quantity.empty())
        throw input_error("compensation export: the quantity '" + e.quantity + "' has no letter or digit to name it");
    return id + "_" + quantity;
}

void write_c_header(std::ostream& out, const CompensationExport& e) {
    check(e);
    const std::string id = compensation_identifier(e);
    std::string guard = id;
    for (char& c : guard) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    guard += "_COMPENSATION_H";
    out << top_comment(e, id, "self-contained C99 (or C++)") << "#ifndef " << guard << "\n#define " << guard
        << "\n\n#include <math.h>\n"
        << arrays_and_lookups(e, id, c_dialect) << "\n#endif /* " << guard << " */\n";
}

void write_glsl(std::ostream& out, const CompensationExport& e) {
    check(e);
    const std::string id = compensation_identifier(e);
    out << top_comment(e, id, "GLSL 3.30 (no #version line: it goes after the includer's)")
        << arrays_and_lookups(e, id, glsl_dialect);
}

void write_hlsl(std::ostream& out, const CompensationExport& e) {
    check(e);
    const std::string id = compensation_identifier(e);
    out << top_comment(e, id, "HLSL") << arrays_and_lookups(e, id, hlsl_dialect);
}

void write_png16(const std::filesystem::path& path, const CompensationExport& e) {
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
            throw input_error("16-bit PNG " + path.string() + ": " + table_item(t, k) + " is " +
                              format_g17(t.values[k]) + ", outside " + (logs(t) ? "(-inf, 0]" : "[0, 1]") + " (" +
                              png_rule(t) + ")");
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
    if (bytes.empty())
        throw std::runtime_error("16-bit PNG " + path.string() + ": libpng: " + std::string(image.message));
    bytes.resize(size);
    write_replacing(path, bytes);
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
    out << "  \"value\": " << json_string(png_rule(*e.E)) << ",\n  \"alphas\": " << json_numbers(g.alphas)
        << ",\n  \"warp_scales\": " << json_numbers(g.scales)
        << ",\n  \"warp_scale_lookup\": " << json_string(rule_power_law) << ",\n  \"n_x\": " << nx
        << ",\n  \"x\": " << json_string(rule_x(g));
    if (g.cluster.weight != 0.0)
        out << ",\n  \"cluster\": {\"mu\": " << format_shortest(g.cluster.mu)
            << ", \"width\": " << format_shortest(g.cluster.width)
            << ", \"weight\": " << format_shortest(g.cluster.weight) << "}";
    out << ",\n  \"mu_of_x\": " << json_string(rule_mu_of_x(g))
        << ",\n  \"lookup\": " << json_string(std::string(rule_lookup) + (logs(*e.E) ? ", of ln E, then exp" : ""))
        << ",\n  \"below_first_alpha\": " << json_string(rule_below)
        << ",\n  \"above_last_alpha\": " << json_string(rule_above) << ",\n  \"mu\": " << json_string(rule_mu)
        << ",\n  \"alpha\": " << json_string(rule_alpha) << ",\n";
    if (!e.missing.empty())
        out << "  \"one_minus_E_avg\": " << json_numbers(e.missing)
            << ",\n  \"one_minus_E_avg_lookup\": " << json_string(rule_power_law) << ",\n";
    out << "  \"max_interpolation_error\": " << format_shortest(e.max_interp_error)
        << ",\n  \"below_grid_error\": " << format_shortest(e.below_grid_error)
        << ",\n  \"grazing_error\": " << format_shortest(e.grazing_error)
        << ",\n  \"grazing_cos_theta\": " << format_shortest(grazing_mu) << "\n}\n";
}

}  // namespace smithlab::fit
