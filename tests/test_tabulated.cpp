// The tabulated NDF (tabulated.hpp) against what it must reproduce: GGX, Beckmann and GTR at gamma = 1.5 sampled at
// irregular angles and read back from CSV give their own Lambda (closed forms; GTR's by quadrature, a route that never
// sees the table) to a bound per number of rows; the per-NDF checks pass; a walk on the table's microsurface gives the
// albedo of GGX's by scattering order; every refusal names the file, the line and the value; normalize rescales; the
// content hash follows the bytes, not the name; the example table in experiments/ndfs/ loads.
#include <algorithm>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <smithlab/tabulated.hpp>
#include <smithlab/walk/trace.hpp>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace {

using smithlab::TabulatedNdf;
namespace walk = smithlab::walk;
constexpr double pi = std::numbers::pi;

// A uniform double in [0, 1) from a 64-bit LCG (Knuth's MMIX constants): the same angles on every platform.
struct Lcg {
    std::uint64_t s;
    double operator()() {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(s >> 11) * 0x1p-53;
    }
};

// n angles from lo to hi degrees (both included), each inner one moved by up to +-35 % of the step.
std::vector<double> jittered_angles(int n, double lo, double hi, std::uint64_t seed) {
    Lcg g{seed};
    std::vector<double> a(n);
    const double h = (hi - lo) / (n - 1);
    for (int i = 0; i < n; ++i) a[i] = lo + i * h + (i == 0 || i == n - 1 ? 0.0 : 0.7 * (g() - 0.5) * h);
    return a;
}

// The CSV text of D at those angles (a column the reader ignores included), every double to 17 digits.
std::string csv_of(const std::vector<double>& theta_deg, const std::function<double(double)>& D) {
    std::string s = "theta_deg,D,note\n";
    for (double t : theta_deg)
        s += smithlab::format_g17(t) + "," + smithlab::format_g17(D(std::cos(t * pi / 180.0))) + ",x\n";
    return s;
}

// The message of the input_error f throws ("" when it throws none).
template <class F>
std::string refusal(F&& f) {
    try {
        f();
    } catch (const smithlab::input_error& e) {
        return e.what();
    }
    return "";
}

std::string refusal_of(const std::string& text, smithlab::TabulatedOptions opts = {}) {
    return refusal([&] { smithlab::tabulated_ndf_from_csv(text, "ndf.csv", opts); });
}

// A valid table: GGX(0.5) at 40 angles over [0, 85] degrees, one row a line after the header.
std::string ggx_table(double scale = 1.0) {
    const smithlab::Ggx g = smithlab::ggx(0.5);
    return csv_of(jittered_angles(40, 0.0, 85.0, 3), [&](double c) { return scale * g.D(c); });
}

}  // namespace

