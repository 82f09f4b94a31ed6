// Fuzz test of everything smithlab parses: NDF specs, CSV, TOML scenes and option values.
//
// The contract: every input ends as exit 0 with a finite answer (no NaN in stdout or in any file
// written), or as exit 2 with a message on stderr and nothing written. Never a crash (a signal, a sanitizer
// report), a hang (each run is wrapped in `timeout 30`, 120 in the sanitized build; 124 fails), exit 1 (reserved
// for a failed check) or an "internal error". Where the input is known to lie outside the accepted domain (a NaN, an
// option value out of its range, an unknown scene key, a wrong TOML type, a duplicate CSV column) it must be
// refused: exit 2.
//
// Why a seeded generator in Catch2 and not clang's libFuzzer (Debian's clang + libFuzzer would do both parts):
// - it runs in the ordinary suite, on every CI run, under both builds (Release and ASan+UBSan) with the one
//   compiler the project uses (g++; libFuzzer needs clang and its own main, i.e. a separate build of everything);
// - it is reproducible: the same seed gives the same inputs on every machine (std::mt19937_64 is fully
//   specified; no std:: distribution is used), and a failure prints the exact command, and the file it read;
// - its time is bounded by a count, not by a budget of seconds, so a CI run is as long as the last one;
// - most of the surface is the executable (option parsing, CSV and scene files, output files), which libFuzzer
//   drives only in-process; here the library parsers run in-process (thousands of inputs) and the CLI as a
//   subprocess (a few hundred runs), each judged by the same contract a user sees.
// What it gives up is coverage guidance: the generators are grammar-aware instead (valid inputs with extreme
// values, then structural and byte-level mutations of them), which is what reaches past the first parse error.
//
// The seed is printed; SMITHLAB_FUZZ_SEED=N runs other inputs, SMITHLAB_FUZZ_SCALE=K runs K times as many of each
// class (e.g. SMITHLAB_FUZZ_SEED=$RANDOM SMITHLAB_FUZZ_SCALE=20 build/tests/test_fuzz for a long local run).
//
// Kept out of the generators on purpose, because they are legitimate work rather than bad input: sample counts and
// grid sizes in the expensive-but-valid range (--n from 1e5 to 1e9, scene counts from 1e5 up to the largest
// accepted), `check --all`, a report without a scene file, and any output path outside the test's scratch directory
// (`--output /dev/null` as root is a known way to replace /dev/null). Nothing else is excluded for failing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/gtr/registry.hpp"
#include "smithlab/samplers.hpp"
#include "smithlab/smith.hpp"

// Every run of the executable goes through cli_run.hpp's run(), under `timeout`: run() quotes SMITHLAB_EXE as one
// shell word, so the word is closed after `timeout` and reopened before the executable's path. -k: a run that
// ignores SIGTERM is killed 5 s later (exit 137).
static const std::string smithlab_fuzz_exe = SMITHLAB_EXE;
#undef SMITHLAB_EXE
#define SMITHLAB_EXE (std::string("timeout' -k 5 " SMITHLAB_FUZZ_HANG_SECONDS " '") + smithlab_fuzz_exe)
#include "cli_run.hpp"

using namespace smithlab_test;

namespace {

// ---- the seed, the counts, the generator -------------------------------------------------------------------------

std::uint64_t base_seed() {
    if (const char* s = std::getenv("SMITHLAB_FUZZ_SEED"); s && *s) return std::strtoull(s, nullptr, 0);
    return 20261201;
}

std::size_t count(std::size_t n) {
    double k = 1.0;
    if (const char* s = std::getenv("SMITHLAB_FUZZ_SCALE"); s && *s) k = std::strtod(s, nullptr);
    if (!(k > 0.0)) k = 1.0;
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(double(n) * k)));
}

std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

struct Gen {
    std::mt19937_64 rng;
    explicit Gen(std::uint64_t seed) : rng(seed) {}
    std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(rng() % n) : 0; }
    double unit() { return double(rng() >> 11) * 0x1p-53; }
    bool chance(double p) { return unit() < p; }
    double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
    template <class T>
    const T& pick(const std::vector<T>& v) {
        return v[below(v.size())];
    }
};

// One generator per class, seeded from the run's seed and the class name; the seed is printed.
Gen start(const std::string& cls, std::size_t n) {
    const std::uint64_t seed = base_seed();
    std::cout << "test_fuzz [" << cls << "]: seed " << seed << " (SMITHLAB_FUZZ_SEED), " << n
              << " inputs (SMITHLAB_FUZZ_SCALE)" << std::endl;
    return Gen(seed ^ fnv1a(cls));
}

