// A TOML table read strictly: the reader of every scene format (report, trace, fit) declares the
// keys each table may hold and reads each through a typed getter, so that nothing wrong is ignored:
//   - a key that is not declared is refused, naming it, the file and line, and the nearest declared key
//     ("scene.toml:7: unknown section 'timng' (did you mean 'timing'?)");
//   - a value of another type than the getter's is refused, naming the key, file:line and the expected type
//     (an integer is taken where a real is meant: min_time = 1 is 1.0; samples = 1000.5 is refused);
//   - integers are read as 64-bit and bounded by the caller ([lo, hi] in the message); an integer beyond 64 bits
//     and a real beyond the doubles (1e400, or 1e-400, which would read as 0) are refused "out of range";
//   - done() refuses a declared key that was given but never read (a reader that forgot one).
// Every refusal is an input_error whose message starts "FILE:LINE: ".
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <toml.hpp>
#include <vector>

namespace smithlab::scene {

class StrictTable {
public:
    // `table` (a TOML table) must outlive this reader. `path` names it in messages: "" for the document, "grid",
    // "grid.alpha". `source` is the file's name as the user gave it. Refuses any key of `table` not in `known`.
    StrictTable(const toml::value& table, std::string source, std::string path, std::vector<std::string> known);

    bool has(const std::string& key) const;

    // Required (refused when absent) and defaulted forms. Each marks the key read.
    std::string text(const std::string& key);
    std::string text(const std::string& key, const std::string& fallback);
    double real(const std::string& key);
    double real(const std::string& key, double fallback);
    std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi);
    std::int64_t integer(const std::string& key, std::int64_t lo, std::int64_t hi, std::int64_t fallback);
    bool flag(const std::string& key, bool fallback);
    std::vector<std::string> texts(const std::string& key);
    std::vector<std::string> texts(const std::string& key, const std::vector<std::string>& fallback);
    std::vector<double> reals(const std::string& key);

    // A sub-table ([grid], or an inline table { log = [lo, hi], n = N }) and an array of tables ([[ndf]]), read
    // strictly with their own keys. tables() of an absent key is empty.
    StrictTable table(const std::string& key, std::vector<std::string> known);
    std::optional<StrictTable> optional_table(const std::string& key, std::vector<std::string> known);
    std::vector<StrictTable> tables(const std::string& key, const std::vector<std::string>& known);

    // The value itself, for a key of several shapes (a list or a table); marks it read.
    const toml::value& value(const std::string& key);

    // "FILE:LINE: grid.mu" for a key of this table (the table's own line when the key is absent).
    std::string where(const std::string& key) const;
    // Throws input_error("FILE:LINE: grid.mu " + message).
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

    // Refuses a declared key that was given but not read.
    void done() const;

private:
    std::string name_of(const std::string& key) const;  // "grid.mu"
    const toml::value& need(const std::string& key);    // present, or refused as missing; marks read
    // A number of `key` (the value itself or an element of its list): one that toml11 clamped (an integer beyond
    // 64 bits, a real beyond the doubles or a nonzero real that would read as 0) is refused "out of range".
    std::int64_t integer_of(const toml::value& v, const std::string& key) const;
    double real_of(const toml::value& v, const std::string& key) const;
    void refuse_unknown_keys() const;

    const toml::value* table_;
    std::string source_, path_;
    std::vector<std::string> known_;
    std::set<std::string> read_;
};

// "an integer (5)", "a string (\"x\")", "a table": what a value is, for "must be X, got Y".
std::string describe_toml(const toml::value& v);

// Refuses a scene's text larger than max_scene_bytes or nesting lists and tables deeper than max_nesting_depth
// (scene/limits.hpp), naming SOURCE:LINE of the first level too deep; strings and comments are skipped.
void check_scene_text(const std::string& text, const std::string& source);

// A scene's text parsed as TOML after check_scene_text; a syntax error is an input_error "malformed scene SOURCE:"
// with toml11's line.
toml::value parse_toml(const std::string& text, const std::string& source);

// An axis of a scene, the one convention of every scene format: a list of numbers, or {log = [lo, hi], n = N}
// (N points evenly spaced in log), {lin = [lo, hi], n = N}, {sqrt = [lo, hi], n = N} (evenly spaced in the square
// root: alpha in perceptual roughness) or {cbrt = [lo, hi], n = N} (in the cube root), 2 <= N <= 1e7. An empty list
// is refused.
std::vector<double> read_axis(StrictTable& t, const std::string& key);

}  // namespace smithlab::scene
