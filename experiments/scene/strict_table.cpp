#include "scene/strict_table.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "scene/nearest_name.hpp"
#include "scene/spaced.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

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

}  // namespace

std::vector<double> spaced(double lo, double hi, std::int64_t n, bool log) {
    std::vector<double> out;
    for (std::int64_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(i) / static_cast<double>(n - 1);
        out.push_back(log ? lo * std::pow(hi / lo, t) : lo + t * (hi - lo));
    }
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

double StrictTable::real(const std::string& key) {
    const toml::value& v = need(key);
    if (v.is_integer()) return static_cast<double>(v.as_integer());
    if (!v.is_floating()) fail(key, "must be a number, got " + describe_toml(v));
    return v.as_floating();
}

double StrictTable::real(const std::string& key, double fallback) { return has(key) ? real(key) : fallback; }

std::int64_t StrictTable::integer(const std::string& key, std::int64_t lo, std::int64_t hi) {
    const toml::value& v = need(key);
    const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
    if (!v.is_integer()) fail(key, "must be an integer in " + range + ", got " + describe_toml(v));
    if (v.as_integer() < lo || v.as_integer() > hi)
        fail(key, "must be an integer in " + range + ", got " + std::to_string(v.as_integer()));
    return v.as_integer();
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
        if (x.is_integer()) out.push_back(static_cast<double>(x.as_integer()));
        else if (x.is_floating()) out.push_back(x.as_floating());
        else fail(key, "must be a list of numbers, got " + describe_toml(x) + " in it");
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

toml::value parse_toml(const std::string& text, const std::string& source) {
    try {
        std::istringstream in(text);
        return toml::parse(in, source);
    } catch (const std::exception& e) {  // toml11's syntax errors carry the line
        throw input_error("malformed scene " + source + ":\n" + e.what());
    }
}

// A list of numbers, or {log = [lo, hi], n = N}, or {lin = [lo, hi], n = N}.
std::vector<double> read_axis(StrictTable& t, const std::string& key) {
    const toml::value& v = t.value(key);
    if (v.is_array()) {
        std::vector<double> out = t.reals(key);
        if (out.empty()) t.fail(key, "is an empty list");
        return out;
    }
    if (!v.is_table())
        t.fail(
            key,
            "must be a list of numbers, {log = [lo, hi], n = N} or {lin = [lo, hi], n = N}, got " + describe_toml(v));
    StrictTable spacing = t.table(key, {"log", "lin", "n"});
    const bool log = spacing.has("log");
    if (log == spacing.has("lin")) t.fail(key, "must hold exactly one of log = [lo, hi] and lin = [lo, hi]");
    const std::string range_key = log ? "log" : "lin";
    const std::vector<double> range = spacing.reals(range_key);
    const std::int64_t n = spacing.integer("n", 2, max_axis_points);
    spacing.done();
    if (range.size() != 2 || !std::isfinite(range[0]) || !std::isfinite(range[1]) || !(range[0] < range[1]) ||
        (log && !(range[0] > 0)))
        spacing.fail(range_key, "must be [lo, hi], finite, with lo < hi (and lo > 0 for log)");
    return spaced(range[0], range[1], n, log);
}

}  // namespace smithlab::report