std::string g17(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string shell_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// ---- numbers as text ---------------------------------------------------------------------------------------------

const std::vector<std::string> special_numbers = {"0",
                                                  "-0",
                                                  "1",
                                                  "-1",
                                                  "0.5",
                                                  "2",
                                                  "3",
                                                  "10",
                                                  "1e-300",
                                                  "-1e-300",
                                                  "4.9e-324",
                                                  "1e-320",
                                                  "2.2250738585072014e-308",
                                                  "1.7976931348623157e308",
                                                  "1e308",
                                                  "-1e308",
                                                  "1e309",
                                                  "-1e309",
                                                  "1e154",
                                                  "1e-154",
                                                  "1e15",
                                                  "1e18",
                                                  "1e50",
                                                  "1e-50",
                                                  "1e-15",
                                                  "1e-5",
                                                  "1e5",
                                                  "1e10",
                                                  "1e-10",
                                                  "inf",
                                                  "-inf",
                                                  "+inf",
                                                  "INF",
                                                  "Infinity",
                                                  "-Infinity",
                                                  "nan",
                                                  "NaN",
                                                  "-nan",
                                                  "+nan",
                                                  "NAN",
                                                  "nan(0x1)",
                                                  "",
                                                  " ",
                                                  "1 ",
                                                  " 1",
                                                  "\t1",
                                                  "1,5",
                                                  "1.5.5",
                                                  "0x1p-3",
                                                  "0x10",
                                                  "0X1P+4",
                                                  "1e",
                                                  "e5",
                                                  "--1",
                                                  "+-1",
                                                  "abc",
                                                  "1abc",
                                                  "1e5x",
                                                  "0.",
                                                  ".",
                                                  "-",
                                                  "+",
                                                  "1_000",
                                                  "\xef\xbc\x91",
                                                  "18446744073709551615",
                                                  "18446744073709551616",
                                                  "-18446744073709551616",
                                                  "9223372036854775807",
                                                  "9223372036854775808",
                                                  "-9223372036854775808",
                                                  "-9223372036854775809",
                                                  "4294967295",
                                                  "4294967296",
                                                  "4294967298",
                                                  "1000000001",
                                                  "99999999999999999999999999",
                                                  "3.0",
                                                  "1e3",
                                                  "001",
                                                  "1/2",
                                                  "true",
                                                  "'",
                                                  "\"",
                                                  "\\",
                                                  "$(id)",
                                                  "`id`",
                                                  "*",
                                                  "%s%n",
                                                  "\xff\xfe",
                                                  "89.999999999999",
                                                  "90",
                                                  "179.999999",
                                                  "180",
                                                  "360",
                                                  "-90",
                                                  "0.1",
                                                  "0.10000000001",
                                                  "1e-16"};

std::string random_number(Gen& g) {
    std::string s;
    if (g.chance(0.3)) s += g.pick<std::string>({"-", "+", ""});
    const std::size_t digits = 1 + g.below(g.chance(0.1) ? 400 : 20);
    for (std::size_t i = 0; i < digits; ++i) s += char('0' + g.below(10));
    if (g.chance(0.5)) {
        s += '.';
        for (std::size_t i = g.below(10); i > 0; --i) s += char('0' + g.below(10));
    }
    if (g.chance(0.6))
        s += g.pick<std::string>({"e", "E", "e-", "e+"}) + std::to_string(g.below(g.chance(0.5) ? 30 : 400));
    return s;
}

std::string random_bytes(Gen& g, std::size_t max_len) {
    static const std::string alphabet =
        "0123456789.eE+-_ ,;:=()[]{}\"'\\/abcdfinxyzAZ\t\n\r#*$`!\x01\x7f\x80\xc3\xa9\xff";
    std::string s;
    for (std::size_t i = 1 + g.below(max_len); i > 0; --i) s += alphabet[g.below(alphabet.size())];
    return s;
}

// A value for a numeric option or field: half the time a typical valid one (from `valid`), else an extreme, junk,
// a random decimal of any size, or random bytes.
template <class Valid>
std::string number_text(Gen& g, Valid valid, double p_valid = 0.5) {
    if (g.chance(p_valid)) return valid(g);
    const double u = g.unit();
    if (u < 0.6) return g.pick(special_numbers);
    if (u < 0.9) return random_number(g);
    return random_bytes(g, 8);
}

// strtod over the whole text: the value a strict parser would see, or nullopt for text that is not one number.
std::optional<double> strict_number(const std::string& t) {
    if (t.empty()) return std::nullopt;  // leading blanks are strtod's to skip: " 1" may be taken as 1
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (end != t.c_str() + t.size()) return std::nullopt;
    return v;
}

bool is_nan_word(const std::string& t) {
    const auto v = strict_number(t);
    return v && std::isnan(*v);
}

// ---- NDF specs ---------------------------------------------------------------------------------------------------

std::string valid_alpha(Gen& g) { return g17(g.chance(0.8) ? g.log_uniform(1e-5, 1.0) : g.log_uniform(1e-60, 1e60)); }
std::string valid_gamma(Gen& g) {
    if (g.chance(0.3)) return std::to_string(g.below(35));
    return g17(g.chance(0.8) ? 20.0 * g.unit() : g.log_uniform(1e-12, 1e20));
}
std::string valid_blinn_n(Gen& g) {
    return g17(g.chance(0.8) ? g.log_uniform(0.1, 2000.0) : g.log_uniform(1e-20, 1e20));
}

// Each value of a spec is a typical valid one 80% of the time, so that a spec with two values reaches the NDF.
std::string value_for(Gen& g, const std::string& key) {
    if (key == "gamma") return number_text(g, valid_gamma, 0.8);
    if (key == "n") return number_text(g, valid_blinn_n, 0.8);
    return number_text(g, valid_alpha, 0.8);
}

// A spec from the grammar name(key=value, ...), with its pieces chosen to be mostly right.
std::string structured_spec(Gen& g) {
    static const std::vector<std::string> good_names = {"ggx", "beckmann", "blinn", "gtr", "gtr", "gtr"};
    static const std::vector<std::string> bad_names = {"GTR", "Ggx", "phong", "", "_", "gtr gtr", "1gtr", "ggx2"};
    static const std::vector<std::string> other_keys = {"alpha", "gamma", "n",   "beta",  "ALPHA",
                                                        "",      "1a",    "a b", "alpha "};
    // Each piece is right most of the time, so that one or two wrong ones are found in a spec that is otherwise fine.
    const std::string name = g.chance(0.9) ? g.pick(good_names) : g.pick(bad_names);
    std::vector<std::string> keys = name == "gtr" ? std::vector<std::string>{"alpha", "gamma"}
        : name == "blinn"                         ? std::vector<std::string>{"n"}
        : name == "ggx" || name == "beckmann"     ? std::vector<std::string>{"alpha"}
                                                  : std::vector<std::string>{g.pick(other_keys)};
    if (g.chance(0.05)) keys.push_back(g.pick(other_keys));           // an extra or duplicate key
    if (g.chance(0.05) && keys.size() > 1) keys.erase(keys.begin());  // a missing one
    if (g.chance(0.2)) std::swap(keys.front(), keys.back());
    std::string s = g.chance(0.05) ? " " + name : name;
    if (g.chance(0.05)) return s;  // no parentheses
    s += g.chance(0.1) ? " (" : "(";
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (i) s += g.chance(0.9) ? ", " : g.pick<std::string>({",", " , ", ";", ",,", ""});
        s += keys[i] + (g.chance(0.9) ? "=" : g.pick<std::string>({" = ", "==", "", ":"})) + value_for(g, keys[i]);
    }
    if (g.chance(0.05)) s += ",";
    s += g.chance(0.95) ? ")" : g.pick<std::string>({"", "))", ") x", "("});
    return s;
}

std::string mutate_bytes(Gen& g, std::string s) {
    static const std::string alphabet = "(),= \t\n\"'\\.eE-+0123456789abcdefghijklmnopqrstuvwxyz_\x7f\x80\xff";
    for (std::size_t k = 1 + g.below(3); k > 0; --k) {
        const std::size_t at = g.below(s.size() + 1);
        switch (g.below(5)) {
            case 0:
                if (at < s.size()) s.erase(at, 1);
                break;
            case 1:
                s.insert(at, 1, alphabet[g.below(alphabet.size())]);
                break;
            case 2:
                if (at < s.size()) s[at] = alphabet[g.below(alphabet.size())];
                break;
            case 3:
                s.resize(at);
                break;
            case 4:
                s.insert(at, s.substr(g.below(s.size() + 1), g.below(12)));
                break;
        }
    }
    return s;
}

std::string spec_text(Gen& g) {
    std::string s = structured_spec(g);
    if (g.chance(0.2)) s = mutate_bytes(g, s);
    return s;
}

const smithlab::NdfRegistry& registry() {
    static const smithlab::NdfRegistry r = smithlab::builtin_registry();
    return r;
}

bool spec_accepted(const std::string& spec) {
    try {
        registry().make(spec);
        return true;
    } catch (const smithlab::input_error&) {
        return false;
    }
}

// ---- judging a run of the executable ------------------------------------------------------------------------------

bool has_nan(const std::string& text) {
    static const std::regex nan_token("(^|[^A-Za-z_])[-+]?nan([^A-Za-z_]|$)", std::regex::icase);
    return std::regex_search(text, nan_token);
}

std::string first_lines(const std::string& s, std::size_t n = 6) {
    std::size_t at = 0;
    for (std::size_t k = 0; k < n && at != std::string::npos; ++k) at = s.find('\n', at ? at + 1 : 0);
    return at == std::string::npos ? s : s.substr(0, at) + "\n...";
}