TEST_CASE("tabulated: Lambda of sampled GGX, Beckmann and GTR 1.5 against their own, by number of rows",
          "[tabulated][sweep]") {
    const smithlab::Ggx g01 = smithlab::ggx(0.1), g05 = smithlab::ggx(0.5);
    const smithlab::Beckmann b03 = smithlab::beckmann(0.3);
    const smithlab::Gtr gt = smithlab::gtr(0.3, 1.5);
    struct Case {
        const char* name;
        std::function<double(double)> D, Lambda;
    };
    const Case cases[] = {
        {"ggx(0.1)", [&](double c) { return g01.D(c); }, [&](double mu) { return g01.Lambda(mu); }},
        {"ggx(0.5)", [&](double c) { return g05.D(c); }, [&](double mu) { return g05.Lambda(mu); }},
        {"beckmann(0.3)", [&](double c) { return b03.D(c); }, [&](double mu) { return b03.Lambda(mu); }},
        {"gtr(0.3, 1.5)", [&](double c) { return gt.D(c); }, [&](double mu) { return smithlab::Lambda(gt, mu); }},
    };
    std::vector<double> mus;
    for (int i = 0; i <= 24; ++i) mus.push_back(std::pow(10.0, -2.0 + 4.0 * i / 24.0));
    // The worst relative error of Lambda over mu in [0.01, 100] where Lambda > 1e-12 (below, G1 = 1 to 1e-12 either
    // way: Beckmann's exp(-mu^2/alpha^2) leaves the table's range past mu ~ 1.6 at alpha 0.3, and its relative error
    // there is that of D where D ~ 1e-100), by rows and angular range. Measured (this case prints them); the bounds are
    // those, rounded up by about 1.5x. Rows to 85 degrees: the tail law past 85 (D linear in cos^2) leaves ~1e-4 at
    // mu > 10, where Lambda lives on slopes beyond tan 85 deg; to 89 the table itself.
    struct Sampling {
        int n;
        double lo, hi;
        double bound[4];  // per case
    };
    const Sampling samplings[] = {
        {60, 0.0, 85.0, {8e-4, 4.5e-4, 4.5e-5, 4e-4}}, {100, 0.0, 85.0, {6e-4, 3.5e-4, 2.5e-5, 3e-4}},
        {200, 0.0, 85.0, {4e-4, 2.2e-4, 8e-7, 2e-4}},  {60, 0.4, 89.0, {1.5e-4, 6e-6, 4.5e-5, 5e-6}},
        {100, 0.4, 89.0, {2.5e-5, 3e-6, 2e-5, 3e-6}},  {200, 0.4, 89.0, {2e-6, 1.1e-6, 9e-7, 1e-6}},
    };
    std::printf("tabulated NDF: worst relative error of Lambda over mu in [0.01, 100] (Lambda > 1e-12)\n");
    std::printf("%-14s %5s %12s %10s %8s %10s\n", "ndf", "rows", "degrees", "error", "at mu", "bound");
    for (std::size_t k = 0; k < std::size(cases); ++k) {
        const Case& cs = cases[k];
        std::vector<double> want;
        for (double mu : mus) want.push_back(cs.Lambda(mu));
        for (const Sampling& s : samplings) {
            const std::string text = csv_of(jittered_angles(s.n, s.lo, s.hi, 11 + s.n), cs.D);
            const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(text, "sampled.csv");
            REQUIRE(tab.points() == static_cast<std::size_t>(s.n));
            double worst = 0.0, at = 0.0;
            for (std::size_t j = 0; j < mus.size(); ++j) {
                const double got = smithlab::Lambda(tab, mus[j]);
                if (want[j] > 1e-12) {
                    const double e = std::abs(got / want[j] - 1.0);
                    if (e > worst) worst = e, at = mus[j];
                } else {
                    CHECK(std::abs(got - want[j]) <= 1e-12);
                }
            }
            std::printf("%-14s %5d %5.1f-%-5.1f %10.2e %8.3g %10.1e\n", cs.name, s.n, s.lo, s.hi, worst, at,
                        s.bound[k]);
            INFO(cs.name << ", " << s.n << " rows over [" << s.lo << ", " << s.hi << "] deg: worst " << worst
                         << " at mu " << at);
            CHECK(worst <= s.bound[k]);
        }
    }
}

TEST_CASE("tabulated: the per-NDF checks pass on a tabulated GGX", "[tabulated]") {
    const smithlab::Ggx g = smithlab::ggx(0.3);
    smithlab::TabulatedOptions opts;
    opts.normalize = true;  // the checks hold the area to 1e-8; the table's own is 1 + 4e-6
    const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(
        csv_of(jittered_angles(100, 0.0, 89.0, 5), [&](double c) { return g.D(c); }), "ggx.csv", opts);
    CHECK(std::abs(tab.normalization_factor() - 1.0) < 1e-4);
    // By GSL's adaptive Gauss-Kronrod: the interpolant's second derivative jumps at every row, which Boost's
    // tanh-sinh (made for analytic integrands) resolves only to ~1e-7 in the visible-area check, and its nested 2D
    // route takes minutes (tabulated.hpp, "Quadrature"). With GSL every residual is below 5e-9, in ~2 s.
    smithlab::CheckOptions co;
    co.backend = smithlab::Backend::gsl;
    for (const smithlab::CheckResult& r : smithlab::run_checks(tab, co)) {
        INFO(r.name << " " << r.where << ": " << r.value << " vs " << r.expected << " (residual " << r.residual()
                    << ")");
        CHECK(r.passed());
    }
}

