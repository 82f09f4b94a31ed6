#include "smithlab/tabulated.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <sstream>
#include <vector>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab {

namespace detail {
// The interpolant of tabulated.hpp: nodes (theta_i, D_i), y_i = ln D_i (-inf where D_i = 0), Steffen slopes dy_i.
struct TabulatedTable {
    std::vector<double> theta, D, y, dy;
    double pole_b = 0.0;        // ln D = y_0 + pole_b (theta^2 - theta_0^2) below theta_0
    double D0 = 0.0, D1 = 0.0;  // the tail: D = D0 + D1 cos^2 past theta_n
    double c2_last = 1.0;       // cos^2 theta_n
    double area = 1.0, factor = 1.0;
    double theta_min_deg = 0.0, theta_max_deg = 0.0;
    std::uint64_t hash = 0;
    std::string source;

    // D at theta in [0, pi/2), the tail excluded (theta <= theta_n).
    double D_inside(double t) const {
        if (t < theta.front())
            return D.front() > 0.0 ? std::exp(y.front() + pole_b * (t * t - theta.front() * theta.front())) : 0.0;
        const std::size_t n = theta.size();
        const std::size_t i = std::min<std::size_t>(
            static_cast<std::size_t>(std::upper_bound(theta.begin(), theta.end(), t) - theta.begin()) - 1, n - 2);
        const double h = theta[i + 1] - theta[i], u = (t - theta[i]) / h;
        if (D[i] > 0.0 && D[i + 1] > 0.0) {  // cubic Hermite of ln D
            const double u2 = u * u, u3 = u2 * u;
            const double v = (2.0 * u3 - 3.0 * u2 + 1.0) * y[i] + (u3 - 2.0 * u2 + u) * h * dy[i] +
                (3.0 * u2 - 2.0 * u3) * y[i + 1] + (u3 - u2) * h * dy[i + 1];
            return std::exp(v);
        }
        return D[i] + (D[i + 1] - D[i]) * u;  // a zero end: linear in D
    }
    // D at theta in [0, pi/2), c2 = cos^2 theta: the tail law past theta_n.
    double D_at(double t, double c2) const {
        if (t > theta.back()) return D0 + D1 * c2;
        return D_inside(t);
    }
};
}  // namespace detail

std::uint64_t fnv1a64(std::string_view bytes) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char b : bytes) {
        h ^= b;
        h *= 0x100000001b3ULL;
    }
    return h;
}