// The contract every run keeps; `must_refuse` names why the input has to end in exit 2 (empty: either is fine).
// Returns what went wrong, or "".
std::string judge(const Run& r, const std::string& must_refuse) {
    if (r.rc == 124 || r.rc == 137)
        return "hang: killed by `timeout " SMITHLAB_FUZZ_HANG_SECONDS "` (exit " + std::to_string(r.rc) + ")";
    if (r.err.find("Sanitizer") != std::string::npos || r.err.find("runtime error:") != std::string::npos)
        return "sanitizer report (exit " + std::to_string(r.rc) + "):\n" + first_lines(r.err, 12);
    if (r.rc < 0 || r.rc > 128)
        return "crash: exit " + std::to_string(r.rc) + " (signal " + std::to_string(r.rc - 128) + ")";
    if (r.err.find("internal error") != std::string::npos)
        return "internal error (exit " + std::to_string(r.rc) + "): " + first_lines(r.err);
    if (r.rc != 0 && r.rc != 2) return "exit " + std::to_string(r.rc) + ": " + first_lines(r.err);
    if (r.rc == 2 && r.err.find_first_not_of(" \t\r\n") == std::string::npos) return "exit 2 without a message";
    if (has_nan(r.out)) return "NaN in stdout (exit " + std::to_string(r.rc) + "):\n" + first_lines(r.out);
    if (r.rc == 0 && !must_refuse.empty()) return "accepted (exit 0) what must be refused: " + must_refuse;
    return "";
}

// Files left behind in dir that an atomic write must never leave: *.partial and other temporaries.
std::string debris(const fs::path& dir) {
    std::string found;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec))
        if (it->path().filename().string().find(".partial") != std::string::npos)
            found += std::string(" ") + it->path().string();
    return found.empty() ? "" : std::string("temporary files left behind:") + found;
}

// A class of CLI inputs: judges each run, reports each failure with its reproducer, and gives up on the class after
// three hangs (each costs 30 s; the ones reported are enough to reproduce).
struct Campaign {
    explicit Campaign(std::string name) : cls(std::move(name)) {}
    std::string cls;
    std::size_t runs = 0, failures = 0, hangs = 0;
    std::set<std::string> kinds;  // distinct failure kinds, for the summary

    std::map<int, std::size_t> exits;  // exit code -> runs

    bool give_up() const { return hangs >= 3; }
    void record(const std::string& args, const Run& r, std::string why, const std::string& context = "") {
        ++runs;
        ++exits[r.rc];
        if (std::getenv("SMITHLAB_FUZZ_VERBOSE")) std::cout << "  exit " << r.rc << ": smithlab " << args << std::endl;
        if (why.empty()) return;
        ++failures;
        if (why.rfind("hang", 0) == 0) ++hangs;
        kinds.insert(why.substr(0, why.find_first_of(":(\n")));
        if (failures <= 25)
            FAIL_CHECK("[" << cls << "] " << why << "\n  reproducer: smithlab " << args << "\n  exit " << r.rc
                           << "\n  stderr: " << first_lines(r.err) << (context.empty() ? "" : "\n" + context));
    }
    ~Campaign() {
        std::cout << "test_fuzz [" << cls << "]: " << runs << " runs (";
        for (const auto& [rc, k] : exits) std::cout << (rc == exits.begin()->first ? "" : ", ") << k << " exit " << rc;
        std::cout << "), " << failures << " failures";
        for (const auto& k : kinds) std::cout << " | " << k;
        std::cout << (give_up() ? " (stopped after 3 hangs)" : "") << std::endl;
        INFO("[" << cls << "]: no input was accepted: the generator no longer reaches past the parser");
        CHECK(exits.count(0) == 1);
    }
};

fs::path fresh_dir(const std::string& name) {
    const fs::path d = scratch() / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

}  // namespace

// ---- in-process: the library's parsers ------------------------------------------------------------------------------

TEST_CASE("fuzz: NDF specs, in-process (parse_spec, builtin_registry().make, one Lambda)", "[fuzz]") {
    const std::size_t n = count(6000);
    Gen g = start("specs", n);
    std::size_t accepted = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::string text = g.chance(0.05) ? random_bytes(g, 40) : spec_text(g);
        const std::string mu_text = number_text(g, [](Gen& h) { return g17(h.log_uniform(1e-13, 1e13)); });
        INFO("input " << i << ": spec '" << text << "'");
        try {
            const smithlab::NdfSpec spec = smithlab::parse_spec(text);
            CHECK(smithlab::is_spec_name(spec.name));
            // The canonical text parses back to itself.
            const std::string canon = smithlab::format_spec(spec);
            CHECK(smithlab::format_spec(smithlab::parse_spec(canon)) == canon);
        } catch (const smithlab::input_error& e) {
            CHECK(std::string(e.what()).size() > 0);
        } catch (const std::exception& e) {
            FAIL_CHECK("parse_spec threw " << e.what() << " (not input_error)");
        }
        try {
            const smithlab::AnyNdf ndf = registry().make(text);
            ++accepted;
            CHECK(registry().make(ndf.spec()).spec() == ndf.spec());
            for (const std::string& key : registry().find(ndf.family())->parameters)
                CHECK(std::isfinite(ndf.param(key)));
            // An accepted NDF answers: Lambda at one mu (the auto route: closed form, or 1D quadrature) is a number
            // >= 0, or the point is refused.
            const auto mu = strict_number(mu_text);
            if (!mu || std::isnan(*mu)) continue;
            INFO("accepted as " << ndf.spec() << "; Lambda at mu = " << g17(*mu) << " (smithlab eval --ndf '"
                                << ndf.spec() << "' --mu " << g17(*mu) << ")");
            try {
                const double L = smithlab::Lambda(ndf, std::abs(*mu));
                CHECK(!std::isnan(L));
                CHECK(L >= 0.0);
            } catch (const smithlab::input_error&) {
            } catch (const std::exception& e) {
                FAIL_CHECK("Lambda threw " << e.what() << " (not input_error)");
            }
        } catch (const smithlab::input_error& e) {
            CHECK(std::string(e.what()).size() > 0);
        } catch (const std::exception& e) {
            FAIL_CHECK("registry().make threw " << e.what() << " (not input_error)");
        }
    }
    std::cout << "test_fuzz [specs]: " << accepted << " of " << n << " accepted" << std::endl;
    CHECK(accepted > n / 10);  // the generator reaches past the parser
}

namespace {

const std::vector<std::string> csv_field_pool = {"ndf",
                                                 "mu",
                                                 "id",
                                                 "",
                                                 " ",
                                                 "ggx(alpha=0.5)",
                                                 "gtr(alpha=0.3, gamma=1.5)",
                                                 "1",
                                                 "0.25",
                                                 "nan",
                                                 "a,b",
                                                 "a\"b",
                                                 "\"",
                                                 "\"\"",
                                                 "line\nbreak",
                                                 "cr\rhere",
                                                 "crlf\r\nhere",
                                                 "\xc3\xa9",
                                                 "\xff",
                                                 std::string("nul\0in", 6),
                                                 "x y"};

std::string csv_field_text(Gen& g) { return g.chance(0.7) ? g.pick(csv_field_pool) : random_bytes(g, 12); }

}  // namespace

