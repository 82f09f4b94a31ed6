#include "scene/strict_table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "scene/limits.hpp"
#include "scene/nearest_name.hpp"
#include "scene/spaced.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::scene {

namespace {

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// A section is a table opened by a [header] or [[header]] line, as opposed to a key = value.
bool is_section(const toml::value& v) {
    const std::string line = v.location().line_str();  // a copy: location() is a temporary
    const auto first = line.find_first_not_of(" \t");
    return (v.is_table() || v.is_array()) && first != std::string::npos && line[first] == '[';
}

// The text of a scalar value as the scene writes it ("0xffff_ffff", "1e-400"), without its digit separators.
std::string token_of(const toml::value& v) {
    const toml::source_location at = v.location();
    const std::string& line = at.line_str();
    if (at.column() < 1 || at.column() - 1 >= line.size()) return "";
    std::string token = line.substr(at.column() - 1, at.region());
    token.erase(std::remove(token.begin(), token.end(), '_'), token.end());
    return token;
}

// Whether an integer token fits in 64 bits, read exactly (toml11 clamps one that does not to the nearest bound).
bool fits_int64(std::string token) {
    if (!token.empty() && token[0] == '+') token.erase(0, 1);
    const bool negative = !token.empty() && token[0] == '-';
    int base = 10;
    if (token.size() > 2 && token[0] == '0' && std::isalpha(static_cast<unsigned char>(token[1]))) {
        base = token[1] == 'x' ? 16 : token[1] == 'o' ? 8 : 2;
        token.erase(0, 2);
    }
    std::int64_t parsed = 0;
    const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), parsed, base);
    return !(negative && base != 10) && ec == std::errc() && end == token.data() + token.size();
}

}  // namespace

std::vector<double> spaced(double lo, double hi, std::int64_t n, Spacing spacing) {
    std::vector<double> out;
    const bool cube = spacing == Spacing::cbrt;
    const double s0 = cube ? std::cbrt(lo) : std::sqrt(lo), s1 = cube ? std::cbrt(hi) : std::sqrt(hi);
    for (std::int64_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(n - 1);
        const double s = s0 + t * (s1 - s0);
        out.push_back(spacing == Spacing::log        ? lo * std::pow(hi / lo, t)
                          : spacing == Spacing::sqrt ? s * s
                          : cube                     ? s * s * s
                                                     : lo + t * (hi - lo));
    }
    out.front() = lo;
    out.back() = hi;
    return out;
}

std::string describe_toml(const toml::value& v) {
    const auto shown = [&](const char* kind) {
        std::string text = v.is_floating() ? format_shortest(v.as_floating()) : toml::format(v);
        if (text.size() > 40) text = text.substr(0, 37) + "...";
        return std::string(kind) + " (" + text + ")";
    };
    switch (v.type()) {
        case toml::value_t::boolean:
            return shown("a boolean");
        case toml::value_t::integer:
            return shown("an integer");
        case toml::value_t::floating:
            return shown("a real");
        case toml::value_t::string:
            return shown("a string");
        case toml::value_t::array:
            return "a list";
        case toml::value_t::table:
            return "a table";
        case toml::value_t::empty:
            return "nothing";
        default:
            return shown("a date or time");
    }
}

StrictTable::StrictTable(const toml::value& table, std::string source, std::string path, std::vector<std::string> known)
    : table_(&table), source_(std::move(source)), path_(std::move(path)), known_(std::move(known)) {
    refuse_unknown_keys();
}