TEST_CASE("tabulated: D and P22 are finite, >= 0, agree, and reproduce the rows", "[tabulated]") {
    const smithlab::Beckmann b = smithlab::beckmann(0.3);  // rows past ~83 degrees are 0: the pieces linear in D
    const std::vector<double> th = jittered_angles(60, 0.0, 89.0, 9);
    for (const std::string& text : {csv_of(th, [&](double c) { return b.D(c); }), ggx_table()}) {
        const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(text, "t.csv");
        for (int i = 0; i <= 4000; ++i) {
            const double c = i == 0 ? 1e-300 : i == 4000 ? 1.0 : std::pow(10.0, -12.0 * (1.0 - i / 4000.0));
            const double d = tab.D(c);
            INFO("cos " << c << ": D " << d);
            REQUIRE(std::isfinite(d));
            REQUIRE(d >= 0.0);
            const double r2 = (1.0 - c) * (1.0 + c) / (c * c), p = tab.slope_density(r2);
            REQUIRE(std::isfinite(p));
            REQUIRE(p >= 0.0);
            // theta from cos (D) and from tan^2 (P22) differ by rounding: relative 1e-16 times |d ln D / d theta|, up
            // to ~4000 for Beckmann(0.3) at 80 degrees.
            if (c > 1e-60) CHECK(std::abs(p - d * c * c * c * c) <= 1e-10 * d * c * c * c * c + 1e-300);
        }
        CHECK(tab.slope_density(INFINITY) == 0.0);
        CHECK(tab.slope_density(1e300) >= 0.0);
        CHECK(tab.D(0.0) == 0.0);
        CHECK(tab.D(-0.5) == 0.0);
        CHECK(std::isnan(tab.D(NAN)));
        CHECK(std::isnan(tab.slope_density(NAN)));
    }
    // At the rows' own angles the interpolant is the row, divided by the table's projected area (here 1 - 7e-8).
    const smithlab::Ggx g = smithlab::ggx(0.5);
    const std::vector<double> a = jittered_angles(40, 0.0, 85.0, 3);
    const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(ggx_table(), "t.csv");
    for (double t : a)
        CHECK(tab.D(std::cos(t * pi / 180.0)) ==
              Approx(g.D(std::cos(t * pi / 180.0)) * tab.normalization_factor()).epsilon(1e-12));
    CHECK(tab.theta_min_deg() == 0.0);
    CHECK(tab.theta_max_deg() == Approx(85.0).epsilon(1e-14));
    CHECK(tab.points() == 40);
    // The tail: D linear in cos^2 to the horizon; GGX's D(90 deg) = alpha^2 / pi.
    CHECK(tab.horizon_D() == Approx(0.25 / pi).epsilon(2e-3));
    CHECK(tab.D(1e-200) == Approx(tab.horizon_D()).epsilon(1e-12));
}

TEST_CASE("tabulated: a cos_theta column, a byte order mark, comments, CRLF and a first angle above 0", "[tabulated]") {
    const smithlab::Ggx g = smithlab::ggx(0.4);
    const std::vector<double> th = jittered_angles(80, 0.5, 88.0, 21);
    std::string text = "\xEF\xBB\xBF# GGX(0.4), by cos theta, after a UTF-8 byte order mark\r\nD,cos_theta\r\n";
    for (double t : th) {
        const double c = std::cos(t * pi / 180.0);
        text += smithlab::format_g17(g.D(c)) + "," + smithlab::format_g17(c) + "\r\n";
        if (t > 40.0 && t < 42.0) text += "# a comment between rows, with a \"quote and, a comma\r\n";
    }
    const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(text, "cos.csv");
    CHECK(tab.points() == 80);
    CHECK(tab.theta_min_deg() == Approx(0.5).epsilon(1e-12));
    for (double mu : {0.05, 0.5, 5.0}) CHECK(smithlab::Lambda(tab, mu) == Approx(g.Lambda(mu)).epsilon(2e-4));
    // Below the first row, ln D is even in theta: D at the pole within the lobe's curvature of GGX's.
    CHECK(tab.D(1.0) == Approx(g.D(1.0)).epsilon(1e-4));
    // A bad row after the comments is named by its line in the file.
    std::string bad = "# one\n# two\ntheta_deg,D\n0,1\n10,0.5\n# three\n20,-0.3\n30,0.1\n";
    const std::string m = refusal_of(bad);
    CHECK(m == "ndf.csv:7: D must be finite and >= 0, got -0.3");
}

