// The renderer formats of a compensation table (compensation/compensation_formats.hpp): the C header compiled as C and
// run, the GLSL and HLSL through glslangValidator and, rewritten into C where they differ from it, run; every lookup
// against AlbedoTable::lookup and lookup_missing. The 16-bit PNG read back with libpng, its axes parsed with
// nlohmann-json; bad input refused, naming the item, nothing left behind. The scattering orders' tables the same way,
// their lookups and A_ms against OrderTables::lookup and multiple_scattering_albedo.
#include <png.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "smithlab/compensation/albedo_grid.hpp"
#include "smithlab/compensation/compensation_formats.hpp"
#include "smithlab/compensation/scattering_orders.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

using namespace smithlab;
using namespace smithlab::compensation;

namespace {

// A small table by hand, smooth in both axes, E = 1 at x = 0 (a white pixel), and 1 - E_avg(alpha) = 0.3 alpha^1.5.
AlbedoTable small_table() {
    AlbedoTable t;
    t.grid = {{0.05, 0.12, 0.3, 0.6, 1.0}, {}, 9, {}};
    // Warp scales that are not a power of alpha across the nodes (as a heavy-tailed NDF's): ln c is interpolated.
    for (const double a : t.grid.alphas) t.grid.scales.push_back(2.4 * std::pow(a, 0.8 + 0.3 * a));
    for (const double a : t.grid.alphas)
        for (int j = 0; j < t.grid.n_x; ++j) {
            const double x = t.grid.x(j);
            t.values.push_back(1.0 - 0.6 * std::sqrt(a) * x * (1.0 - 0.7 * x));
        }
    return t;
}

std::vector<double> small_missing(const AlbedoTable& t) {
    std::vector<double> v;
    for (const double a : t.grid.alphas) v.push_back(0.3 * std::pow(a, 1.5));
    return v;
}

CompensationExport export_of(const AlbedoTable& t) {
    return {"ggx", "height-correlated", "E", &t, small_missing(t), 2.5e-4, 1.25e-3, 5e-4};
}

std::filesystem::path scratch_dir(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
        ("smithlab_formats_" + name + "_" +
         std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    std::filesystem::create_directories(dir);
    return dir;
}

template <class Export>
std::string text_of(void (*write)(std::ostream&, const Export&), const Export& e) {
    std::ostringstream s;
    write(s, e);
    return s.str();
}

// An export in `language` (write_source).
template <class Export>
std::string source_of(const Export& e, Language language) {
    std::ostringstream s;
    write_source(s, e, language);
    return s.str();
}

// Every text writer of an export: its source in each language, then `json`, its axes' JSON.
template <class Export>
std::vector<std::function<void(std::ostream&, const Export&)>> text_writers(void (*json)(std::ostream&,
                                                                                         const Export&)) {
    std::vector<std::function<void(std::ostream&, const Export&)>> writers;
    for (const SourceFormat& f : source_formats)
        writers.push_back([language = f.language](std::ostream& o, const Export& e) { write_source(o, e, language); });
    writers.push_back(json);
    return writers;
}

int run(const std::string& command, const std::filesystem::path& log) {
    return std::system((command + " > " + log.string() + " 2>&1").c_str());
}

// The float nearest v, written so that C reads it back (into a float array).
std::string c_float(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(static_cast<float>(v)));
    return buf;
}

// The points looked up: at the nodes (alpha and the cosines of x_j), between them, below the first alpha, above the
// last, mu at 0 and 1 and beyond them (the lookups clamp it). Each is a float, as a renderer passes it.
struct Point {
    float alpha, mu;
};

std::vector<Point> points(const AlbedoTable& t) {
    std::vector<double> alphas = t.grid.alphas;
    for (const double a : {0.08, 0.2, 0.45, 0.8, 0.01, 1e-4, 1.3, 4.0}) alphas.push_back(a);
    std::vector<Point> p;
    for (const double a : alphas) {
        std::vector<double> mus = {0.0, 0.004, 0.1, 0.37, 0.9, 1.0, -0.2, 1.25};
        for (const int j : {1, 3, 7}) mus.push_back(t.grid.mu_of(t.grid.scale(a), t.grid.x(j)));
        for (const double m : mus) p.push_back({static_cast<float>(a), static_cast<float>(m)});
    }
    return p;
}

// The start of a C program that includes `file` (a header twice: its guard) and holds the points as pts[k][0] (alpha)
// and pts[k][1] (mu).
std::string program_head(const std::string& file, const std::vector<Point>& p) {
    std::string s = "#include <math.h>\n#include <stdio.h>\n#include \"" + file + "\"\n";
    if (file.ends_with(".h")) s += "#include \"" + file + "\"\n";  // twice: the guard
    s += "static const float pts[" + std::to_string(p.size()) + "][2] = {\n";
    for (const Point& q : p) s += "    {" + c_float(q.alpha) + ", " + c_float(q.mu) + "},\n";
    return s + "};\n";
}

// A C program that includes `file` and prints NAME_E at every point (and NAME_E_avg and NAME_missing when with_avg),
// one line each.
std::string lookup_program(const std::string& file, const std::string& id, const std::vector<Point>& p, bool with_avg) {
    return program_head(file, p) +
        "int main(void) {\n    unsigned k;\n    for (k = 0; k < sizeof pts / sizeof pts[0]; ++k)\n"
        "        printf(\"%.9g %.9g %.9g\\n\", " +
        id + "_E(pts[k][0], pts[k][1]), " +
        (with_avg ? id + "_E_avg(pts[k][0]), " + id + "_missing(pts[k][0])" : std::string("0.0, 0.0")) +
        ");\n    return 0;\n}\n";
}

// Compiles `source` (in dir, which holds the included file) as C99 with warnings as errors and runs it: its output.
std::ifstream program_output(const std::filesystem::path& dir, const std::string& source) {
    std::ofstream(dir / "main.c") << source;
    const std::string exe = (dir / "lookup").string();
    REQUIRE(run("cc -std=c99 -Wall -Wextra -Wpedantic -Werror -o " + exe + " " + (dir / "main.c").string() + " -lm",
                dir / "cc.log") == 0);
    REQUIRE(run(exe, dir / "out.txt") == 0);
    return std::ifstream(dir / "out.txt");
}

// Runs the program `source` (program_output) and checks each lookup against the table's in double, at the same float
// inputs, mu clamped: E within float rounding (1e-6), 1 - E_avg within 1e-5 of lookup_missing relative to it, E_avg
// within 1e-6 of 1 - lookup_missing.
void check_lookups(const std::filesystem::path& dir, const std::string& source, const AlbedoTable& t,
                   const std::vector<double>& missing, const std::vector<Point>& p) {
    std::ifstream in = program_output(dir, source);
    for (const Point& q : p) {
        double e = 0.0, avg = 0.0, m = 0.0;
        REQUIRE(in >> e >> avg >> m);
        const double mu = std::clamp(static_cast<double>(q.mu), 0.0, 1.0);
        INFO("alpha " << q.alpha << " mu " << q.mu);
        CHECK(std::abs(e - t.lookup(q.alpha, mu)) < 1e-6);
        if (missing.empty()) continue;
        const double want = lookup_missing(t.grid.alphas, missing, q.alpha);
        INFO("1 - E_avg " << m << ", lookup_missing " << want);
        CHECK(std::abs(m - want) < 1e-5 * want);
        CHECK(std::abs(avg - (1.0 - want)) < 1e-6);
    }
}

// GLSL where it differs from C: an array's initializer float[N](...) is {...}; constructors int(x) and float(x) are
// casts. The rest, the arithmetic, is the GLSL's own (its literals unsuffixed: C computes them in double).
std::string glsl_as_c(const std::string& glsl) {
    std::string c = std::regex_replace(glsl, std::regex(R"(= float\[\d+\]\()"), "= {");
    c = std::regex_replace(c, std::regex("\n\\);"), "\n};");
    c = std::regex_replace(c, std::regex(R"(\bint\()"), "(int)(");
    return std::regex_replace(c, std::regex(R"(\bfloat\()"), "(float)(");
}

bool has_glslang() { return std::system("command -v glslangValidator > /dev/null 2>&1") == 0; }

// The E lookups called in a shader: a float of alpha and mu.
std::string E_calls(const std::string& id, bool with_avg) {
    return id + "_E(alpha, mu)" + (with_avg ? " + " + id + "_E_avg(alpha) + " + id + "_missing(alpha)" : "");
}

// The GLSL in a fragment shader (#version 330 core) whose colour is `calls`, a float of the uniforms alpha and mu,
// through the reference compiler.
void check_glsl_compiles(const std::filesystem::path& dir, const std::string& glsl, const std::string& calls) {
    std::ofstream(dir / "table.frag") << "#version 330 core\n"
                                      << glsl << "\nuniform float alpha;\nuniform float mu;\nout vec4 color;\n"
                                      << "void main() {\n    float v = " << calls
                                      << ";\n    color = vec4(v, v, v, 1.0);\n}\n";
    CHECK(run("glslangValidator " + (dir / "table.frag").string(), dir / "glsl.log") == 0);
}

// The HLSL with a pixel shader's entry point whose colour is `calls`, of alpha and mu from the position, through
// glslangValidator's HLSL front end (-D; it compiles to SPIR-V).
void check_hlsl_compiles(const std::filesystem::path& dir, const std::string& hlsl, const std::string& calls) {
    std::ofstream(dir / "table.hlsl") << hlsl << "\nfloat4 main(float4 pos : SV_Position) : SV_Target {\n"
                                      << "    float alpha = pos.x;\n    float mu = pos.y;\n    float v = " << calls
                                      << ";\n    return float4(v, v, v, 1.0f);\n}\n";
    CHECK(run("glslangValidator -D -V -e main -S frag -o " + (dir / "table.spv").string() + " " +
                  (dir / "table.hlsl").string(),
              dir / "hlsl.log") == 0);
}

// A PNG as libpng reads it: its header and its samples (16-bit big-endian, or 8-bit).
struct PngRead {
    png_uint_32 width = 0, height = 0;
    int bit_depth = 0, color_type = 0;
    std::vector<unsigned> samples;
};

// libpng's errors return through setjmp to this frame, where every object with a destructor already exists.
bool read_png(const std::filesystem::path& path, PngRead& out) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    std::vector<unsigned char> data;
    std::vector<png_bytep> rows;
    if (!info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        std::fclose(f);
        return false;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    out.width = png_get_image_width(png, info);
    out.height = png_get_image_height(png, info);
    out.bit_depth = png_get_bit_depth(png, info);
    out.color_type = png_get_color_type(png, info);
    const std::size_t row_bytes = png_get_rowbytes(png, info);
    data.resize(row_bytes * out.height);
    rows.resize(out.height);
    for (png_uint_32 r = 0; r < out.height; ++r) rows[r] = data.data() + r * row_bytes;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    if (out.bit_depth == 16)
        for (std::size_t k = 0; k + 1 < data.size(); k += 2) out.samples.push_back(data[k] * 256u + data[k + 1]);
    else out.samples.assign(data.begin(), data.end());
    return true;
}

// The bytes write_png16 gives, in a file for read_png.
void write_png_file(const std::filesystem::path& path, const CompensationExport& e) {
    std::ostringstream s;
    write_png16(s, e);
    std::ofstream(path, std::ios::binary) << s.str();
}

}  // namespace