void StrictTable::refuse_unknown_keys() const {
    std::vector<std::pair<std::uint_least32_t, std::string>> lines;  // sorted by line: the file's order
    for (const auto& [key, value] : table_->as_table()) {
        if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
        const std::string near = nearest_name(key, known_);
        const std::string hint =
            near.empty() ? " (known here: " + joined(known_) + ")" : " (did you mean '" + name_of(near) + "'?)";
        lines.push_back({value.location().line(),
                         source_ + ":" + std::to_string(value.location().line()) + ": unknown " +
                             (is_section(value) ? "section '" : "key '") + name_of(key) + "'" + hint});
    }
    if (lines.empty()) return;
    std::sort(lines.begin(), lines.end());
    std::string message;
    for (const auto& [line, text] : lines) message += (message.empty() ? "" : "\n") + text;
    throw input_error(message);
}

bool StrictTable::has(const std::string& key) const { return table_->as_table().count(key) != 0; }

std::string StrictTable::name_of(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

std::string StrictTable::where(const std::string& key) const {
    const auto found = table_->as_table().find(key);
    if (found != table_->as_table().end())
        return source_ + ":" + std::to_string(found->second.location().line()) + ": " + name_of(key);
    if (path_.empty()) return source_ + ": " + name_of(key);  // the document has no line of its own
    return source_ + ":" + std::to_string(table_->location().line()) + ": " + name_of(key);
}

void StrictTable::fail(const std::string& key, const std::string& message) const {
    throw input_error(where(key) + " " + message);
}

const toml::value& StrictTable::need(const std::string& key) {
    if (!has(key)) fail(key, "is missing");
    read_.insert(key);
    return table_->as_table().at(key);
}

const toml::value& StrictTable::value(const std::string& key) { return need(key); }

std::string StrictTable::text(const std::string& key) {
    const toml::value& v = need(key);
    if (!v.is_string()) fail(key, "must be a string, got " + describe_toml(v));
    return v.as_string().str;
}

std::string StrictTable::text(const std::string& key, const std::string& fallback) {
    return has(key) ? text(key) : fallback;
}

std::int64_t StrictTable::integer_of(const toml::value& v, const std::string& key) const {
    const std::int64_t x = v.as_integer();
    const bool at_bound =
        x == std::numeric_limits<std::int64_t>::max() || x == std::numeric_limits<std::int64_t>::min();
    if (at_bound && !fits_int64(token_of(v)))
        fail(key,
             "is out of range: a TOML integer is 64-bit, in [-9223372036854775808, 9223372036854775807], got " +
                 token_of(v));
    return x;
}

double StrictTable::real_of(const toml::value& v, const std::string& key) const {
    if (v.is_integer()) return static_cast<double>(integer_of(v, key));
    const double x = v.as_floating();
    // toml11 reads a real beyond the largest double as +-DBL_MAX and one below the smallest as 0 (or a subnormal
    // rounded its own way): such a value is read again from its text, strictly.
    if (x != 0.0 && std::abs(x) >= std::numeric_limits<double>::min() &&
        std::abs(x) < std::numeric_limits<double>::max())
        return x;
    const std::string token = token_of(v);
    try {
        return parse_double(token, "value");
    } catch (const input_error&) {
        fail(key,
             "is out of range: a real must lie within the doubles (4.9e-324 to 1.8e308 in magnitude, or 0), got " +
                 token);
    }
}

double StrictTable::real(const std::string& key) {
    const toml::value& v = need(key);
    if (!v.is_integer() && !v.is_floating()) fail(key, "must be a number, got " + describe_toml(v));
    return real_of(v, key);
}

double StrictTable::real(const std::string& key, double fallback) { return has(key) ? real(key) : fallback; }

std::int64_t StrictTable::integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
    const toml::value& v = need(key);
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!v.is_integer()) fail(key, "must be an integer in " + range + ", got " + describe_toml(v));
    const std::int64_t x = integer_of(v, key);
    if (x < lo || x > hi) fail(key, "must be an integer in " + range + ", got " + std::to_string(x));
    return x;
}

std::int64_t StrictTable::integer(const std::string& key, std::int64_t lo, std::int64_t hi, std::int64_t fallback) {
    return has(key) ? integer(key, lo, hi) : fallback;
}