TEST_CASE("tabulated: every refusal names the file, the line and the value", "[tabulated]") {
    const std::string h = "theta_deg,D\n";
    struct Bad {
        std::string text, want;
    };
    const Bad bad[] = {
        {"", "ndf.csv: no header"},
        {"theta_deg,X\n0,1\n", "ndf.csv:1: the header has no 'D' column (columns: 'theta_deg', 'X')"},
        {"angle,D\n0,1\n", "ndf.csv:1: the header has no 'theta_deg' or 'cos_theta' column (columns: 'angle', 'D')"},
        {"theta_deg,D,D\n0,1,1\n", "ndf.csv:1: the header has two 'D' columns"},
        {"theta_deg,cos_theta,D\n0,1,1\n", "ndf.csv:1: the header has both 'theta_deg' and 'cos_theta' columns"},
        {h + "0,1\n5,abc\n", "ndf.csv:3: D is not a number: 'abc'"},
        {h + "0,1\nfive,1\n", "ndf.csv:3: theta_deg is not a number: 'five'"},
        {h + "0,1\n5,inf\n", "ndf.csv:3: D must be finite and >= 0, got inf"},
        {h + "0,1\n5,nan\n", "ndf.csv:3: D must be finite and >= 0, got nan"},
        {h + "0,1\n5,0.5\n10,0.2\n15,0.1\n20,0.05\n25,0.02\n30,-0.3\n",
         "ndf.csv:8: D must be finite and >= 0, got -0.3"},
        {h + "0,1\n5,0.5\n5,0.4\n", "ndf.csv:4: theta_deg must increase from row to row, got 5 after 5 (line 3)"},
        {h + "0,1\n5,0.5\n4.9,0.4\n", "ndf.csv:4: theta_deg must increase from row to row, got 4.9 after 5 (line 3)"},
        {"cos_theta,D\n1,1\n0.9,0.5\n0.95,0.4\n",
         "ndf.csv:4: cos_theta must decrease from row to row (theta_m increasing), got 0.95 after 0.9 (line 3)"},
        {h + "0,1\n45,0.5\n90,0.4\n", "ndf.csv:4: theta_deg must be in [0, 90), got 90"},
        {h + "-1,1\n45,0.5\n", "ndf.csv:2: theta_deg must be in [0, 90), got -1"},
        {"cos_theta,D\n1,1\n0.5,0.5\n0,0.4\n", "ndf.csv:4: cos_theta must be in (0, 1], got 0"},
        {"cos_theta,D\n1.5,1\n", "ndf.csv:2: cos_theta must be in (0, 1], got 1.5"},
        {h + "0,1\n5\n", "ndf.csv:3: expected 2 fields, got 1"},
        {h + "0,1\n5,\"0.5\"x\n", "ndf.csv:3: characters after a closing quote"},
        {h + "0,0.3\n45,0.1\n", "ndf.csv:3: the table ends after 2 data rows; the interpolation needs at least 3"},
        {h, "ndf.csv:1: the table ends after 0 data rows; the interpolation needs at least 3"},
    };
    for (const Bad& b : bad) {
        const std::string m = refusal_of(b.text);
        INFO("text:\n" << b.text << "\nmessage: " << m);
        CHECK(m.rfind(b.want, 0) == 0);
    }
    // The normalization: a GGX scaled by 1.3 is refused, naming its area and the rows' lines.
    const std::string m = refusal_of(ggx_table(1.3));
    INFO(m);
    CHECK(m.rfind("ndf.csv: the projected area of D", 0) == 0);
    CHECK(m.find("must be within 0.01 of 1, got 1.29999") != std::string::npos);
    CHECK(m.find("lines 2-41") != std::string::npos);
    // A file that is not there, or a directory.
    CHECK(refusal([] { smithlab::read_tabulated_ndf("/nonexistent/ndf.csv"); }) ==
          "tabulated ndf: cannot open '/nonexistent/ndf.csv': No such file or directory");
    CHECK(refusal([] {
              smithlab::read_tabulated_ndf(std::filesystem::temp_directory_path());
          }).find("is a directory") != std::string::npos);
}