TEST_CASE("fuzz: CSV reader, in-process (read_csv, write_csv_record round trip)", "[fuzz][csv]") {
    const std::size_t n = count(4000);
    Gen g = start("csv", n);
    for (std::size_t i = 0; i < n; ++i) {
        // Records written by write_csv_record read back as themselves, at the lines they were written on.
        std::vector<std::vector<std::string>> records;
        for (std::size_t r = 1 + g.below(6); r > 0; --r) {
            std::vector<std::string> fields;
            for (std::size_t f = 1 + g.below(5); f > 0; --f) fields.push_back(csv_field_text(g));
            if (fields.size() == 1 && fields[0].empty()) fields.push_back("");  // a lone empty field is a blank line
            records.push_back(fields);
        }
        std::ostringstream out;
        std::vector<std::size_t> lines;
        std::size_t line = 1;
        for (const auto& rec : records) {
            lines.push_back(line);
            std::ostringstream one;
            smithlab::write_csv_record(one, rec);
            const std::string s = one.str();
            line += std::count(s.begin(), s.end(), '\n');
            out << s;
        }
        std::string text = out.str();
        if (g.chance(0.3)) {  // CRLF line ends, outside quoted fields too: records stay the same
            std::string crlf;
            bool quoted = false;
            for (char c : text) {
                if (c == '"') quoted = !quoted;
                if (c == '\n' && !quoted) crlf += '\r';
                crlf += c;
            }
            text = crlf;
        }
        INFO("input " << i << ": " << ::Catch::Detail::stringify(text));
        {
            std::istringstream in(text);
            const auto back = smithlab::read_csv(in);
            REQUIRE(back.size() == records.size());
            for (std::size_t k = 0; k < back.size(); ++k) {
                CHECK(back[k].error.empty());
                CHECK(back[k].fields == records[k]);
                CHECK(back[k].line == lines[k]);
            }
        }
        // Mutated text: any bytes read without a throw, as records with lines that only grow.
        const std::string bad = mutate_bytes(g, text);
        INFO("mutated: " << ::Catch::Detail::stringify(bad));
        try {
            std::istringstream in(bad);
            std::size_t last = 0;
            for (const auto& rec : smithlab::read_csv(in)) {
                CHECK(rec.line > last);
                last = rec.line;
                CHECK((!rec.error.empty() || !rec.fields.empty()));
            }
        } catch (const std::exception& e) {
            FAIL_CHECK("read_csv threw " << e.what());
        }
    }
}

// ---- the executable: option values ----------------------------------------------------------------------------

namespace {

const std::vector<std::string>& method_names() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v = {"auto", "closed", "spline", "quadrature", "quadrature2d", "fixed"};
        const smithlab::VariantRegistry variants = smithlab::builtin_variants();
        for (const auto& variant : variants.list()) v.push_back(variant.name);
        return v;
    }();
    return names;
}

// A CLI run gets each option's value valid this often: most runs then carry one or two hostile values and reach
// past the parser to the code that uses the others.
constexpr double cli_valid = 0.75;

std::string valid_mu(Gen& g) {
    if (g.chance(0.1)) return g.pick<std::string>({"0", "inf", "-inf", "-0"});
    return (g.chance(0.2) ? "-" : "") + g17(g.chance(0.7) ? g.log_uniform(1e-4, 1e4) : g.log_uniform(1e-300, 1e300));
}

std::string valid_tolerance(Gen& g) { return g17(g.log_uniform(1e-15, 0.1)); }

// Why a numeric text must be refused by an option with the accepted range [lo, hi] (hi_open: [lo, hi)).
std::string out_of_range(const std::string& what, const std::string& t, double lo, double hi, bool hi_open = false) {
    if (t.empty()) return what + " is empty";
    if (is_nan_word(t)) return what + " is NaN";
    const auto v = strict_number(t);
    if (v && (*v < lo || *v > hi || (hi_open && *v >= hi))) return what + " = " + t + " is outside its range";
    return "";
}

// --seed is an unsigned 64-bit integer: a negative one, one past 2^64 - 1, a fraction or nothing must be refused.
std::string bad_seed(const std::string& t) {
    if (t.empty()) return "--seed is empty";
    if (std::regex_match(t, std::regex("-0*[1-9][0-9]*"))) return "--seed is negative";
    if (std::regex_match(t, std::regex("\\+?[0-9]+"))) {
        const std::string digits =
            t.substr(t.find_first_not_of("+0") == std::string::npos ? t.size() : t.find_first_not_of("+0"));
        if (digits.size() > 20 || (digits.size() == 20 && digits > "18446744073709551615"))
            return "--seed is above 2^64 - 1";
    }
    if (std::regex_match(t, std::regex("[-+]?[0-9]*\\.[0-9]*[1-9][0-9]*"))) return "--seed is not an integer";
    if (is_nan_word(t)) return "--seed is NaN";
    return "";
}

std::string bad_n(const std::string& t) {
    if (t.empty()) return "--n is empty";
    if (std::regex_match(t, std::regex("-[0-9]+|\\+?0+"))) return "--n is not positive";
    if (std::regex_match(t, std::regex("\\+?[0-9]+")) && (t.size() > 12 || std::stoll(t) > 1000000000LL))
        return "--n is above 1e9";
    return "";
}

// Sample counts: small valid ones, or values around and beyond the limits (never the expensive valid range).
std::string n_text(Gen& g) {
    const double u = g.unit();
    if (u < cli_valid) return std::to_string(1 + g.below(200));
    if (u < 0.9)
        return g.pick<std::string>({"0", "-1", "-0", "1000000001", "1e3", "1.5", "", "nan", "inf", "1e10",
                                    "9223372036854775807", "9223372036854775808", "18446744073709551617", " 5", "5 ",
                                    "0x10", "abc", "+7", "10.0"});
    std::string t = random_number(g);
    const auto v = strict_number(t);
    if (v && *v >= 1e5 && *v <= 1e9) return "100";  // the expensive valid range: not a parser input
    return t;
}

std::string seed_text(Gen& g) {
    if (g.chance(0.5)) return std::to_string(g.rng());
    return number_text(
        g, [](Gen& h) { return std::to_string(h.below(1000)); }, cli_valid);
}

}  // namespace

TEST_CASE("fuzz: eval options (--ndf, --mu, --method, --backend, --tolerance, --downward)", "[fuzz][cli]") {
    const std::size_t n = count(160);
    Gen g = start("eval", n);
    Campaign c("eval");
    const fs::path d = fresh_dir("fuzz_eval");
    for (std::size_t i = 0; i < n && !c.give_up(); ++i) {
        const std::string spec = g.chance(0.9) ? structured_spec(g) : spec_text(g);
        const std::string mu = number_text(g, valid_mu, cli_valid);
        std::string args = "eval --ndf " + shell_quote(spec) + " --mu " + shell_quote(mu);
        std::string refuse;
        if (!spec_accepted(spec)) refuse = "the spec is refused by builtin_registry().make()";
        if (!strict_number(mu) || is_nan_word(mu)) refuse = "--mu is not a number or NaN";
        if (g.chance(0.6)) {
            const std::string m = g.chance(0.95) ? g.pick(method_names()) : random_bytes(g, 10);
            args += " --method " + shell_quote(m);
            if (std::find(method_names().begin(), method_names().end(), m) == method_names().end())
                refuse = "unknown --method";
        }
        if (g.chance(0.3)) {
            const std::string b =
                g.chance(cli_valid) ? g.pick<std::string>({"boost", "gsl"}) : g.pick<std::string>({"GSL", "", "qags"});
            args += " --backend " + shell_quote(b);
            if (b != "boost" && b != "gsl") refuse = "unknown --backend";
        }
        if (g.chance(0.4)) {
            const std::string t = number_text(g, valid_tolerance, cli_valid);
            args += " --tolerance " + shell_quote(t);
            if (const std::string why = out_of_range("--tolerance", t, 1e-15, 0.1); !why.empty()) refuse = why;
        }
        if (g.chance(0.15)) {
            const std::string w =
                g.chance(cli_valid) ? g.pick<std::string>({"smith", "hammon"}) : g.pick<std::string>({"Smith", ""});
            args += " --downward " + shell_quote(w);
            if (w != "smith" && w != "hammon") refuse = "unknown --downward";
        }
        const Run r = run(args);
        std::string why = judge(r, refuse);
        if (why.empty() && r.rc == 0) {
            // lambda and g1 are numbers, g1 in [0, 1].
            const auto at = r.out.find("\ng1      ");
            const double g1 = at == std::string::npos ? -1.0 : std::strtod(r.out.c_str() + at + 9, nullptr);
            if (!(g1 >= 0.0 && g1 <= 1.0)) why = "exit 0 without a g1 in [0, 1]:\n" + r.out;
        }
        if (why.empty()) why = debris(d);
        c.record(args, r, why);
    }
}