bool StrictTable::flag(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const toml::value& v = need(key);
    if (!v.is_boolean()) fail(key, "must be true or false, got " + describe_toml(v));
    return v.as_boolean();
}

std::vector<std::string> StrictTable::texts(const std::string& key) {
    const toml::value& v = need(key);
    if (!v.is_array()) fail(key, "must be a list of strings, got " + describe_toml(v));
    std::vector<std::string> out;
    for (const toml::value& x : v.as_array()) {
        if (!x.is_string()) fail(key, "must be a list of strings, got " + describe_toml(x) + " in it");
        out.push_back(x.as_string().str);
    }
    return out;
}

std::vector<std::string> StrictTable::texts(const std::string& key, const std::vector<std::string>& fallback) {
    return has(key) ? texts(key) : fallback;
}

std::vector<double> StrictTable::reals(const std::string& key) {
    const toml::value& v = need(key);
    if (!v.is_array()) fail(key, "must be a list of numbers, got " + describe_toml(v));
    std::vector<double> out;
    for (const toml::value& x : v.as_array()) {
        if (!x.is_integer() && !x.is_floating())
            fail(key, "must be a list of numbers, got " + describe_toml(x) + " in it");
        out.push_back(real_of(x, key));
    }
    return out;
}

StrictTable StrictTable::table(const std::string& key, std::vector<std::string> known) {
    const toml::value& v = need(key);
    if (!v.is_table()) fail(key, "must be a table, got " + describe_toml(v));
    return StrictTable(v, source_, name_of(key), std::move(known));
}

std::optional<StrictTable> StrictTable::optional_table(const std::string& key, std::vector<std::string> known) {
    if (!has(key)) return std::nullopt;
    return table(key, std::move(known));
}

std::vector<StrictTable> StrictTable::tables(const std::string& key, const std::vector<std::string>& known) {
    if (!has(key)) return {};
    const toml::value& v = need(key);
    const auto is_table = [](const toml::value& x) { return x.is_table(); };
    if (!v.is_array() || !std::all_of(v.as_array().begin(), v.as_array().end(), is_table))
        fail(key, "must be tables, each opened by [[" + name_of(key) + "]], got " + describe_toml(v));
    std::vector<StrictTable> out;
    for (const toml::value& x : v.as_array()) out.emplace_back(x, source_, name_of(key), known);
    return out;
}

void StrictTable::done() const {
    for (const auto& [key, value] : table_->as_table())
        if (!read_.count(key)) fail(key, "is not used by this reader (a key it declares but does not read)");
}

namespace {

// The index just past a string that opens at text[i] (", ', """ or '''), counting the lines it spans; an unclosed
// one ends at the end of its line (toml11 then reports it).
std::size_t skip_string(const std::string& text, std::size_t i, std::size_t& line) {
    const char quote = text[i];
    const std::string close(text.compare(i, 3, std::string(3, quote)) == 0 ? 3 : 1, quote);
    for (i += close.size(); i < text.size(); ++i) {
        if (text[i] == '\n' && close.size() == 1) return i;  // the caller counts this line
        if (text[i] == '\n') {
            ++line;
        } else if (quote == '"' && text[i] == '\\') {
            if (i + 1 < text.size() && text[i + 1] == '\n') ++line;
            ++i;  // the escaped character
        } else if (text.compare(i, close.size(), close) == 0) {
            return i + close.size();
        }
    }
    return i;
}

}  // namespace