TEST_CASE("tabulated: a binary table's bytes reach the message escaped, UTF-8 kept", "[tabulated]") {
    // ESC, BEL, NUL and 0xFF in a field: as \xNN, and the NUL does not cut the message short.
    std::string text = "theta_deg,D\n0,1\n5,\x1b[31m\x07\xff";
    text.push_back('\0');
    text += "x\n";
    const std::string m = refusal_of(text);
    CHECK(m == "ndf.csv:3: D is not a number: '\\x1b[31m\\x07\\xff\\x00x'");
    // A header in another script stays readable; a lone continuation byte and an overlong form do not pass.
    CHECK(refusal_of("\xce\xb8_deg,D\n0,1\n").find("(columns: '\xce\xb8_deg', 'D')") != std::string::npos);
    CHECK(smithlab::printable("\x80 \xc0\xaf \xed\xa0\x80 \xf4\x90\x80\x80 \xe2\x82\xac\t\\") ==
          "\\x80 \\xc0\\xaf \\xed\\xa0\\x80 \\xf4\\x90\\x80\\x80 \xe2\x82\xac\t\\");
}

TEST_CASE("tabulated: a device, a FIFO and a file past the cap are refused before they are read", "[tabulated]") {
    namespace fs = std::filesystem;
    // /dev/zero would be read without end, a FIFO with no writer would block in open.
    CHECK(refusal([] { smithlab::read_tabulated_ndf("/dev/zero"); }) ==
          "tabulated ndf: '/dev/zero' is not a regular file (a FIFO, a device or a socket): give a CSV file");
    const fs::path dir = fs::temp_directory_path() / ("smithlab_tabulated_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path fifo = dir / "fifo.csv";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK(refusal([&] { smithlab::read_tabulated_ndf(fifo); }).find("is not a regular file") != std::string::npos);
    // A sparse file one byte past the cap.
    const fs::path big = dir / "big.csv";
    std::ofstream(big).put('\n');
    fs::resize_file(big, smithlab::tabulated_max_bytes + 1);
    CHECK(refusal([&] { smithlab::read_tabulated_ndf(big); }).find("is larger than 67108864 bytes (64 MiB)") !=
          std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("tabulated: normalize divides D by its projected area", "[tabulated]") {
    smithlab::TabulatedOptions opts;
    opts.normalize = true;
    const TabulatedNdf plain = smithlab::tabulated_ndf_from_csv(ggx_table(), "ggx.csv");
    CHECK(plain.normalization_factor() == 1.0 / plain.area_as_read());  // within the tolerance: divided all the same
    CHECK(plain.area_as_read() == Approx(1.0).epsilon(1e-4));
    const TabulatedNdf scaled = smithlab::tabulated_ndf_from_csv(ggx_table(1.3), "ggx.csv", opts);
    CHECK(scaled.area_as_read() == Approx(1.3 * plain.area_as_read()).epsilon(1e-13));
    CHECK(scaled.normalization_factor() == Approx(1.0 / 1.3).epsilon(1e-4));
    CHECK(smithlab::projected_area(scaled) == Approx(1.0).epsilon(1e-9));  // the checks' own quadrature
    for (double c : {1.0, 0.7, 0.2, 0.01, 1e-9}) CHECK(scaled.D(c) == Approx(plain.D(c)).epsilon(1e-12));
    // An all-zero D has no scale.
    const std::string m = refusal_of("theta_deg,D\n0,0\n30,0\n60,0\n", opts);
    CHECK(m.find("ndf.csv: the projected area of D is 0") == 0);
}

TEST_CASE("tabulated: the content hash follows the bytes, not the name", "[tabulated]") {
    CHECK(smithlab::fnv1a64("") == 0xcbf29ce484222325ULL);  // the FNV-1a 64 test vectors
    CHECK(smithlab::fnv1a64("a") == 0xaf63dc4c8601ec8cULL);
    CHECK(smithlab::fnv1a64("foobar") == 0x85944171f73967e8ULL);
    const std::string text = ggx_table();
    const TabulatedNdf a = smithlab::tabulated_ndf_from_csv(text, "a.csv");
    const TabulatedNdf b = smithlab::tabulated_ndf_from_csv(text, "elsewhere/b.csv");
    CHECK(a.content_hash() == b.content_hash());
    CHECK(a.content_id() == b.content_id());
    CHECK(a.content_hash() == smithlab::fnv1a64(text));
    CHECK(a.source() == "a.csv");
    CHECK(b.source() == "elsewhere/b.csv");
    char want[40];
    std::snprintf(want, sizeof want, "fnv1a64:%016llx", static_cast<unsigned long long>(a.content_hash()));
    CHECK(a.content_id() == want);
    CHECK(a.content_id().size() == 8 + 16);
    // One digit changed in one row.
    std::string edited = text;
    const std::size_t at = edited.find('\n', edited.find('\n') + 1) + 3;  // inside the second data row's angle
    REQUIRE(std::isdigit(static_cast<unsigned char>(edited[at])));
    edited[at] = edited[at] == '7' ? '6' : '7';
    const TabulatedNdf e = smithlab::tabulated_ndf_from_csv(edited, "a.csv");
    CHECK(e.content_hash() != a.content_hash());
    CHECK(e.content_id() != a.content_id());
    // The file reader hashes the same bytes.
    const std::filesystem::path p = std::filesystem::temp_directory_path() / "smithlab_test_tabulated_hash.csv";
    {
        std::ofstream out(p, std::ios::binary);
        out << text;
    }
    const TabulatedNdf f = smithlab::read_tabulated_ndf(p);
    std::filesystem::remove(p);
    CHECK(f.content_hash() == a.content_hash());
    CHECK(f.source() == p.string());
    // Copies share the table.
    const TabulatedNdf copy = a;
    CHECK(copy.content_id() == a.content_id());
    CHECK(copy.D(0.5) == a.D(0.5));
}

TEST_CASE("tabulated: 1 % noise per row keeps the projected area well inside its tolerance", "[tabulated]") {
    // Two lobes as in experiments/ndfs/two_lobe.csv (GGX 0.08 x 0.3 + Beckmann 0.45 x 0.7: normalized), 120 rows over
    // [0, 88] degrees, each D times exp(0.01 z), z standard normal (Box-Muller on the LCG), 200 draws.
    const smithlab::Ggx g = smithlab::ggx(0.08);
    const smithlab::Beckmann b = smithlab::beckmann(0.45);
    Lcg u{77};
    double s1 = 0.0, s2 = 0.0, worst = 0.0;
    const int draws = 200;
    for (int k = 0; k < draws; ++k) {
        const std::vector<double> th = jittered_angles(120, 0.0, 88.0, 100 + k);
        std::string text = "theta_deg,D\n";
        for (double t : th) {
            const double c = std::cos(t * pi / 180.0);
            const double z = std::sqrt(-2.0 * std::log(1.0 - u())) * std::cos(2.0 * pi * u());
            text += smithlab::format_g17(t) + "," +
                smithlab::format_g17((0.3 * g.D(c) + 0.7 * b.D(c)) * std::exp(0.01 * z)) + "\n";
        }
        const double a = smithlab::tabulated_ndf_from_csv(text, "noisy.csv").area_as_read() - 1.0;
        s1 += a;
        s2 += a * a;
        worst = std::max(worst, std::abs(a));
    }
    const double mean = s1 / draws, sd = std::sqrt(s2 / draws - mean * mean);
    std::printf(
        "tabulated NDF, 1 %% noise on 120 rows: area - 1 mean %.2e, sd %.2e, worst of %d %.2e (tolerance %.0e)\n", mean,
        sd, draws, worst, smithlab::tabulated_area_tolerance);
    CHECK(worst < smithlab::tabulated_area_tolerance / 2.0);
    CHECK(std::abs(mean) + 5.0 * sd < smithlab::tabulated_area_tolerance);
}

TEST_CASE("tabulated: the example table experiments/ndfs/two_lobe.csv", "[tabulated]") {
    const std::filesystem::path p =
        std::filesystem::path(SMITHLAB_SOURCE_DIR) / "experiments" / "ndfs" / "two_lobe.csv";
    const TabulatedNdf tab = smithlab::read_tabulated_ndf(p);  // normalized by its maker to within the tolerance
    CHECK(tab.points() == 120);
    CHECK(tab.theta_min_deg() == 0.0);
    CHECK(tab.theta_max_deg() == Approx(88.0).epsilon(1e-14));
    CHECK(std::abs(tab.area_as_read() - 1.0) < smithlab::tabulated_area_tolerance / 3.0);
    // Lambda is linear in P22 (Walter 2007 eq. 48): the mixture's is 0.3 Lambda_GGX(0.08) + 0.7 Lambda_Beckmann(0.45).
    // The rows carry 1 % noise (the area as read is 0.998, divided out): within 3.9e-3 of it from mu = 0.01 to 100.
    const smithlab::Ggx g = smithlab::ggx(0.08);
    const smithlab::Beckmann b = smithlab::beckmann(0.45);
    for (double mu : {0.01, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0}) {
        const double want = 0.3 * g.Lambda(mu) + 0.7 * b.Lambda(mu), got = smithlab::Lambda(tab, mu);
        INFO("mu " << mu << ": " << got << " vs the mixture's " << want);
        CHECK(std::abs(got / want - 1.0) < 5e-3);
    }
    smithlab::TabulatedOptions opts;
    opts.normalize = true;
    const TabulatedNdf n = smithlab::read_tabulated_ndf(p, opts);
    CHECK(n.normalization_factor() == Approx(1.0 / tab.area_as_read()).epsilon(1e-15));
    CHECK(n.content_id() == tab.content_id());
}

TEST_CASE("tabulated: a walk on the table's microsurface scatters as on GGX's, order by order",
          "[tabulated][walk][slow]") {
    const smithlab::Ggx g = smithlab::ggx(0.5);
    const TabulatedNdf tab = smithlab::tabulated_ndf_from_csv(
        csv_of(jittered_angles(200, 0.0, 89.0, 13), [&](double c) { return g.D(c); }), "ggx.csv");
    const walk::Microsurface<TabulatedNdf> ms_tab(tab);
    const walk::Microsurface<smithlab::Ggx> ms_ggx(g);
    walk::CellRequest r;
    r.wi = smithlab::Vec3(std::sin(pi / 4.0), 0.0, std::cos(pi / 4.0));
    r.walks = 200'000;
    r.seed = 1;
    const walk::CellResult a = walk::trace_cell(ms_tab, walk::Mirror{}, r);
    r.seed = 2;
    const walk::CellResult b = walk::trace_cell(ms_ggx, walk::Mirror{}, r);
    CHECK(a.albedo.capped == 0);
    for (int order = 0; order < walk::order_bins; ++order) {
        const walk::Estimate x = a.albedo.albedo(walk::Hemisphere::reflection, order, walk::Component::all);
        const walk::Estimate y = b.albedo.albedo(walk::Hemisphere::reflection, order, walk::Component::all);
        INFO("order bin " << order << ": table " << x.value << " +- " << x.stderr_ << ", ggx " << y.value << " +- "
                          << y.stderr_);
        CHECK(std::abs(x.value - y.value) < 4.0 * std::hypot(x.stderr_, y.stderr_));
    }
}