namespace {
using detail::TabulatedTable;
using std::numbers::pi;

// 8-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun table 25.4).
constexpr std::array<double, 4> gl_x = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> gl_w = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

template <class F>
double gauss_legendre(const F& f, double a, double b) {
    const double m = 0.5 * (a + b), r = 0.5 * (b - a);
    double s = 0.0;
    for (std::size_t k = 0; k < gl_x.size(); ++k) s += gl_w[k] * (f(m - r * gl_x[k]) + f(m + r * gl_x[k]));
    return s * r;
}

// The text with its comment lines emptied: a line whose first character is '#', where a record starts (not inside a
// quoted field, tracked as read_csv does: a quote opens one only at the start of a field). Every line end is kept,
// so that read_csv skips the emptied lines as blank and the line numbers stay the file's. A UTF-8 byte order mark
// (spreadsheets write one) is dropped.
std::string blank_comments(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    bool quoted = false, line_start = true, field_start = true;
    for (std::size_t i = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (line_start && ch == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
            if (i < text.size()) out += '\n';
            continue;
        }
        out += ch;
        if (quoted) {
            if (ch == '"') {
                if (i + 1 < text.size() && text[i + 1] == '"') out += text[++i];
                else quoted = false;
            }
        } else if (ch == '"' && field_start) {
            quoted = true;
        }
        field_start = !quoted && (ch == ',' || ch == '\n');
        line_start = !quoted && ch == '\n';
    }
    return out;
}

[[noreturn]] void refuse(const std::string& source, std::size_t line, const std::string& what) {
    throw input_error(source + ":" + std::to_string(line) + ": " + what);
}

std::string format_value(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}

// Steffen's slopes (Steffen 1990) on the run of positive nodes [a, b]: eq. 11 inside, eq. 26-27 at its ends.
void steffen_slopes(TabulatedTable& t, std::size_t a, std::size_t b) {
    const std::vector<double>& x = t.theta;
    const std::vector<double>& y = t.y;
    auto secant = [&](std::size_t i) { return (y[i + 1] - y[i]) / (x[i + 1] - x[i]); };
    auto sign = [](double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; };
    if (a == b) {
        t.dy[a] = 0.0;
        return;
    }
    if (b == a + 1) {
        t.dy[a] = t.dy[b] = secant(a);
        return;
    }
    for (std::size_t i = a + 1; i < b; ++i) {
        const double h0 = x[i] - x[i - 1], h1 = x[i + 1] - x[i], s0 = secant(i - 1), s1 = secant(i);
        const double p = (s0 * h1 + s1 * h0) / (h0 + h1);
        t.dy[i] = (sign(s0) + sign(s1)) * std::min({std::abs(s0), std::abs(s1), 0.5 * std::abs(p)});
    }
    // The end slope: the parabola's through the three end nodes, limited to [0, 2 s] in the direction of the secant s.
    auto end = [&](double s0, double s1, double h0, double h1) {
        const double p = s0 * (1.0 + h0 / (h0 + h1)) - s1 * h0 / (h0 + h1);
        if (p * s0 <= 0.0) return 0.0;
        if (std::abs(p) > 2.0 * std::abs(s0)) return 2.0 * s0;
        return p;
    };
    t.dy[a] = end(secant(a), secant(a + 1), x[a + 1] - x[a], x[a + 2] - x[a + 1]);
    t.dy[b] = end(secant(b - 1), secant(b - 2), x[b] - x[b - 1], x[b - 1] - x[b - 2]);
}

// The projected area 2 pi integral_0^{pi/2} D sin cos dtheta of the interpolant (tabulated.hpp).
double projected_area(const TabulatedTable& t) {
    auto f = [&](double th) { return t.D_inside(th) * std::sin(th) * std::cos(th); };
    double s = 0.0;
    if (t.theta.front() > 0.0) s += gauss_legendre(f, 0.0, t.theta.front());
    for (std::size_t i = 0; i + 1 < t.theta.size(); ++i) s += gauss_legendre(f, t.theta[i], t.theta[i + 1]);
    // The tail: integral_0^{c_n} (D0 + D1 u^2) u du, u = cos theta.
    s += t.D0 * t.c2_last / 2.0 + t.D1 * t.c2_last * t.c2_last / 4.0;
    return 2.0 * pi * s;
}

// The columns of the header: the angle's (theta_deg or cos_theta) and D's.
struct Columns {
    int angle, D;
    bool by_cos;
    const char* angle_name;
};

Columns header_columns(const CsvRecord& head, const std::string& source) {
    if (!head.error.empty()) refuse(source, head.line, "header: " + head.error);
    int theta_col = -1, cos_col = -1, D_col = -1;
    for (std::size_t k = 0; k < head.fields.size(); ++k) {
        const std::string& h = head.fields[k];
        int* col = h == "theta_deg" ? &theta_col : h == "cos_theta" ? &cos_col : h == "D" ? &D_col : nullptr;
        if (!col) continue;
        if (*col >= 0) refuse(source, head.line, "the header has two '" + h + "' columns");
        *col = static_cast<int>(k);
    }
    if (theta_col >= 0 && cos_col >= 0)
        refuse(source, head.line, "the header has both 'theta_deg' and 'cos_theta' columns; give the angle once");
    if ((theta_col < 0 && cos_col < 0) || D_col < 0) {
        std::string got;
        for (const auto& h : head.fields) got += (got.empty() ? "'" : ", '") + h + "'";
        refuse(source, head.line,
               std::string("the header has no '") + (D_col < 0 ? "D" : "theta_deg' or 'cos_theta") +
                   "' column (columns: " + got + ")");
    }
    const bool by_cos = cos_col >= 0;
    return {by_cos ? cos_col : theta_col, D_col, by_cos, by_cos ? "cos_theta" : "theta_deg"};
}

// A row's angle in radians, from theta_deg in [0, 90) or cos_theta in (0, 1] (a, read from a_text).
double row_theta(double a, const std::string& a_text, const Columns& c, const std::string& source, std::size_t line) {
    if (c.by_cos) {
        if (!(a > 0.0 && a <= 1.0)) refuse(source, line, "cos_theta must be in (0, 1], got " + a_text);
        return std::atan2(std::sqrt((1.0 - a) * (1.0 + a)), a);  // exact near the pole, where acos is not
    }
    if (!(a >= 0.0 && a < 90.0)) refuse(source, line, "theta_deg must be in [0, 90), got " + a_text);
    return a * (pi / 180.0);
}

// The nodes (theta_i, D_i) of the data rows (records after the header), checked row by row.
void read_nodes(const std::vector<CsvRecord>& records, const Columns& c, const std::string& source, TabulatedTable& t) {
    const CsvRecord& head = records.front();
    std::string prev_text;
    std::size_t prev_line = 0;
    for (std::size_t r = 1; r < records.size(); ++r) {
        const CsvRecord& rec = records[r];
        if (!rec.error.empty()) refuse(source, rec.line, rec.error);
        if (rec.fields.size() != head.fields.size())
            refuse(
                source, rec.line,
                "expected " + std::to_string(head.fields.size()) + " fields, got " + std::to_string(rec.fields.size()));
        const std::string& a_text = rec.fields[c.angle];
        const std::string& d_text = rec.fields[c.D];
        double a = 0.0, d = 0.0;
        try {
            a = parse_double(a_text, c.angle_name);
            d = parse_double(d_text, "D");
        } catch (const input_error& e) {
            refuse(source, rec.line, e.what());
        }
        const double theta = row_theta(a, a_text, c, source, rec.line);
        if (!(d >= 0.0 && d < INFINITY)) refuse(source, rec.line, "D must be finite and >= 0, got " + d_text);
        if (!t.theta.empty() && !(theta > t.theta.back()))
            refuse(source, rec.line,
                   c.by_cos ? "cos_theta must decrease from row to row (theta_m increasing), got " + a_text +
                           " after " + prev_text + " (line " + std::to_string(prev_line) + ")"
                            : "theta_deg must increase from row to row, got " + a_text + " after " + prev_text +
                           " (line " + std::to_string(prev_line) + ")");
        t.theta.push_back(theta);
        t.D.push_back(d);
        prev_text = a_text;
        prev_line = rec.line;
    }
}

// ln D and Steffen's slopes on each run of positive D, and the pole's law (D is even in theta).
void log_interpolant(TabulatedTable& t) {
    const std::size_t n = t.theta.size();
    t.y.resize(n);
    t.dy.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) t.y[i] = t.D[i] > 0.0 ? std::log(t.D[i]) : -INFINITY;
    for (std::size_t i = 0; i < n;) {
        if (!(t.D[i] > 0.0)) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < n && t.D[j + 1] > 0.0) ++j;
        steffen_slopes(t, i, j);
        i = j + 1;
    }
    if (t.theta[0] == 0.0) t.dy[0] = 0.0;
    else t.pole_b = t.dy[0] / (2.0 * t.theta[0]);
}