void check_scene_text(const std::string& text, const std::string& source) {
    if (text.size() > max_scene_bytes)
        throw input_error("scene " + source + " is larger than " + std::to_string(max_scene_bytes) +
                          " bytes (1 MiB), the most a scene file may hold");
    // The open lists and tables, and the dots of the key being read: a dotted key a.b.c nests a table per dot.
    std::string open;
    int dots = 0;
    bool in_key = true;  // a line at the top, a table header and an inline table's entries start with a key
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size();) {
        const char c = text[i];
        if (c == '"' || c == '\'') {
            i = skip_string(text, i, line);
            continue;
        }
        if (c == '#') {
            i = std::min(text.find('\n', i), text.size());
            continue;
        }
        if (c == '\n') ++line;
        if (c == '[' || c == '{') open.push_back(c);
        if ((c == ']' || c == '}') && !open.empty()) open.pop_back();
        if (c == '.' && in_key) ++dots;
        if (c == '\n' || c == '=' || c == ',' || c == '[' || c == '{' || c == ']' || c == '}') dots = 0;
        if (c == '\n') in_key = open.empty();
        if (c == '=' || c == '}') in_key = false;
        if (c == '{' || c == ',') in_key = c == '{' || (!open.empty() && open.back() == '{');
        if (c == '[') in_key = in_key && open.size() <= 2 && open.find('{') == std::string::npos;  // [table], [[array]]
        if (static_cast<int>(open.size()) + dots > max_nesting_depth)
            throw input_error(source + ":" + std::to_string(line) +
                              ": lists, tables and dotted keys nested deeper than " +
                              std::to_string(max_nesting_depth) + " levels, the most a scene may nest");
        ++i;
    }
}

toml::value parse_toml(const std::string& text, const std::string& source) {
    check_scene_text(text, source);  // before toml11, which reads nesting by recursion
    try {
        std::istringstream in(text);
        return toml::parse(in, source);
    } catch (const std::exception& e) {  // toml11's syntax errors carry the line
        throw input_error("malformed scene " + source + ":\n" + e.what());
    }
}

// A list of numbers, or {log = [lo, hi], n = N}, {lin = [lo, hi], n = N}, {sqrt = [lo, hi], n = N} or
// {cbrt = [lo, hi], n = N}.
std::vector<double> read_axis(StrictTable& t, const std::string& key) {
    const toml::value& v = t.value(key);
    if (v.is_array()) {
        std::vector<double> out = t.reals(key);
        if (out.empty()) t.fail(key, "is an empty list");
        return out;
    }
    if (!v.is_table())
        t.fail(key,
               "must be a list of numbers, {log = [lo, hi], n = N}, {lin = [lo, hi], n = N}, {sqrt = [lo, hi], "
               "n = N} or {cbrt = [lo, hi], n = N}, got " +
                   describe_toml(v));
    StrictTable spacing = t.table(key, {"log", "lin", "sqrt", "cbrt", "n"});
    const int given =
        int{spacing.has("log")} + int{spacing.has("lin")} + int{spacing.has("sqrt")} + int{spacing.has("cbrt")};
    if (given != 1)
        t.fail(key, "must hold exactly one of log = [lo, hi], lin = [lo, hi], sqrt = [lo, hi] and cbrt = [lo, hi]");
    const Spacing kind = spacing.has("log") ? Spacing::log
        : spacing.has("sqrt")               ? Spacing::sqrt
        : spacing.has("cbrt")               ? Spacing::cbrt
                                            : Spacing::lin;
    const std::string range_key = kind == Spacing::log ? "log"
        : kind == Spacing::sqrt                        ? "sqrt"
        : kind == Spacing::cbrt                        ? "cbrt"
                                                       : "lin";
    const std::vector<double> range = spacing.reals(range_key);
    const std::int64_t n = spacing.integer("n", 2, max_axis_points);
    spacing.done();
    if (range.size() != 2 || !std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[0] < range[1]) ||
        (kind == Spacing::log && !(range[0] > 0)) ||
        ((kind == Spacing::sqrt || kind == Spacing::cbrt) && !(range[0] >= 0)))
        spacing.fail(range_key,
                     "must be [lo, hi], finite, with lo < hi (and lo > 0 for log, lo >= 0 for sqrt and cbrt)");
    return spaced(range[0], range[1], n, kind);
}

}  // namespace smithlab::scene