TEST_CASE("fuzz: sample options (--ndf, --sampler, --theta-i, --n, --seed, --output)", "[fuzz][cli]") {
    const std::size_t n = count(100);
    Gen g = start("sample", n);
    Campaign c("sample");
    const fs::path d = fresh_dir("fuzz_sample");
    const std::vector<smithlab::SamplerInfo> samplers = smithlab::builtin_samplers();
    for (std::size_t i = 0; i < n && !c.give_up(); ++i) {
        const std::string spec = g.chance(0.9) ? structured_spec(g) : spec_text(g);
        std::string refuse = spec_accepted(spec) ? "" : "the spec is refused by builtin_registry().make()";
        const bool known_sampler = g.chance(0.9);
        const smithlab::SamplerInfo& s = samplers[g.below(samplers.size())];
        const std::string sampler = known_sampler ? s.name : g.pick<std::string>({"", "VNDF", "dcos ", "x"});
        if (!known_sampler) refuse = "unknown --sampler";
        std::string args = "sample --ndf " + shell_quote(spec) + " --sampler " + shell_quote(sampler);
        const std::string theta = number_text(
            g, [](Gen& h) { return g17(h.chance(0.7) ? 89.0 * h.unit() : 180.0 * h.unit()); }, cli_valid);
        if (g.chance(0.8)) {
            args += " --theta-i " + shell_quote(theta);
            const bool upper = known_sampler && s.incidence == smithlab::SamplerInfo::Incidence::upper;
            if (const std::string why = out_of_range("--theta-i", theta, 0.0, upper ? 90.0 : 180.0, true); !why.empty())
                refuse = why;
        }
        const std::string count_text = n_text(g);
        const bool with_n = g.chance(0.9);
        if (with_n) {
            args += " --n " + shell_quote(count_text);
            if (const std::string why = bad_n(count_text); !why.empty()) refuse = why;
        }
        if (g.chance(0.6)) {
            const std::string seed = seed_text(g);
            args += " --seed " + shell_quote(seed);
            if (const std::string why = bad_seed(seed); !why.empty()) refuse = why;
        }
        const bool to_file = g.chance(0.3);
        const fs::path out = d / ("m" + std::to_string(i) + ".csv");
        if (to_file) args += " --output " + shell_quote(out.string());
        const Run r = run(args);
        std::string why = judge(r, refuse);
        if (why.empty() && r.rc == 0) {
            // Rows x,y,z,pdf: finite, a unit normal, pdf >= 0; as many as asked for.
            std::istringstream rows(to_file ? slurp(out) : r.out);
            std::string line;
            std::getline(rows, line);
            std::size_t k = 0;
            while (why.empty() && std::getline(rows, line)) {
                ++k;
                double x, y, z, pdf;
                if (std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &x, &y, &z, &pdf) != 4 || !std::isfinite(x) ||
                    !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(pdf) || pdf < 0.0 ||
                    std::abs(x * x + y * y + z * z - 1.0) > 1e-9)
                    why = "row " + std::to_string(k) + " is not a finite unit normal with a pdf >= 0: " + line;
            }
            const auto v = strict_number(count_text);
            if (why.empty() && with_n && v && std::regex_match(count_text, std::regex("[0-9]+")) &&
                k != std::size_t(*v))
                why = "asked for " + count_text + " samples, got " + std::to_string(k);
        }
        if (why.empty() && r.rc == 2 && fs::exists(out)) why = "exit 2 but the output file was written";
        if (why.empty()) why = debris(d);
        c.record(args, r, why);
        fs::remove(out);
    }
}

// ---- the executable: CSV files --------------------------------------------------------------------------------------