// The tail: D = D0 + D1 cos^2 through the last node, D1 by least squares over the last four.
void fit_tail(TabulatedTable& t) {
    const std::size_t n = t.theta.size();
    const double c_last = std::cos(t.theta[n - 1]);
    t.c2_last = c_last * c_last;
    const std::size_t q = std::min<std::size_t>(4, n);
    double suu = 0.0, sud = 0.0, dmax = 0.0;
    for (std::size_t i = n - q; i < n; ++i) {
        const double c = std::cos(t.theta[i]), u = c * c - t.c2_last, dd = t.D[i] - t.D[n - 1];
        suu += u * u;
        sud += u * dd;
        dmax = std::max(dmax, t.D[i]);
    }
    const double D1 = suu > 0.0 ? sud / suu : 0.0;
    t.D0 = std::clamp(t.D[n - 1] - D1 * t.c2_last, 0.0, dmax);
    t.D1 = (t.D[n - 1] - t.D0) / t.c2_last;
}

// The projected area, refused unless within the tolerance of 1 or normalize is on; then D divided by it: the Smith
// model holds only for a normalized D (the checks, G1's visible-area identity, hold it to 1e-8), and the factor is
// reported (TabulatedNdf::note).
void normalize_area(TabulatedTable& t, const std::vector<CsvRecord>& records, const std::string& source,
                    const TabulatedOptions& opts) {
    t.area = projected_area(t);
    if (!(std::abs(t.area - 1.0) <= tabulated_area_tolerance)) {
        if (!opts.normalize)
            throw input_error(source +
                              ": the projected area of D (2 pi times the integral of D cos sin dtheta, the "
                              "interpolant's) must be within " +
                              format_value(tabulated_area_tolerance) + " of 1, got " + format_value(t.area) +
                              " (rows at lines " + std::to_string(records[1].line) + "-" +
                              std::to_string(records.back().line) +
                              "); to divide D by it, give normalize=1 (tabulated(file=..., normalize=1))");
        if (!(t.area > 0.0 && t.area < INFINITY))
            throw input_error(source + ": the projected area of D is " + format_value(t.area) +
                              "; there is no scale to normalize it by");
    }
    t.factor = 1.0 / t.area;
    const double ln_f = std::log(t.factor);
    for (std::size_t i = 0; i < t.theta.size(); ++i) {
        t.D[i] *= t.factor;
        t.y[i] += ln_f;  // -inf stays -inf; the slopes of ln D are unchanged
    }
    t.D0 *= t.factor;
    t.D1 *= t.factor;
}

}  // namespace

