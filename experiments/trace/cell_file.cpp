#include "trace/cell_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string_view>

#include "output/sealed_file.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::trace {

namespace fs = std::filesystem;

fs::path cell_path(const fs::path& out, std::uint64_t index) {
    return out / "cells" / format_printf("cell-%06llu.csv", static_cast<unsigned long long>(index));
}

std::string cell_key(const CellSettings& w, const TraceCell& c, const AnyNdf& ndf, const walk::Material& m) {
    std::ostringstream k;
    k << "smithlab " << SMITHLAB_VERSION << "|ndf=" << ndf.key() << "|material=" << m.spec()
      << "|theta_i=" << format_g17(c.theta_i) << "|phi_i=" << format_g17(c.phi_i) << "|walks=" << w.walks
      << "|seed=" << w.seed << "|cell=" << c.index << "|max_order=" << w.max_order << "|downward=" << w.downward
      << "|hit_normal=" << w.hit_normal << "|brdf=" << w.brdf.n_theta << "x" << w.brdf.n_phi;
    return k.str();
}

void write_cell(const fs::path& path, const std::string& key, const CellRows& rows) {
    std::ostringstream body;
    body << "key," << csv_field(key) << "\n"
         << "bounces," << rows.bounces << "\n"
         << "capped," << rows.capped << "\n"
         << "total," << format_g17(rows.total.value) << "," << format_g17(rows.total.stderr_) << "\n";
    for (const std::string& a : rows.albedo) body << "a," << a << "\n";
    for (const std::string& b : rows.brdf) body << "b," << b << "\n";
    output::write_sealed(path, body.str());
}

namespace {

// A line "TAG,INTEGER" into v.
bool read_integer(std::istream& in, const char* tag, std::int64_t& v) {
    std::string line;
    if (!std::getline(in, line) || line.rfind(std::string(tag) + ",", 0) != 0) return false;
    char* end = nullptr;
    v = std::strtoll(line.c_str() + std::strlen(tag) + 1, &end, 10);
    return *end == '\0';
}

// The line "total,VALUE,STDERR" into e.
bool read_total(std::istream& in, walk::Estimate& e) {
    std::string line;
    if (!std::getline(in, line) || line.rfind("total,", 0) != 0) return false;
    char* end = nullptr;
    e.value = std::strtod(line.c_str() + 6, &end);
    if (*end != ',') return false;
    e.stderr_ = std::strtod(end + 1, &end);
    return *end == '\0' && std::isfinite(e.value) && std::isfinite(e.stderr_);
}

// False when a comma-separated piece of `row` reads whole as a number that is not finite ("nan", "inf"). A piece of a
// quoted field never reads whole as a number, so the plain split is enough.
bool finite_numbers(std::string_view row) {
    for (std::size_t at = 0; at <= row.size();) {
        const std::size_t end = std::min(row.find(',', at), row.size());
        double x = 0.0;
        const auto r = std::from_chars(row.data() + at, row.data() + end, x);
        if (r.ec == std::errc{} && r.ptr == row.data() + end && !std::isfinite(x)) return false;
        at = end + 1;
    }
    return true;
}

// The "a," and "b," lines to the end; false at any other line or a number that is not finite.
bool read_rows(std::istream& in, CellRows& rows) {
    for (std::string line; std::getline(in, line);) {
        if (!finite_numbers(line)) return false;
        if (line.rfind("a,", 0) == 0) rows.albedo.push_back(line.substr(2));
        else if (line.rfind("b,", 0) == 0) rows.brdf.push_back(line.substr(2));
        else return false;
    }
    return true;
}

// "cell 3" for OUT/cells/cell-000003.csv (cell_path), else the path.
std::string cell_name(const fs::path& path) {
    const std::string stem = path.stem().string();
    std::uint64_t index = 0;
    const char* digits = stem.data() + std::min<std::size_t>(5, stem.size());
    const auto r = std::from_chars(digits, stem.data() + stem.size(), index);
    if (stem.rfind("cell-", 0) == 0 && r.ec == std::errc{} && r.ptr == stem.data() + stem.size())
        return "cell " + std::to_string(index);
    return "cell file " + path.string();
}

}  // namespace

std::optional<CellRows> read_cell(const fs::path& path, const std::string& key, std::size_t albedo_rows,
                                  std::size_t brdf_rows) {
    const std::optional<std::string> body = output::read_sealed(path, "trace: " + cell_name(path));
    if (!body) return std::nullopt;
    std::istringstream in{*body};
    std::string line;
    if (!std::getline(in, line) || line != "key," + csv_field(key)) return std::nullopt;
    CellRows rows;
    if (!read_integer(in, "bounces", rows.bounces) || !read_integer(in, "capped", rows.capped) ||
        !read_total(in, rows.total) || !read_rows(in, rows))
        return std::nullopt;
    if (rows.albedo.size() != albedo_rows || rows.brdf.size() != brdf_rows) return std::nullopt;
    return rows;
}

}  // namespace smithlab::trace