TEST_CASE("fuzz: eval --input on generated CSV files", "[fuzz][cli][csv]") {
    const std::size_t n = count(100);
    Gen g = start("eval-csv", n);
    Campaign c("eval-csv");
    const fs::path d = fresh_dir("fuzz_csv");
    for (std::size_t i = 0; i < n && !c.give_up(); ++i) {
        std::string refuse;
        // The header: ndf and mu among pass-through columns, sometimes missing, duplicated or clashing.
        std::vector<std::string> header = {"ndf", "mu"};
        if (g.chance(0.5))
            header.insert(header.begin() + g.below(3), g.pick<std::string>({"id", "note", "x y", "a,b", "\"q\""}));
        if (g.chance(0.1)) {
            header.push_back(g.pick<std::string>({"ndf", "mu"}));
            refuse = std::string("a duplicate '") + header.back() + "' column";
        }
        if (g.chance(0.05)) {
            header.erase(header.begin() + g.below(header.size()));
            if (std::count(header.begin(), header.end(), "ndf") == 0 ||
                std::count(header.begin(), header.end(), "mu") == 0)
                refuse = "no 'ndf' or 'mu' column";
        }
        if (g.chance(0.05)) {
            header.push_back(g.pick<std::string>({"lambda", "g1"}));
            refuse = std::string("a '") + header.back() + "' column, which eval writes";
        }
        const auto col = [&](const std::string& name) {
            return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
        };
        std::ostringstream text;
        smithlab::write_csv_record(text, header);
        const std::size_t rows = g.below(8);
        std::vector<std::string> specs;
        for (std::size_t k = 0; k < 2; ++k) specs.push_back(structured_spec(g));
        for (std::size_t k = 0; k < rows; ++k) {
            std::vector<std::string> row(header.size());
            for (std::size_t f = 0; f < row.size(); ++f)
                row[f] = g.chance(0.8) ? std::string("p") + std::to_string(k) : csv_field_text(g);
            if (col("ndf") < row.size()) {
                row[col("ndf")] = g.chance(0.8) ? g.pick(specs) : spec_text(g);
                if (!spec_accepted(row[col("ndf")])) refuse = "row " + std::to_string(k + 2) + ": a refused spec";
            }
            if (col("mu") < row.size()) {
                row[col("mu")] = number_text(g, valid_mu, cli_valid);
                if (!strict_number(row[col("mu")]) || is_nan_word(row[col("mu")]))
                    refuse = "row " + std::to_string(k + 2) + ": mu not a number or NaN";
            }
            if (g.chance(0.05)) {
                row.push_back("extra");
                refuse = "a row with a field too many";
            }
            smithlab::write_csv_record(text, row);
        }
        std::string csv = text.str();
        if (g.chance(0.15)) {
            csv = mutate_bytes(g, csv);
            refuse.clear();  // a mutated file may or may not be valid
        }
        const fs::path in = d / ("in" + std::to_string(i) + ".csv");
        const fs::path out = d / ("out" + std::to_string(i) + ".csv");
        write(in, csv);
        std::string args = "eval --input " + shell_quote(in.string());
        const double where = g.unit();
        fs::path written = out;
        if (where < 0.6) {
            args += " --output " + shell_quote(out.string());
        } else if (where < 0.65) {
            args += " --output " + shell_quote(d.string());  // an existing directory
            refuse = "--output is a directory";
            written.clear();
        } else if (where < 0.7) {
            args += " --output " + shell_quote(in.string());  // the input itself
            refuse = "--output is the input file";
            written.clear();
        } else if (where < 0.73) {
            args = "eval --input " + shell_quote(d.string()) + " --output " + shell_quote(out.string());
            refuse = "--input is a directory";
        } else {
            written.clear();  // stdout
        }
        if (g.chance(0.3)) {
            const std::string m = g.pick(method_names());
            args += " --method " + shell_quote(m);
        }
        const Run r = run(args);
        std::string why = judge(r, refuse);
        const std::string result =
            written.empty() ? (r.rc == 0 ? r.out : "") : (fs::exists(written) ? slurp(written) : "");
        if (why.empty() && r.rc == 0) {
            if (!written.empty() && !fs::exists(written)) why = "exit 0 but no output file";
            std::istringstream res(result);
            const auto recs = smithlab::read_csv(res);
            if (why.empty() && recs.empty()) why = "exit 0 with an empty result";
            for (std::size_t k = 1; why.empty() && k < recs.size(); ++k) {
                const auto& f = recs[k].fields;
                const double g1 = f.empty() ? -1.0 : std::strtod(f.back().c_str(), nullptr);
                if (f.size() < 2 || has_nan(f[f.size() - 2]) || !(g1 >= 0.0 && g1 <= 1.0))
                    why = "result row " + std::to_string(k) + " has no finite lambda and g1 in [0, 1]";
            }
        }
        if (why.empty() && r.rc == 2) {
            if (!written.empty() && fs::exists(written)) why = "exit 2 but the output file was written";
            else if (slurp(in) != csv) why = "the input file was changed";
        }
        if (why.empty()) why = debris(d);
        c.record(args, r, why, "  " + in.filename().string() + ": " + ::Catch::Detail::stringify(csv));
        fs::remove(in);
        fs::remove(out);
    }
}

// ---- the executable: scenes -----------------------------------------------------------------------------------------