TabulatedNdf tabulated_ndf_from_csv(const std::string& text, const std::string& source, const TabulatedOptions& opts) {
    std::istringstream in(blank_comments(text));
    const std::vector<CsvRecord> records = read_csv(in);
    if (records.empty())
        throw input_error(source + ": no header; expected a line naming the columns theta_deg (or cos_theta) and D");
    const Columns columns = header_columns(records.front(), source);
    auto table = std::make_shared<TabulatedTable>();
    TabulatedTable& t = *table;
    read_nodes(records, columns, source, t);
    const std::size_t n = t.theta.size();
    if (n < tabulated_min_points)
        refuse(source, records.back().line,
               "the table ends after " + std::to_string(n) + " data row" + (n == 1 ? "" : "s") +
                   "; the interpolation needs at least " + std::to_string(tabulated_min_points));
    log_interpolant(t);
    fit_tail(t);
    normalize_area(t, records, source, opts);
    t.theta_min_deg = t.theta.front() * (180.0 / pi);
    t.theta_max_deg = t.theta.back() * (180.0 / pi);
    t.hash = fnv1a64(text);
    t.source = source;
    return TabulatedNdf(std::move(table));
}

TabulatedNdf read_tabulated_ndf(const std::filesystem::path& path, const TabulatedOptions& opts) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // through symlinks; before open, which a FIFO blocks
    const std::string quoted = "tabulated ndf: '" + path.string() + "'";
    const std::string too_large = quoted + " is larger than " + std::to_string(tabulated_max_bytes) +
        " bytes (64 MiB), the most a table may hold";
    if (status.type() == fs::file_type::directory) throw input_error(quoted + " is a directory, not a CSV file");
    if (status.type() != fs::file_type::regular && status.type() != fs::file_type::not_found)
        throw input_error(quoted + " is not a regular file (a FIFO, a device or a socket): give a CSV file");
    if (const std::uintmax_t size = fs::file_size(path, ec); !ec && size > tabulated_max_bytes)
        throw input_error(too_large);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw input_error("tabulated ndf: cannot open '" + path.string() + "': " + std::strerror(errno));
    // In blocks, refused as soon as it passes the cap: a file growing as it is read is never held whole.
    std::string text;
    std::array<char, 1 << 16> block;
    while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0) {
        text.append(block.data(), static_cast<std::size_t>(in.gcount()));
        if (text.size() > tabulated_max_bytes) throw input_error(too_large);
    }
    if (in.bad()) throw input_error("tabulated ndf: cannot read '" + path.string() + "'");
    return tabulated_ndf_from_csv(text, path.string(), opts);
}