TEST_CASE("compensation formats: identifiers", "[compensation][formats]") {
    const AlbedoTable t = small_table();
    CompensationExport e = export_of(t);
    CHECK(compensation_identifier(e) == "smithlab_ggx_hc");
    e = {"gtr(gamma=1.5)", "separable", "E_R+E_T outside eta=1.5", &t, {}, 0.0, 0.0, 0.0};
    CHECK(compensation_identifier(e) == "smithlab_gtr_gamma_1_5_sep_E_R_E_T_outside_eta_1_5");
    e.g2 = "uncorrelated";
    CHECK_THROWS_AS(compensation_identifier(e), input_error);
    e = export_of(t);
    e.family = "()";
    CHECK_THROWS_AS(compensation_identifier(e), input_error);
    e = export_of(t);
    e.quantity = "+";
    CHECK_THROWS_AS(compensation_identifier(e), input_error);
}

TEST_CASE("compensation formats: the C header compiles as C and looks up as AlbedoTable::lookup",
          "[compensation][formats]") {
    const AlbedoTable t = small_table();
    const CompensationExport e = export_of(t);
    const std::string h = source_of(e, Language::c);
    CHECK(h.find("#ifndef SMITHLAB_GGX_HC_COMPENSATION_H") != std::string::npos);
    CHECK(h.find("height-correlated Smith G2") != std::string::npos);
    CHECK(h.find("below the first alpha: the first row") != std::string::npos);
    CHECK(h.find("above the last alpha: the last row") != std::string::npos);
    CHECK(h.find("mu clamped to [0, 1]") != std::string::npos);
    CHECK(h.find("within 0.00025 of the exact values") != std::string::npos);
    CHECK(h.find("within 0.00125 below the first alpha") != std::string::npos);
    // The comment's lines joined: its phrases may break across them.
    const std::string joined = std::regex_replace(h, std::regex("\n \\*   "), " ");
    CHECK(joined.find("within 0.0005 at grazing mu < 0.002 (theta > 89.885 degrees)") != std::string::npos);
    CHECK(h.find("Kulla and Conty 2017") != std::string::npos);
    CHECK(h.find("Turquin 2019") != std::string::npos);
    CHECK(h.find("(1 - E_avg) = smithlab_ggx_hc_missing(alpha)") != std::string::npos);
    CHECK(h.find("should divide by smithlab_ggx_hc_missing(alpha)") != std::string::npos);
    CHECK(h.find("ln(1 - E_avg) linear in ln(alpha)") != std::string::npos);
    CHECK(h.find("smithlab_ggx_hc_log_missing_table[5]") != std::string::npos);
    CHECK(h.find("_E_avg_table") == std::string::npos);
    const std::filesystem::path dir = scratch_dir("c");
    std::ofstream(dir / "table.h") << h;
    CHECK(run("cc -std=c99 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -x c " + (dir / "table.h").string(),
              dir / "syntax.log") == 0);
    CHECK(run("c++ -std=c++17 -Wall -Wextra -Werror -fsyntax-only -x c++ " + (dir / "table.h").string(),
              dir / "syntax_cxx.log") == 0);
    const std::vector<Point> p = points(t);
    check_lookups(dir, lookup_program("table.h", "smithlab_ggx_hc", p, true), t, e.missing, p);
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: GLSL and HLSL compile with glslangValidator and look up as AlbedoTable::lookup",
          "[compensation][formats]") {
    REQUIRE(has_glslang());  // glslang-tools, a CI dependency (.ci/deps)
    const AlbedoTable t = small_table();
    const CompensationExport e = export_of(t);
    const std::string glsl = source_of(e, Language::glsl), hlsl = source_of(e, Language::hlsl);
    CHECK(glsl.find("\n#version") == std::string::npos);  // the includer's
    const std::filesystem::path dir = scratch_dir("shaders");
    check_glsl_compiles(dir, glsl, E_calls("smithlab_ggx_hc", true));
    check_hlsl_compiles(dir, hlsl, E_calls("smithlab_ggx_hc", true));
    const std::vector<Point> p = points(t);
    SECTION("GLSL, its constructors as C casts") {
        std::ofstream(dir / "table_glsl.c") << glsl_as_c(glsl);
        check_lookups(dir, lookup_program("table_glsl.c", "smithlab_ggx_hc", p, true), t, e.missing, p);
    }
    SECTION("HLSL, which is C here") {
        std::ofstream(dir / "table_hlsl.c") << hlsl;
        check_lookups(dir, lookup_program("table_hlsl.c", "smithlab_ggx_hc", p, true), t, e.missing, p);
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: a tiny 1 - E_avg keeps its relative precision in every format",
          "[compensation][formats]") {
    const AlbedoTable t = small_table();
    CompensationExport e = export_of(t);
    // 1 - E_avg ~ alpha^2 from 1e-9 at the first alpha: as a float, E_avg = 1 - 1e-9 is 1, and a lobe divided by
    // 1 - E_avg would divide by 0.
    e.missing.clear();
    for (const double a : t.grid.alphas) e.missing.push_back(1e-9 * (a / 0.05) * (a / 0.05));
    REQUIRE(e.missing.front() == 1e-9);
    CHECK(1.0f - static_cast<float>(1.0 - e.missing.front()) == 0.0f);
    // Down to alpha 0.01, a fifth of the first: far below it the float lookup's error grows with the power continued
    // (at 1e-4, alpha^2 from 1e-9, C's logf and expf come to 9e-6 of it).
    std::vector<Point> p;
    for (const Point& q : points(t))
        if (q.alpha >= 0.01f) p.push_back(q);
    for (const double a : {0.05, 0.06, 0.1, 0.03, 0.5}) p.push_back({static_cast<float>(a), 0.5f});
    const std::filesystem::path dir = scratch_dir("tiny");
    SECTION("C") {
        std::ofstream(dir / "table.h") << source_of(e, Language::c);
        check_lookups(dir, lookup_program("table.h", "smithlab_ggx_hc", p, true), t, e.missing, p);
    }
    SECTION("GLSL, its constructors as C casts") {
        std::ofstream(dir / "table_glsl.c") << glsl_as_c(source_of(e, Language::glsl));
        check_lookups(dir, lookup_program("table_glsl.c", "smithlab_ggx_hc", p, true), t, e.missing, p);
    }
    SECTION("HLSL, which is C here") {
        std::ofstream(dir / "table_hlsl.c") << source_of(e, Language::hlsl);
        check_lookups(dir, lookup_program("table_hlsl.c", "smithlab_ggx_hc", p, true), t, e.missing, p);
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: without E_avg, and with labels that are not identifiers", "[compensation][formats]") {
    REQUIRE(has_glslang());
    const AlbedoTable t = small_table();
    const CompensationExport e{
        "gtr(gamma=1.5) /*/ \"x\"", "separable", "E_R+E_T outside eta=1.5", &t, {}, 0.0, 0.0, 0.0};
    const std::string id = "smithlab_gtr_gamma_1_5_x_sep_E_R_E_T_outside_eta_1_5";
    REQUIRE(compensation_identifier(e) == id);
    const std::string h = source_of(e, Language::c), glsl = source_of(e, Language::glsl),
                      hlsl = source_of(e, Language::hlsl);
    for (const std::string* s : {&h, &glsl, &hlsl}) {
        CHECK(s->find("_E_avg") == std::string::npos);
        CHECK(s->find("_missing") == std::string::npos);
        CHECK(s->find("No E_avg is given") != std::string::npos);
        CHECK(s->find("separable Smith G2") != std::string::npos);
    }
    const std::filesystem::path dir = scratch_dir("no_avg");
    std::ofstream(dir / "table.h") << h;
    CHECK(run("cc -std=c99 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -x c " + (dir / "table.h").string(),
              dir / "syntax.log") == 0);
    check_glsl_compiles(dir, glsl, E_calls(id, false));
    check_hlsl_compiles(dir, hlsl, E_calls(id, false));
    const std::vector<Point> p = points(t);
    check_lookups(dir, lookup_program("table.h", id, p, false), t, {}, p);
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: a table of ln E with a node cluster, in every format", "[compensation][formats]") {
    REQUIRE(has_glslang());
    // A dielectric's table as the fit writes it from inside: ln E stored, nodes clustered about a critical cosine.
    AlbedoTable t = small_table();
    t.grid.cluster = {0.42, 0.02, 0.3};
    for (double& v : t.values) v = std::log(v);
    t.stored = Stored::log;
    const double E = std::exp(t.at(2, 4));
    CHECK(std::abs(t.lookup(0.3, t.grid.mu(2, 4)) - E) < 1e-14 * E);  // a node: exp of the stored ln E
    CHECK(std::abs(t.grid.x_of(t.grid.scales[2], t.grid.mu(2, 4)) - t.grid.x(4)) < 1e-15);
    const CompensationExport e{"ggx", "height-correlated", "E_R+E_T eta=1.5 inside", &t, {}, 2.5e-4, 1e-3, 5e-4};
    const std::string id = "smithlab_ggx_hc_E_R_E_T_eta_1_5_inside";
    const std::string h = source_of(e, Language::c), glsl = source_of(e, Language::glsl),
                      hlsl = source_of(e, Language::hlsl);
    for (const std::string* s : {&h, &glsl, &hlsl}) {
        CHECK(s->find(id + "_log_E_table[45]") != std::string::npos);
        CHECK(s->find(id + "_E_table") == std::string::npos);
        CHECK(s->find("nodes clustered about mu = 0.42") != std::string::npos);
        CHECK(s->find("of ln E, then exp") != std::string::npos);
    }
    const std::filesystem::path dir = scratch_dir("log");
    check_glsl_compiles(dir, glsl, E_calls(id, false));
    check_hlsl_compiles(dir, hlsl, E_calls(id, false));
    // Points on both sides of the cluster and in it, where x changes fastest.
    std::vector<Point> p = points(t);
    for (const double mu : {0.40, 0.415, 0.419, 0.42, 0.421, 0.43, 0.5})
        for (const double a : {0.06, 0.3, 0.9}) p.push_back({static_cast<float>(a), static_cast<float>(mu)});
    SECTION("C") {
        std::ofstream(dir / "table.h") << h;
        check_lookups(dir, lookup_program("table.h", id, p, false), t, {}, p);
    }
    SECTION("GLSL, its constructors as C casts") {
        std::ofstream(dir / "table_glsl.c") << glsl_as_c(glsl);
        check_lookups(dir, lookup_program("table_glsl.c", id, p, false), t, {}, p);
    }
    SECTION("HLSL, which is C here") {
        std::ofstream(dir / "table_hlsl.c") << hlsl;
        check_lookups(dir, lookup_program("table_hlsl.c", id, p, false), t, {}, p);
    }
    SECTION("the PNG holds -ln E / K, K the largest -ln E, and its axes say so") {
        write_png_file(dir / "E.png", e);
        PngRead r;
        REQUIRE(read_png(dir / "E.png", r));
        REQUIRE(r.samples.size() == t.values.size());
        const double K = -*std::min_element(t.values.begin(), t.values.end());
        for (std::size_t k = 0; k < t.values.size(); ++k)
            CHECK(r.samples[k] == std::lround(-t.values[k] / K * 65535.0));
        CHECK(*std::max_element(r.samples.begin(), r.samples.end()) == 65535u);
        std::ostringstream s;
        write_axes_json(s, e);
        const nlohmann::json j = nlohmann::json::parse(s.str());
        CHECK(j.at("stored").get<std::string>() == "ln E");
        CHECK(j.at("log_scale").get<double>() == K);
        CHECK(j.at("cluster").at("mu").get<double>() == 0.42);
        CHECK(j.at("cluster").at("width").get<double>() == 0.02);
        CHECK(j.at("cluster").at("weight").get<double>() == 0.3);
        CHECK(j.at("x").get<std::string>().find("asinh((mu - 0.42) / 0.02)") != std::string::npos);
        CHECK(j.at("lookup").get<std::string>().find("of ln E, then exp") != std::string::npos);
    }
    SECTION("an E above 1 in the PNG is refused") {
        t.values[7] = 1e-3;  // ln E > 0
        std::ostringstream png;
        CHECK_THROWS_WITH(write_png16(png, e), Catch::Contains("outside (-inf, 0]"));
        CHECK(png.str().empty());
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: the 16-bit PNG and its axes", "[compensation][formats]") {
    const AlbedoTable t = small_table();
    CompensationExport e = export_of(t);
    e.family = "my \"ndf\" \\ 1";
    const std::filesystem::path dir = scratch_dir("png");
    const std::filesystem::path png = dir / "E.png";
    write_png_file(png, e);
    PngRead r;
    REQUIRE(read_png(png, r));
    CHECK(r.width == 9);
    CHECK(r.height == 5);
    CHECK(r.bit_depth == 16);
    CHECK(r.color_type == PNG_COLOR_TYPE_GRAY);
    REQUIRE(r.samples.size() == t.values.size());
    for (std::size_t k = 0; k < t.values.size(); ++k) {
        INFO("row " << k / 9 << " column " << k % 9);
        CHECK(r.samples[k] == std::lround(t.values[k] * 65535.0));
    }
    CHECK(r.samples[0] == 65535);  // E = 1 at x = 0

    std::ostringstream s;
    write_axes_json(s, e);
    const nlohmann::json j = nlohmann::json::parse(s.str());
    CHECK(j.at("alphas").get<std::vector<double>>() == t.grid.alphas);
    CHECK(j.at("n_x").get<int>() == t.grid.n_x);
    CHECK(j.at("image").at("width").get<int>() == 9);
    CHECK(j.at("image").at("height").get<int>() == 5);
    CHECK(j.at("image").at("bit_depth").get<int>() == 16);
    CHECK(j.at("scale").get<int>() == 65535);
    CHECK(j.at("family").get<std::string>() == e.family);
    CHECK(j.at("g2").get<std::string>() == "height-correlated");
    CHECK(j.at("quantity").get<std::string>() == "E");
    CHECK(j.at("identifier").get<std::string>() == "smithlab_my_ndf_1_hc");
    CHECK(j.at("one_minus_E_avg").get<std::vector<double>>() == e.missing);
    CHECK(j.at("one_minus_E_avg_lookup").get<std::string>().find("ln of it linear in ln(alpha)") != std::string::npos);
    CHECK(j.at("warp_scales").get<std::vector<double>>() == t.grid.scales);
    CHECK(j.at("warp_scale_lookup").get<std::string>().find("ln of it linear in ln(alpha)") != std::string::npos);
    CHECK_FALSE(j.contains("E_avg"));
    CHECK(j.at("mu_of_x").get<std::string>() == "c x^2 / (1 + c - x^2)");
    CHECK(j.at("max_interpolation_error").get<double>() == e.max_interp_error);
    CHECK(j.at("below_grid_error").get<double>() == e.below_grid_error);
    CHECK(j.at("grazing_error").get<double>() == e.grazing_error);
    CHECK(j.at("grazing_cos_theta").get<double>() == grazing_mu);
    CHECK(j.at("stored").get<std::string>() == "E");
    CHECK_FALSE(j.contains("log_scale"));
    CHECK_FALSE(j.contains("cluster"));
    CHECK(j.at("x").get<std::string>().find("(1 + c) mu / (mu + c)") != std::string::npos);
    CHECK(j.at("lookup").get<std::string>().find("bilinear in (sqrt(alpha), x)") != std::string::npos);
    CHECK(j.at("below_first_alpha").get<std::string>().find("first row") != std::string::npos);
    CHECK(j.at("above_last_alpha").get<std::string>().find("last row") != std::string::npos);
    e.missing.clear();
    std::ostringstream s2;
    write_axes_json(s2, e);
    CHECK_FALSE(nlohmann::json::parse(s2.str()).contains("one_minus_E_avg"));
    CHECK_FALSE(nlohmann::json::parse(s2.str()).contains("one_minus_E_avg_lookup"));
    std::filesystem::remove_all(dir);
}

TEST_CASE("compensation formats: bad input is refused, naming the item, and leaves no file",
          "[compensation][formats]") {
    std::ostringstream sink, png;
    // The PNG's bytes are written only once every value has passed.
    auto nothing_written = [&] { CHECK(png.str().empty()); };
    AlbedoTable t = small_table();
    SECTION("a NaN in the table") {
        t.values[2 * 9 + 4] = std::nan("");
        const CompensationExport e = export_of(t);
        for (const auto& write : text_writers(write_axes_json)) {
            CHECK_THROWS_AS(write(sink, e), input_error);
            CHECK_THROWS_WITH(write(sink, e), Catch::Contains("E at alpha 0.3, x_4 = 0.5"));
        }
        CHECK_THROWS_AS(write_png16(png, e), input_error);
        nothing_written();
    }
    SECTION("1 - E_avg of another size") {
        CompensationExport e = export_of(t);
        e.missing.pop_back();
        CHECK_THROWS_WITH(write_source(sink, e, Language::c), Catch::Contains("4 values of 1 - E_avg for 5 alphas"));
        CHECK_THROWS_AS(write_png16(png, e), input_error);
        nothing_written();
    }
    SECTION("1 - E_avg <= 0, > 1, NaN or below the normal floats") {
        for (const double bad : {0.0, -1e-3, 1.5, std::nan(""), HUGE_VAL, 1e-40}) {
            CompensationExport e = export_of(t);
            e.missing[3] = bad;
            INFO("1 - E_avg " << bad);
            for (const auto& write : text_writers(write_axes_json)) {
                CHECK_THROWS_AS(write(sink, e), input_error);
                CHECK_THROWS_WITH(write(sink, e), Catch::Contains("1 - E_avg at alpha 0.6"));
            }
            CHECK_THROWS_AS(write_png16(png, e), input_error);
            nothing_written();
        }
        CompensationExport e = export_of(t);
        e.missing[3] = 1.0;  // E_avg = 0: allowed
        CHECK_NOTHROW(write_source(sink, e, Language::c));
    }
    SECTION("a value outside [0, 1] in the PNG") {
        t.values[7] = 1.5;
        const CompensationExport e = export_of(t);
        CHECK_NOTHROW(write_source(sink, e, Language::c));
        CHECK_THROWS_WITH(write_png16(png, e), Catch::Contains("x_7") && Catch::Contains("outside [0, 1]"));
        nothing_written();
        // A rounding past 1 (an albedo at its limit 1, computed to a tolerance) is the end value, not an error.
        t.values[7] = 1.0 + 2.0 * std::numeric_limits<double>::epsilon();
        CHECK_NOTHROW(write_png16(png, export_of(t)));
    }
    SECTION("no table, a table of the wrong size, alphas out of order") {
        CompensationExport e = export_of(t);
        e.E = nullptr;
        CHECK_THROWS_WITH(write_source(sink, e, Language::glsl), Catch::Contains("no table"));
        e.E = &t;
        t.values.pop_back();
        CHECK_THROWS_WITH(write_source(sink, e, Language::hlsl), Catch::Contains("44 values for 5 alphas x 9 cosines"));
        t = small_table();
        std::swap(t.grid.alphas[1], t.grid.alphas[2]);
        CHECK_THROWS_WITH(write_axes_json(sink, e), Catch::Contains("alphas must ascend"));
        t = small_table();
        t.grid.scales[2] = 1e-40;  // a subnormal float: its logarithm in float is not the double's
        CHECK_THROWS_WITH(write_source(sink, e, Language::glsl), Catch::Contains("the warp's scale at alpha 0.3"));
        t.grid.scales.pop_back();
        CHECK_THROWS_WITH(write_source(sink, e, Language::c), Catch::Contains("4 warp scales for 5 alphas"));
        t = small_table();
        e.max_interp_error = std::nan("");
        CHECK_THROWS_WITH(write_source(sink, e, Language::c), Catch::Contains("max interpolation error"));
    }
}

namespace {

// Orders by hand on small_table's grid, smooth in both axes: q_2 + q_3 < 1, p in [0.3, 1] (1 at x = 1, where the walk
// puts it when no walk hits a fourth time), and q_1 (from 0 at x = 1) for the separable G2.
OrderTables small_orders(bool separable) {
    const AlbedoGrid g = small_table().grid;
    OrderTables o;
    for (AlbedoTable* t : {&o.q2, &o.q3, &o.p}) t->grid = g;
    if (separable) o.q1.grid = g;
    for (const double a : g.alphas)
        for (int j = 0; j < g.n_x; ++j) {
            const double x = g.x(j);
            o.q2.values.push_back(0.85 - 0.4 * std::sqrt(a) * x);
            o.q3.values.push_back(0.1 + 0.15 * a * x);
            o.p.values.push_back(0.3 + 0.7 * x * x);
            if (separable) o.q1.values.push_back(0.2 * a * (1.0 - x));
        }
    return o;
}

OrderExport order_export_of(const OrderTables& o) {
    return {"ggx", o.q1.values.empty() ? "height-correlated" : "separable", &o, 2.1e-3};
}

// The mirror facets' albedo E and the Fresnel average F_avg at which NAME_ms is asked, each at every point: E from 0
// to 1 (where nothing is missed), F_avg from 0 to 1 (the white furnace, where A_ms = 1 - E).
const std::vector<std::pair<float, float>> E_and_F = {{0.35f, 0.0f}, {0.35f, 0.3f}, {0.6f, 0.8f}, {0.9f, 1.0f},
                                                      {0.0f, 0.95f}, {1.0f, 0.5f},  {0.2f, 1.0f}};

// A C program that includes `file` and prints, at every point, NAME_q2, NAME_q3, NAME_p, NAME_q1 (0 without one) and
// NAME_ms at each of E_and_F, one line each.
std::string order_program(const std::string& file, const std::string& id, const std::vector<Point>& p, bool q1) {
    const std::string at = "(pts[k][0], pts[k][1]";
    std::string s = program_head(file, p) +
        "int main(void) {\n    unsigned k;\n    for (k = 0; k < sizeof pts / sizeof pts[0]; ++k) {\n"
        "        printf(\"%.9g %.9g %.9g %.9g\", " +
        id + "_q2" + at + "), " + id + "_q3" + at + "), " + id + "_p" + at + "), " +
        (q1 ? id + "_q1" + at + ")" : std::string("0.0")) + ");\n";
    for (const auto& [E, F] : E_and_F)
        s += "        printf(\" %.9g\", " + id + "_ms" + at + ", " + c_float(E) + ", " + c_float(F) + "));\n";
    return s + "        printf(\"\\n\");\n    }\n    return 0;\n}\n";
}

// Runs the program `source` (program_output) and checks each lookup against OrderTables::lookup in double and NAME_ms
// against multiple_scattering_albedo of it, at the same float inputs, mu clamped: within float rounding (1e-6).
void check_order_lookups(const std::filesystem::path& dir, const std::string& source, const OrderTables& o,
                         const std::vector<Point>& p) {
    std::ifstream in = program_output(dir, source);
    for (const Point& q : p) {
        double q2 = 0.0, q3 = 0.0, pk = 0.0, q1 = 0.0;
        REQUIRE(in >> q2 >> q3 >> pk >> q1);
        const ScatteringOrders want = o.lookup(q.alpha, std::clamp(static_cast<double>(q.mu), 0.0, 1.0));
        INFO("alpha " << q.alpha << " mu " << q.mu);
        CHECK(std::abs(q2 - want.q2) < 1e-6);
        CHECK(std::abs(q3 - want.q3) < 1e-6);
        CHECK(std::abs(pk - want.p) < 1e-6);
        CHECK(std::abs(q1 - want.q1) < 1e-6);
        for (const auto& [E, F] : E_and_F) {
            double ms = 0.0;
            REQUIRE(in >> ms);
            INFO("E " << E << " F_avg " << F);
            CHECK(std::abs(ms - multiple_scattering_albedo(E, want, F)) < 1e-6);
        }
    }
}

// Every lookup of the orders called in a shader: a float of alpha and mu.
std::string order_calls(const std::string& id, bool q1) {
    return id + "_q2(alpha, mu) + " + id + "_q3(alpha, mu) + " + id + "_p(alpha, mu) + " +
        (q1 ? id + "_q1(alpha, mu) + " : "") + id + "_ms(alpha, mu, 0.5, 0.8)";
}

}  // namespace

TEST_CASE("compensation formats: the orders' identifiers", "[compensation][formats][orders]") {
    const OrderTables o = small_orders(false);
    OrderExport e = order_export_of(o);
    CHECK(order_identifier(e) == "smithlab_ggx_hc_orders");
    e = {"gtr(gamma=1.5)", "separable", &o, 0.0};
    CHECK(order_identifier(e) == "smithlab_gtr_gamma_1_5_sep_orders");
    e.g2 = "uncorrelated";
    CHECK_THROWS_AS(order_identifier(e), input_error);
    e = order_export_of(o);
    e.family = "()";
    CHECK_THROWS_AS(order_identifier(e), input_error);
}

TEST_CASE(
    "compensation formats: the orders' C header compiles and looks up as OrderTables::lookup and "
    "multiple_scattering_albedo",
    "[compensation][formats][orders]") {
    for (const bool separable : {false, true}) {
        const OrderTables o = small_orders(separable);
        const OrderExport e = order_export_of(o);
        const std::string id = order_identifier(e), h = source_of(e, Language::c);
        INFO(id);
        // The comment's lines joined: its phrases may break across them.
        const std::string joined = std::regex_replace(h, std::regex("\n \\*   "), " ");
        CHECK(h.find("#ifndef " + std::string(separable ? "SMITHLAB_GGX_SEP_ORDERS_H" : "SMITHLAB_GGX_HC_ORDERS_H")) !=
              std::string::npos);
        CHECK(joined.find("Kulla-Conty-like conductor compensation") != std::string::npos);
        CHECK(joined.find("single scattering E_F(mu) (with the facets' Fresnel F) exact") != std::string::npos);
        CHECK(joined.find("A_ms(mu) = (1 - E(mu)) (q_1 F_avg + (1 - q_1) (q_2 F_avg^2 + q_3 F_avg^3 + (1 - q_2 - q_3) "
                          "F_avg^4 p / (1 - F_avg (1 - p)))) = " +
                          id + "_ms(alpha, mu, E, F_avg), smithlab's multiple_scattering_albedo") != std::string::npos);
        CHECK(joined.find("the worst standard error of q_2 and q_3 is 0.0021") != std::string::npos);
        CHECK(joined.find("Grid: n_alpha x n_x = 5 x 9, alpha in [0.05, 1]") != std::string::npos);
        CHECK(joined.find(separable ? "separable Smith G2" : "height-correlated Smith G2") != std::string::npos);
        CHECK(joined.find(separable ? "smithlab_ggx_sep_E(alpha, mu)" : "smithlab_ggx_hc_E(alpha, mu)") !=
              std::string::npos);
        CHECK(joined.find("below the first alpha: the first row") != std::string::npos);
        CHECK(h.find(id + "_p_table[45]") != std::string::npos);
        CHECK((h.find("_q1") != std::string::npos) == separable);
        CHECK((joined.find("q_1 = 0 (no q_1 table)") != std::string::npos) == !separable);
        CHECK((joined.find("q_1 = (E_hc - E_sep) / (1 - E_sep)") != std::string::npos) == separable);
        const std::filesystem::path dir = scratch_dir("orders_c");
        std::ofstream(dir / "orders.h") << h;
        CHECK(run("cc -std=c99 -Wall -Wextra -Wpedantic -Werror -fsyntax-only -x c " + (dir / "orders.h").string(),
                  dir / "syntax.log") == 0);
        CHECK(run("c++ -std=c++17 -Wall -Wextra -Werror -fsyntax-only -x c++ " + (dir / "orders.h").string(),
                  dir / "syntax_cxx.log") == 0);
        const std::vector<Point> p = points(o.q2);
        check_order_lookups(dir, order_program("orders.h", id, p, separable), o, p);
        std::filesystem::remove_all(dir);
    }
}

TEST_CASE("compensation formats: the orders' GLSL and HLSL compile with glslangValidator and look up as the library",
          "[compensation][formats][orders]") {
    REQUIRE(has_glslang());
    for (const bool separable : {false, true}) {
        const OrderTables o = small_orders(separable);
        const OrderExport e = order_export_of(o);
        const std::string id = order_identifier(e);
        const std::string glsl = source_of(e, Language::glsl), hlsl = source_of(e, Language::hlsl);
        INFO(id);
        CHECK(glsl.find("\n#version") == std::string::npos);
        const std::filesystem::path dir = scratch_dir("orders_shaders");
        check_glsl_compiles(dir, glsl, order_calls(id, separable));
        check_hlsl_compiles(dir, hlsl, order_calls(id, separable));
        const std::vector<Point> p = points(o.q2);
        std::ofstream(dir / "orders_glsl.c") << glsl_as_c(glsl);
        check_order_lookups(dir, order_program("orders_glsl.c", id, p, separable), o, p);
        std::ofstream(dir / "orders_hlsl.c") << hlsl;
        check_order_lookups(dir, order_program("orders_hlsl.c", id, p, separable), o, p);
        std::filesystem::remove_all(dir);
    }
}

TEST_CASE("compensation formats: the orders' JSON holds the tables and their axes", "[compensation][formats][orders]") {
    for (const bool separable : {false, true}) {
        const OrderTables o = small_orders(separable);
        const OrderExport e = order_export_of(o);
        const nlohmann::json j = nlohmann::json::parse(text_of(write_orders_axes_json, e));
        CHECK(j.at("identifier").get<std::string>() == order_identifier(e));
        CHECK(j.at("family").get<std::string>() == "ggx");
        CHECK(j.at("g2").get<std::string>() == e.g2);
        CHECK(j.at("tables").at("q2").get<std::vector<double>>() == o.q2.values);
        CHECK(j.at("tables").at("q3").get<std::vector<double>>() == o.q3.values);
        CHECK(j.at("tables").at("p").get<std::vector<double>>() == o.p.values);
        CHECK(j.at("tables").contains("q1") == separable);
        if (separable) CHECK(j.at("tables").at("q1").get<std::vector<double>>() == o.q1.values);
        CHECK(j.at("q1_rule").get<std::string>().starts_with(separable ? "q_1 = (E_hc" : "q_1 = 0"));
        CHECK(j.at("multiple_scattering_albedo").get<std::string>().find("F_avg^4 p / (1 - F_avg (1 - p))") !=
              std::string::npos);
        CHECK(j.at("alphas").get<std::vector<double>>() == o.q2.grid.alphas);
        CHECK(j.at("warp_scales").get<std::vector<double>>() == o.q2.grid.scales);
        CHECK(j.at("n_x").get<int>() == 9);
        CHECK(j.at("lookup").get<std::string>().find("bilinear in (sqrt(alpha), x)") != std::string::npos);
        CHECK(j.at("below_first_alpha").get<std::string>().find("first row") != std::string::npos);
        CHECK(j.at("max_standard_error_q2_q3").get<double>() == 2.1e-3);
    }
}

TEST_CASE("compensation formats: bad orders are refused, naming the item, and nothing is written",
          "[compensation][formats][orders]") {
    OrderTables o = small_orders(true);
    OrderExport e = order_export_of(o);
    // Each writer throws input_error with `item` in its message, and writes nothing.
    auto refused = [&](const std::string& item) {
        for (const auto& write : text_writers(write_orders_axes_json)) {
            std::ostringstream sink;
            CHECK_THROWS_AS(write(sink, e), input_error);
            CHECK_THROWS_WITH(write(sink, e), Catch::Contains(item));
            CHECK(sink.str().empty());
        }
    };
    CHECK_NOTHROW(source_of(e, Language::c));
    SECTION("no tables") {
        e.orders = nullptr;
        refused("no tables");
    }
    SECTION("q_1 and the G2 at odds") {
        e.g2 = "height-correlated";
        refused("a q_1 table with the height-correlated G2");
        o = small_orders(false);
        e.g2 = "separable";
        refused("no q_1 table with the separable G2");
    }
    SECTION("mismatched grids") {
        o.q3.grid.alphas[2] = 0.31;
        refused("q_3's grid is not q_2's");
        o = small_orders(true);
        o.p.grid.n_x = 10;
        refused("p's grid is not q_2's");
        o = small_orders(true);
        o.q1.grid.scales[0] *= 1.001;
        refused("q_1's grid is not q_2's");
        o = small_orders(true);
        o.q3.grid.cluster = {0.42, 0.02, 0.3};
        refused("q_3's grid is not q_2's");
    }
    SECTION("a grid the lookups cannot follow, tables of the wrong size or stored as ln") {
        for (AlbedoTable* t : {&o.q2, &o.q3, &o.p, &o.q1}) std::swap(t->grid.alphas[1], t->grid.alphas[2]);
        refused("alphas must ascend");
        o = small_orders(true);
        o.q2.values.pop_back();
        refused("q_2 has 44 values for 5 alphas x 9 cosines");
        o = small_orders(true);
        o.p.stored = Stored::log;
        refused("p is stored as ln");
    }
    SECTION("non-finite values") {
        o.q2.values[2 * 9 + 4] = std::nan("");
        refused("q_2 at alpha 0.3, x_4 = 0.5 is not a finite float");
        o = small_orders(true);
        o.q1.values[3] = HUGE_VAL;
        refused("q_1 at alpha 0.05, x_3");
    }
    SECTION("p outside (0, 1], q outside [0, 1]") {
        for (const double bad : {0.0, -0.1, 1.0 + 1e-9, 1e-40}) {
            o = small_orders(true);
            o.p.values[10] = bad;
            INFO("p " << bad);
            refused("p at alpha 0.12, x_1 = 0.125 is " + format_g17(bad) + ", outside (0, 1]");
        }
        for (const auto& [name, t] : {std::pair{"q_2", &o.q2}, {"q_3", &o.q3}, {"q_1", &o.q1}})
            for (const double bad : {-1e-9, 1.5}) {
                o = small_orders(true);
                t->values[7] = bad;
                INFO(name << " " << bad);
                refused(std::string(name) + " at alpha 0.05, x_7 = 0.875 is " + format_g17(bad) + ", outside [0, 1]");
            }
        o = small_orders(true);
        o.p.values[10] = 1.0;  // no walk hits a fourth time: allowed
        o.q2.values[0] = 0.0;
        o.q1.values[0] = 1.0;
        CHECK_NOTHROW(source_of(e, Language::c));
    }
    SECTION("the worst standard error") {
        e.max_stderr = std::nan("");
        refused("the worst standard error");
        e.max_stderr = -1e-3;
        refused("the worst standard error");
    }
}