namespace {

// Tiny valid scenes (cheap variants, a few points, 10 ms of timing): every key a mutation can reach.
const std::vector<std::string> base_scenes = {
    "title = \"small\"\n"
    "[grid]\nalpha = [0.1, 0.5]\nmu = { log = [0.01, 100.0], n = 3 }\n"
    "[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5, 3.0]\n"
    "[variants]\ninclude = [\"dimov-spline\", \"schlick-ggx\"]\nexclude = [\"q2d-*\"]\n"
    "[g2]\ninclude = [\"g2-hammon-lerp\"]\nfamilies = [\"ggx\"]\nmu = [0.5, 2.0]\n"
    "[timing]\nmin_time = 0.01\n",
    "[grid]\nalpha = { lin = [0.2, 0.6], n = 2 }\nmu = [0.5, 1.0, 4.0]\n"
    "[[ndf]]\nfamily = \"ggx\"\n"
    "[[ndf]]\nfamily = \"beckmann\"\n"
    "[variants]\ninclude = [\"schlick-ggx\", \"beckmann-rational\", \"closed-form\"]\n"
    "[timing]\nmin_time = 0.01\n",
    "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"schlick-ggx\"]\n"
    "[timing]\nmin_time = 0.01\n"
    "[sampling]\nfamilies = [\"ggx\"]\nalpha = [0.5]\ntheta_o = 30\nsamples = 200\nseed = 3\n",
};

// The type each key's value must have, and for counts their range.
enum class Kind { string, real, count, seed, list, axis, other };
Kind kind_of(const std::string& key) {
    if (key == "title" || key == "family") return Kind::string;
    if (key == "min_time" || key == "theta_o") return Kind::real;
    if (key == "n" || key == "samples") return Kind::count;
    if (key == "seed") return Kind::seed;
    if (key == "include" || key == "exclude" || key == "families") return Kind::list;
    if (key == "alpha" || key == "mu" || key == "gamma") return Kind::axis;
    return Kind::other;
}

const std::set<std::string> known_keys = {"title",
                                          "grid",
                                          "alpha",
                                          "mu",
                                          "ndf",
                                          "family",
                                          "gamma",
                                          "variants",
                                          "include",
                                          "exclude",
                                          "g2",
                                          "families",
                                          "timing",
                                          "min_time",
                                          "sampling",
                                          "theta_o",
                                          "samples",
                                          "seed",
                                          "figures",
                                          "pareto",
                                          "error_maps",
                                          "dimov_heightfields",
                                          "dimov_spline_mean",
                                          "dimov_gamma4_vs_10",
                                          "log",
                                          "lin",
                                          "n"};

struct Mutated {
    std::string text, refuse, what;
};

std::vector<std::string> split_lines(const std::string& s) {
    std::vector<std::string> lines;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
}

// A typo of a key: a character dropped, doubled, swapped or changed; never a known key.
std::string typo(Gen& g, std::string key) {
    const std::string original = key;
    while (key == original || known_keys.count(key)) {
        key = original;
        const std::size_t at = g.below(key.size());
        switch (g.below(4)) {
            case 0:
                key.erase(at, 1);
                break;
            case 1:
                key.insert(at, 1, key[at]);
                break;
            case 2:
                if (at + 1 < key.size()) std::swap(key[at], key[at + 1]);
                else key += 'e';
                break;
            case 3:
                key[at] = char('a' + g.below(26));
                break;
        }
        if (key.empty()) key = original + "x";
    }
    return key;
}

// A value of the wrong type for `kind`, or an extreme of the right one; refuse says whether it must be refused.
std::pair<std::string, std::string> scene_value(Gen& g, Kind kind) {
    const std::vector<std::pair<std::string, int>> pool = {
        // text, type: 0 string, 1 integer, 2 float, 3 bool, 4 array, 5 table, 6 date
        {"\"x\"", 0},
        {"\"\"", 0},
        {"\"0.5\"", 0},
        {"-1", 1},
        {"0", 1},
        {"1", 1},
        {"2", 1},
        {"3", 1},
        {"7", 1},
        {"100", 1},
        {"4294967298", 1},
        {"9223372036854775807", 1},
        {"-9223372036854775808", 1},
        {"0.5", 2},
        {"3.5", 2},
        {"1000.5", 2},
        {"1e-300", 2},
        {"1e300", 2},
        {"-0.5", 2},
        {"nan", 2},
        {"inf", 2},
        {"-inf", 2},
        {"true", 3},
        {"[]", 4},
        {"[1.0, \"a\"]", 4},
        {"[0.5, 0.5]", 4},
        {"[1e-300, 1e300]", 4},
        {"[nan]", 4},
        {"[[1.0]]", 4},
        {"{}", 5},
        {"{ log = [0.5, 0.1], n = 3 }", 5},
        {"{ lin = [0.1, 0.5], n = 4294967298 }", 5},
        {"{ log = [1e-300, 1e300], n = 5 }", 5},
        {"{ lin = [0.1, 0.5] }", 5},
        {"1979-05-27", 6}};
    const auto& [text, type] = g.pick(pool);
    const std::string name = "value " + text;
    std::string refuse;
    const auto refuse_if = [&](bool bad, const std::string& why) {
        if (bad && refuse.empty()) refuse = name + ": " + why;
    };
    refuse_if(text.find("nan") != std::string::npos, "NaN");
    switch (kind) {
        case Kind::string:
            refuse_if(type != 0, "not a string");
            break;
        case Kind::real:
            refuse_if(type != 1 && type != 2, "not a number");
            break;  // an integer may stand for a real
        case Kind::count:
            refuse_if(type != 1, "not an integer");
            refuse_if(text[0] == '-' || text == "0" || text.size() >= 10, "outside any sensible count");
            break;
        case Kind::seed:
            refuse_if(type != 1, "not an integer");
            refuse_if(text[0] == '-', "a negative seed");
            break;
        case Kind::list:
            refuse_if(text != "[]", "not a list of strings");
            break;
        case Kind::axis:
            refuse_if(type != 4 && type != 5, "neither a list nor {log|lin = [lo, hi], n = N}");
            refuse_if(text == "[]" || text == "{}" || text.find('"') != std::string::npos ||
                          text.find("[[") != std::string::npos || text.find("[0.5, 0.1]") != std::string::npos ||
                          text.find("4294967298") != std::string::npos || text == "{ lin = [0.1, 0.5] }",
                      "an empty, malformed or reversed axis, or a count beyond any grid");
            break;
        case Kind::other:
            break;
    }
    return {text, refuse};
}

Mutated mutate_scene(Gen& g, const std::string& base) {
    std::vector<std::string> lines = split_lines(base);
    const auto key_lines = [&] {
        std::vector<std::size_t> v;
        for (std::size_t k = 0; k < lines.size(); ++k)
            if (lines[k].find(" = ") != std::string::npos) v.push_back(k);
        return v;
    }();
    const std::size_t at = g.pick(key_lines);
    const std::string key = lines[at].substr(0, lines[at].find(" = "));
    Mutated m;
    if (g.chance(0.3)) {  // a valid scene with extreme values on one axis: it must run right or be refused
        std::vector<std::size_t> axes;
        for (std::size_t k = 0; k < lines.size(); ++k)
            if (kind_of(lines[k].substr(0, lines[k].find(" = "))) == Kind::axis) axes.push_back(k);
        const std::size_t k = g.pick(axes);
        const std::string axis = lines[k].substr(0, lines[k].find(" = "));
        const std::vector<std::string> extremes = axis == "gamma"
            ? std::vector<std::string>{"0.0",  "1e-9", "0.999999999", "1.0",    "1.000000001",
                                       "19.7", "31.0", "32.5",        "1000.0", "1e15"}
            : axis == "mu"
            ? std::vector<std::string>{"1e-12", "1e-4", "0.5", "1e4", "1e12", "1e154", "1e-300", "1e300"}
            : std::vector<std::string>{"1e-4", "1e-3", "0.3", "0.999999", "1.0", "1e-15", "1e-50", "2.0", "1e10"};
        std::string v = "[" + g.pick(extremes);
        for (std::size_t j = g.below(3); j > 0; --j) v += ", " + g.pick(extremes);
        lines[k] = axis + " = " + v + "]";
        return {join_lines(lines), "", lines[k]};
    }
    switch (g.below(8)) {
        case 0: {  // a key misspelled
            const std::string t = typo(g, key);
            lines[at] = t + lines[at].substr(key.size());
            m = {join_lines(lines), "unknown key '" + t + "'", "key " + key + " -> " + t};
            break;
        }
        case 1: {  // a table name misspelled
            std::vector<std::size_t> tables;
            for (std::size_t k = 0; k < lines.size(); ++k)
                if (!lines[k].empty() && lines[k][0] == '[') tables.push_back(k);
            const std::size_t k = g.pick(tables);
            const std::size_t open = lines[k].find_first_not_of('['), close = lines[k].find(']');
            const std::string t = typo(g, lines[k].substr(open, close - open));
            lines[k] = lines[k].substr(0, open) + t + lines[k].substr(close);
            m = {join_lines(lines), "unknown table '" + t + "'", "table -> " + t};
            break;
        }
        case 2: {  // an unknown key added
            const std::string t = g.pick<std::string>({"gama", "exlude", "min_tme", "titel", "colour", "n_points"});
            lines.insert(lines.begin() + at + 1, t + " = 1");
            m = {join_lines(lines), "unknown key '" + t + "'", "added " + t};
            break;
        }
        case 3:
        case 4: {  // a value replaced
            const auto [value, refuse] = scene_value(g, kind_of(key));
            lines[at] = key + " = " + value;
            m = {join_lines(lines), refuse, key + " = " + value};
            break;
        }
        case 5: {  // a count of an axis, or the values of a list axis
            std::string& l = lines[at];
            const std::size_t p = l.find("n = ");
            if (p != std::string::npos) {
                const std::string v = g.pick<std::string>({"1", "0", "-3", "2", "4294967298", "3.5", "\"3\"", "1e5"});
                l = l.substr(0, p + 4) + v + " }";
                m = {join_lines(lines), v == "2" ? "" : "n = " + v + " is not a count >= 2 of a sensible grid",
                     "n = " + v};
            } else if (kind_of(key) == Kind::axis) {
                const std::string v =
                    g.pick<std::string>({"0.0", "-0.1", "1e-320", "1e308", "inf", "2.0", "0.9999999999999999"});
                lines[at] = key + " = [" + v + "]";
                const bool bad = key != "mu" && ((v == "0.0" && key == "alpha") || v == "-0.1" || v == "inf");
                m = {join_lines(lines), bad ? key + " = [" + v + "] is outside the NDF's parameter range" : "",
                     lines[at]};
            } else {
                const auto [value, refuse] = scene_value(g, kind_of(key));
                lines[at] = key + " = " + value;
                m = {join_lines(lines), refuse, key + " = " + value};
            }
            break;
        }
        case 6: {  // a line deleted or duplicated
            if (g.chance(0.5)) {
                m.what = "deleted: " + lines[at];
                lines.erase(lines.begin() + at);
                m.text = join_lines(lines);
            } else {
                m.what = "duplicated: " + lines[at];
                lines.insert(lines.begin() + at, lines[at]);
                m = {join_lines(lines), "a duplicate key", m.what};
            }
            break;
        }
        default: {  // bytes
            m = {mutate_bytes(g, join_lines(lines)), "", "byte mutation"};
            break;
        }
    }
    return m;
}

std::string nan_in_files(const fs::path& dir) {
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        const std::string ext = it->path().extension().string();
        if (it->is_regular_file() && (ext == ".md" || ext == ".csv" || ext == ".json") && has_nan(slurp(it->path())))
            return "NaN in " + it->path().string();
    }
    return "";
}

}  // namespace

