// Cell files and fit cache files carry a CRC-64 of their contents (smithlab/util/checksum.hpp): a file with a value
// edited, a bit flipped, two rows swapped or `nan` written in is traced again, the run names it on stderr once, and
// the outputs are the bytes of a clean run.
#include <catch2/catch.hpp>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"
#include "smithlab/util/checksum.hpp"

using namespace smithlab_test;
using Catch::Matchers::Contains;

namespace {

fs::path fresh(const std::string& name) {
    const fs::path d = scratch() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The start of the line after the n-th newline (n = 0: the first line).
std::size_t line_start(const std::string& text, int n) {
    std::size_t at = 0;
    for (int i = 0; i < n; ++i) at = text.find('\n', at) + 1;
    return at;
}

// The damages: each keeps the file's layout (the same lines, numbers where numbers were) but for the bit flip.
struct Damage {
    const char* name;
    std::function<std::string(std::string)> apply;
};

// A digit of the value after the `field`-th comma of line `line`, incremented (9 -> 0): still a number.
std::string edit_digit(std::string text, int line, int field) {
    std::size_t at = line_start(text, line);
    for (int i = 0; i < field; ++i) at = text.find(',', at) + 1;
    while (!(text[at] >= '1' && text[at] <= '9')) ++at;
    text[at] = text[at] == '9' ? '0' : static_cast<char>(text[at] + 1);
    return text;
}

// The value after the `field`-th comma of line `line` replaced by nan.
std::string write_nan(std::string text, int line, int field) {
    std::size_t at = line_start(text, line);
    for (int i = 0; i < field; ++i) at = text.find(',', at) + 1;
    const std::size_t end = text.find_first_of(",\n", at);
    return text.replace(at, end - at, "nan");
}

std::string swap_lines(std::string text, int a) {
    const std::size_t s = line_start(text, a), m = line_start(text, a + 1), e = line_start(text, a + 2);
    return text.substr(0, s) + text.substr(m, e - m) + text.substr(s, m - s) + text.substr(e);
}

std::string flip_bit(std::string text) {
    text[text.size() / 2] = static_cast<char>(text[text.size() / 2] ^ 0x04);
    return text;
}

// Cell files: line 4 is the first "a," row (specular at order 1), line 5 the second (diffuse); field 8 its value.
const std::vector<Damage> cell_damages{
    {"a digit edited", [](std::string t) { return edit_digit(std::move(t), 5, 8); }},
    {"a bit flipped", flip_bit},
    {"two rows swapped", [](std::string t) { return swap_lines(std::move(t), 4); }},
    {"nan written in", [](std::string t) { return write_nan(std::move(t), 5, 8); }},
};

// Cache files: line 2 is the first point; field 4 its s0 (the first moment), field 5 s1.
const std::vector<Damage> cache_damages{
    {"a digit edited", [](std::string t) { return edit_digit(std::move(t), 2, 5); }},
    {"a bit flipped", flip_bit},
    {"two rows swapped", [](std::string t) { return swap_lines(std::move(t), 2); }},
    {"nan written in", [](std::string t) { return write_nan(std::move(t), 2, 5); }},
};

const std::string trace_scene =
    "materials = [\"lambert(albedo=0.8)\"]\n[walks]\nn = 2000\nseed = 3\n[grid]\n"
    "alpha = [0.3, 0.6]\ntheta_i = [0, 40]\n[[ndf]]\nfamily = \"ggx\"\n";

const std::string fit_scene = R"TOML(title = "damaged"
material = "lambert(albedo=1)"
albedos = [0.5, 1.0]
models = ["lambert", "fujii"]
[[ndf]]
family = "ggx"
[training]
alpha = [0.2, 0.8]
theta = [0.0, 40.0, 70.0]
phi = [0.0, 180.0]
walks = 300
[validation]
points = 4
walks = 300
albedo_theta = [0.0, 60.0]
albedo_walks = 300
)TOML";

std::string trace_cmd(const fs::path& d, const std::string& out) {
    return "trace '" + (d / "s.toml").string() + "' --threads 2 --output '" + (d / out).string() + "'";
}

std::string fit_cmd(const fs::path& d, const std::string& out) {
    return "fit '" + (d / "s.toml").string() + "' --threads 2 --output '" + (d / out).string() + "'";
}

}  // namespace