double TabulatedNdf::D(double c) const {
    if (!(c > 0.0)) return std::isnan(c) ? c : 0.0;
    if (c > 1.0) c = 1.0;
    const double s2 = (1.0 - c) * (1.0 + c);
    if (scale_ == 1.0) return t_->D_at(std::atan2(std::sqrt(s2), c), c * c);
    // D_s(c) = P22_s(tan^2) / c^4 with P22_s(r^2) = P22(r^2 / s^2) / s^2 (Walter 2007 eq. 42): the table's D at the
    // direction c' of slope r / s, cos^2 c' = s^2 c^2 / (s^2 c^2 + sin^2), times s^2 / (s^2 c^2 + sin^2)^2 (no 0/0
    // where c^4 underflows).
    const double sc = scale_ * c, w = sc * sc + s2;
    return t_->D_at(std::atan2(std::sqrt(s2), sc), sc * sc / w) * (scale_ * scale_) / (w * w);
}

double TabulatedNdf::table_P22(double r2) const {
    if (!(r2 < INFINITY)) return std::isnan(r2) ? r2 : 0.0;
    if (r2 < 0.0) r2 = 0.0;
    const double c2 = 1.0 / (1.0 + r2);
    const double d = t_->D_at(std::atan(std::sqrt(r2)), c2);
    return d * c2 * c2;
}

double TabulatedNdf::slope_density(double r2) const {
    if (scale_ == 1.0) return table_P22(r2);
    const double s2 = scale_ * scale_;
    return table_P22(r2 / s2) / s2;
}

std::string TabulatedNdf::note() const {
    if (std::abs(area_as_read() - 1.0) < 1e-9) return "";  // as normalized as its rows' digits carry: nothing to say
    return source() + ": " +
        format_printf("D multiplied by %.9g (its projected area was %.9g, not 1)", normalization_factor(),
                      area_as_read());
}

TabulatedNdf TabulatedNdf::scaled(double s) const {
    require(s >= 1e-4 && s <= 1e4, "tabulated: scale", "in [1e-4, 1e4]", s);
    TabulatedNdf out = *this;
    out.scale_ = s;
    return out;
}

std::size_t TabulatedNdf::points() const { return t_->theta.size(); }
double TabulatedNdf::theta_min_deg() const { return t_->theta_min_deg; }
double TabulatedNdf::theta_max_deg() const { return t_->theta_max_deg; }
double TabulatedNdf::horizon_D() const { return t_->D0; }
double TabulatedNdf::area_as_read() const { return t_->area; }
double TabulatedNdf::normalization_factor() const { return t_->factor; }
std::uint64_t TabulatedNdf::content_hash() const { return t_->hash; }
const std::string& TabulatedNdf::source() const { return t_->source; }

std::string TabulatedNdf::content_id() const {
    return format_printf("fnv1a64:%016llx", static_cast<unsigned long long>(t_->hash));
}

}  // namespace smithlab