TEST_CASE("fuzz: report SCENE on mutated tiny scenes", "[fuzz][cli][scene]") {
    const std::size_t n = count(60);
    Gen g = start("scenes", n);
    Campaign c("scenes");
    const fs::path d = fresh_dir("fuzz_scene");
    for (std::size_t i = 0; i < n && !c.give_up(); ++i) {
        const std::string& base = g.pick(base_scenes);
        const Mutated m = mutate_scene(g, base);
        const std::string name = "s" + std::to_string(i) + ".toml", out = "out" + std::to_string(i);
        write(d / name, m.text);
        const std::string args = report_args(d, name, out);
        const Run r = run(args);
        std::string why = judge(r, m.refuse);
        if (why.empty() && r.rc == 0) why = nan_in_files(d / out);
        if (why.empty() && r.rc == 2 && fs::exists(d / out)) why = "exit 2 but the output directory was written";
        if (why.empty()) why = debris(d);
        c.record(args, r, why, "  mutation: " + m.what + "\n  " + name + ":\n" + m.text);
        fs::remove_all(d / out);
        fs::remove(d / name);
    }
}

namespace {

// Tiny valid trace and fit scenes and a report scene with a [walk] (tens of walks: each runs in well under a second).
// Each has an alpha axis (mutate_scene picks one).
const std::vector<std::pair<std::string, std::string>> walk_scenes = {
    {"trace",
     "title = \"t\"\nmaterials = [\"mirror\", \"lambert(albedo=1)\"]\n"
     "[walks]\nn = 50\nseed = 3\nmax_order = 0\ndownward = \"smith\"\nhit_normal = \"visible\"\n"
     "[grid]\nalpha = [0.5]\ntheta_i = [0.0, 45.0]\nphi_i = [0.0]\n"
     "[[ndf]]\nfamily = \"gtr\"\ngamma = [1.5]\n"
     "[brdf]\ntheta_bins = 2\nphi_bins = 2\n"},
    {"trace",
     "materials = [\"dielectric(eta=1.5)\"]\n[walks]\nn = 50\n[grid]\nalpha = [0.3]\n"
     "theta_i = { lin = [0.0, 60.0], n = 2 }\n[[ndf]]\nfamily = \"ggx\"\n[[ndf]]\nspec = \"ggx(alpha=0.3)\"\n"},
    {"fit",
     "title = \"f\"\nmaterial = \"lambert(albedo=1)\"\nalbedos = [0.5, 1.0]\nmodels = [\"lambert\"]\nfloor = 0.02\n"
     "energy_bound = true\nseed = 2\nestimator = \"position_free\"\n"
     "[[ndf]]\nfamily = \"ggx\"\n"
     "[training]\nalpha = [0.3, 0.6]\ntheta = [0.0, 45.0]\nphi = [0.0]\nwalks = 100\n"
     "[validation]\npoints = 2\nwalks = 100\nalbedo_theta = [0.0]\nalbedo_walks = 100\n"
     "[compensation]\nalpha = [0.5]\nmu = 2\n"},
    {"report",
     "[grid]\nalpha = [0.5]\nmu = [1.0]\n[[ndf]]\nfamily = \"ggx\"\n[variants]\ninclude = [\"schlick-ggx\"]\n"
     "[timing]\nmin_time = 0.01\n"
     "[walk]\nmaterials = [\"mirror\"]\nalpha = [0.5]\ntheta_i = [45.0]\nwalks = 100\nseed = 1\n"
     "[[walk.ndf]]\nfamily = \"ggx\"\n"},
};

// A hostile value for any key: numbers past their types, deep nesting, text where a number goes. Each must be
// refused (exit 2) or read as what it is; a refusal names the file and line.
std::string hostile_value(Gen& g) {
    return g.pick<std::string>({"18446744073709551616", "0xffffffffffffffff", "-9223372036854775809", "1e400", "-1e400",
                                "1e-400", "[1e400]", "[1e-400, 0.5]", "5e-324", "[5e-324]",
                                std::string(200, '[') + std::string(200, ']'), "{ a = { b = { c = 1 } } }", "\"1e400\"",
                                "99999999999999999999", "0b11", "0o777", "1_000", "[[0.5], [0.5]]"});
}

}  // namespace

TEST_CASE("fuzz: trace and fit SCENE and the report's [walk] on mutated tiny scenes", "[fuzz][cli][scene]") {
    const std::size_t n = count(40);
    Gen g = start("walk scenes", n);
    Campaign c("walk scenes");
    const fs::path d = fresh_dir("fuzz_walk_scene");
    for (std::size_t i = 0; i < n && !c.give_up(); ++i) {
        const auto& [command, base] = g.pick(walk_scenes);
        Mutated m;
        if (g.chance(0.5)) {  // a hostile value on one key
            std::vector<std::string> lines = split_lines(base);
            std::vector<std::size_t> keys;
            for (std::size_t k = 0; k < lines.size(); ++k)
                if (lines[k].find(" = ") != std::string::npos) keys.push_back(k);
            const std::size_t at = g.pick(keys);
            const std::string key = lines[at].substr(0, lines[at].find(" = "));
            lines[at] = key + " = " + hostile_value(g);
            m = {join_lines(lines), "", lines[at]};
        } else {
            m = mutate_scene(g, base);
            m.refuse.clear();  // mutate_scene's expectations are the report's keys; here only the contract is judged
        }
        const std::string name = "w" + std::to_string(i) + ".toml", out = "out" + std::to_string(i);
        write(d / name, m.text);
        const std::string args = command == "report"
            ? report_args(d, name, out)
            : command + " '" + (d / name).string() + "' --output '" + (d / out).string() + "' --threads 1";
        const Run r = run(args);
        std::string why = judge(r, m.refuse);
        if (why.empty() && r.rc == 0) why = nan_in_files(d / out);
        // A trace refused for its capped walks keeps the cells it traced (OUT/cells, the resume files a killed run
        // leaves too) and says so; nothing else may be there.
        const bool kept_cells = r.err.find("the traced cells stay") != std::string::npos &&
            std::distance(fs::directory_iterator(d / out), fs::directory_iterator{}) == 1 &&
            fs::exists(d / out / "cells");
        if (why.empty() && r.rc == 2 && fs::exists(d / out) && !kept_cells)
            why = "exit 2 but the output directory was written";
        // A refusal that names the scene file names a line of it ("w3.toml:12: ..."). (An NDF's or material's values
        // are checked when the cells are prepared, after the read: those messages name the value, not the line.)
        if (const std::size_t at = r.err.find(name + ":"); why.empty() && r.rc == 2 && at != std::string::npos) {
            const std::size_t digit = at + name.size() + 1;
            const bool syntax = r.err.find("malformed scene") != std::string::npos;  // toml11's own line follows
            if (!syntax && (digit >= r.err.size() || !std::isdigit(static_cast<unsigned char>(r.err[digit]))))
                why = "refused naming the file without a line: " + r.err;
        }
        if (why.empty()) why = debris(d);
        c.record(args, r, why, "  mutation: " + m.what + "\n  " + name + ":\n" + m.text);
        fs::remove_all(d / out);
        fs::remove(d / name);
    }
}