TEST_CASE("checksum: CRC-64/XZ of the standard check string, and a sealed text unsealed only when untouched",
          "[checks][damaged]") {
    // The published check value of CRC-64/XZ (the CRC RevEng catalogue): crc("123456789").
    CHECK(smithlab::util::crc64("123456789") == 0x995DC9BBDF1939FAULL);
    const std::string body = "key,k\nrow,1\n";
    const std::string sealed = body + smithlab::util::checksum_line(body);
    REQUIRE(smithlab::util::unseal(sealed).has_value());
    CHECK(*smithlab::util::unseal(sealed) == body);
    CHECK_FALSE(smithlab::util::unseal(body).has_value());
    std::string edited = sealed;
    edited[9] = '2';
    CHECK_FALSE(smithlab::util::unseal(edited).has_value());
    CHECK_FALSE(smithlab::util::unseal(sealed.substr(0, sealed.size() - 1)).has_value());
}

TEST_CASE("trace: a cell file with a value edited, a bit flipped, rows swapped or nan written in is traced again",
          "[checks][damaged][walk]") {
    const fs::path d = fresh("damaged_cells");
    write(d / "s.toml", trace_scene);
    REQUIRE(run(trace_cmd(d, "clean")).rc == 0);
    const std::string clean = slurp(d / "clean" / "albedo.csv");
    REQUIRE(run(trace_cmd(d, "out")).rc == 0);
    const fs::path cell = d / "out" / "cells" / "cell-000001.csv";
    for (const Damage& damage : cell_damages) {
        INFO(damage.name);
        const std::string text = slurp(cell);
        REQUIRE(text.rfind("key,", 0) == 0);
        const std::string damaged = damage.apply(text);
        REQUIRE(damaged != text);
        write(cell, damaged);
        const Run r = run(trace_cmd(d, "out"));
        INFO(r.err);
        REQUIRE(r.rc == 0);
        CHECK_THAT(r.out, Contains("traced 1\nreused 3\n"));
        CHECK_THAT(r.err, Contains("trace: cell 1: checksum mismatch, traced again\n"));
        CHECK(count(r.err, "checksum mismatch") == 1);
        CHECK(slurp(d / "out" / "albedo.csv") == clean);
        CHECK(slurp(cell) == text);
    }
    // Whole files under another key (the scene changed) are traced again without a word.
    std::string reseeded = trace_scene;
    reseeded.replace(reseeded.find("seed = 3"), 8, "seed = 4");
    write(d / "s.toml", reseeded);
    const Run other = run(trace_cmd(d, "out"));
    REQUIRE(other.rc == 0);
    CHECK_THAT(other.out, Contains("traced 4\nreused 0\n"));
    CHECK_THAT(other.err, !Contains("checksum"));
    fs::remove_all(d);
}

TEST_CASE("fit: a cache file with a value edited, a bit flipped, rows swapped or nan written in is traced again",
          "[checks][damaged][fit]") {
    const fs::path d = fresh("damaged_cache");
    write(d / "s.toml", fit_scene);
    REQUIRE(run(fit_cmd(d, "clean")).rc == 0);
    REQUIRE(run(fit_cmd(d, "out")).rc == 0);
    fs::path group;
    for (const auto& e : fs::recursive_directory_iterator(d / "out" / "cache"))
        if (e.path().filename() == "training-0.csv") group = e.path();
    REQUIRE(!group.empty());
    const std::vector<std::string> outputs{"errors.csv", "constants.csv", "validation.csv"};
    for (const Damage& damage : cache_damages) {
        INFO(damage.name);
        const std::string text = slurp(group);
        REQUIRE(text.rfind("key,", 0) == 0);
        const std::string damaged = damage.apply(text);
        REQUIRE(damaged != text);
        write(group, damaged);
        const Run r = run(fit_cmd(d, "out"));
        INFO(r.err);
        REQUIRE(r.rc == 0);
        CHECK_THAT(r.out, Contains("traced 9"));  // the group: alpha 0.2, 3 pairs with a 0 + 3 pairs x 2 phi
        CHECK_THAT(r.err, Contains("fit: cache " + group.string() + ": checksum mismatch, traced again\n"));
        CHECK(count(r.err, "checksum mismatch") == 1);
        for (const std::string& f : outputs) CHECK(slurp(d / "out" / f) == slurp(d / "clean" / f));
        CHECK(slurp(group) == text);
    }
    fs::remove_all(d);
}
