#include "trace/trace_rows.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "output/ndf_columns.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::trace {

namespace {

const char* const hemisphere_name[] = {"reflection", "transmission", "all"};
const char* const component_name[] = {"specular", "diffuse", "all"};
const char* const order_name[] = {"1", "2", "3", "4+", "all"};
constexpr int order_columns = walk::order_bins + 1;  // 1, 2, 3, 4+, all

const std::vector<std::string> albedo_columns = {"ndf",   "material",  "theta_i", "phi_i",  "hemisphere",
                                                 "order", "component", "albedo",  "stderr", "walks"};
const std::vector<std::string> brdf_columns = {"ndf",        "material",   "theta_i",  "phi_i",    "hemisphere",
                                               "theta_o_lo", "theta_o_hi", "phi_o_lo", "phi_o_hi", "order",
                                               "component",  "value",      "stderr",   "walks"};

// One CSV record, without its line end.
std::string record(const std::vector<std::string>& fields) {
    std::string s;
    for (std::size_t k = 0; k < fields.size(); ++k) {
        if (k) s += ',';
        s += csv_field(fields[k]);
    }
    return s;
}

// The tally's order selection of column o (1, 2, 3, 4+, all).
int order_of(int o) { return o == walk::order_bins ? walk::all_orders : o; }

// Band t of n equal bands of |cos theta_o| from the pole, in degrees from the macro normal (tally.hpp).
std::pair<double, double> band_degrees(int t, int n, bool transmission) {
    const double deg = 180.0 / std::numbers::pi;
    const double lo = std::acos(1.0 - static_cast<double>(t) / n) * deg,
                 hi = std::acos(std::max(0.0, 1.0 - static_cast<double>(t + 1) / n)) * deg;
    return transmission ? std::pair{180.0 - hi, 180.0 - lo} : std::pair{lo, hi};
}

std::vector<std::string> albedo_rows(const CellLabel& l, const walk::AlbedoTally& a) {
    std::vector<std::string> rows;
    for (int h = 0; h < 3; ++h)
        for (int o = 0; o < order_columns; ++o)
            for (int c = 0; c < 3; ++c) {
                const walk::Estimate e =
                    a.albedo(static_cast<walk::Hemisphere>(h), order_of(o), static_cast<walk::Component>(c));
                rows.push_back(record({l.ndf, l.material, l.theta_i, l.phi_i, hemisphere_name[h], order_name[o],
                                       component_name[c], format_g17(e.value), format_g17(e.stderr_), l.walks}));
            }
    return rows;
}

std::vector<std::string> brdf_rows(const CellLabel& l, const walk::BrdfTally& b) {
    std::vector<std::string> rows;
    const double sector = 360.0 / b.bins.n_phi;
    for (int h = 0; h < (b.bins.transmission ? 2 : 1); ++h)
        for (int t = 0; t < b.bins.n_theta; ++t)
            for (int q = 0; q < b.bins.n_phi; ++q) {
                const auto [theta_lo, theta_hi] = band_degrees(t, b.bins.n_theta, h == 1);
                for (int o = 0; o < order_columns; ++o)
                    for (int c = 0; c < 3; ++c) {
                        const walk::Estimate e = b.value(h, t, q, order_of(o), static_cast<walk::Component>(c));
                        rows.push_back(record({l.ndf, l.material, l.theta_i, l.phi_i, hemisphere_name[h],
                                               format_g17(theta_lo), format_g17(theta_hi), format_g17(q * sector),
                                               format_g17((q + 1) * sector), order_name[o], component_name[c],
                                               format_g17(e.value), format_g17(e.stderr_), l.walks}));
                    }
            }
    return rows;
}

// Where a row's first field (the NDF spec, quoted when it holds a comma or a quote) ends.
std::size_t first_field_end(const std::string& row) {
    if (row.empty() || row[0] != '"') return row.find(',');
    for (std::size_t i = 1; i < row.size(); ++i)
        if (row[i] == '"') {
            if (i + 1 < row.size() && row[i + 1] == '"') ++i;
            else return i + 1;
        }
    return std::string::npos;
}

// The header of a table of `columns` with the parameter columns after the first (ndf).
std::string header(const std::vector<std::string>& columns, const std::vector<std::string>& params) {
    std::vector<std::string> all = {columns.front()};
    all.insert(all.end(), params.begin(), params.end());
    all.insert(all.end(), columns.begin() + 1, columns.end());
    return record(all);
}

// Writes `rows` to out, each with `params` (",CELL" per parameter column) after its first field.
void write_rows(std::ostream& out, const std::vector<std::string>& rows, const std::string& params) {
    for (const std::string& row : rows) {
        const std::size_t at = first_field_end(row);
        if (at == std::string::npos) throw std::logic_error("trace: a row without its ndf field: " + row);
        out.write(row.data(), static_cast<std::streamsize>(at));
        out << params;
        out.write(row.data() + at, static_cast<std::streamsize>(row.size() - at));
        out << '\n';
    }
}

}  // namespace

CellLabel cell_label(const AnyNdf& ndf, const walk::Material& m, const TraceCell& cell, std::int64_t walks) {
    return {ndf.spec(), m.spec(), format_shortest(cell.theta_i), format_shortest(cell.phi_i), std::to_string(walks)};
}

CellRows cell_rows(const CellLabel& label, const walk::CellResult& r) {
    CellRows rows;
    rows.bounces = r.albedo.events;
    rows.capped = r.albedo.capped;
    rows.total = r.albedo.albedo(walk::Hemisphere::all, walk::all_orders, walk::Component::all);
    rows.albedo = albedo_rows(label, r.albedo);
    if (r.brdf) rows.brdf = brdf_rows(label, *r.brdf);
    return rows;
}

std::size_t albedo_row_count() { return 3u * order_columns * 3; }

std::size_t brdf_row_count(const walk::BrdfBins& bins, bool transmits) {
    if (bins.empty()) return 0;
    return (transmits ? 2u : 1u) * static_cast<std::size_t>(bins.n_theta) * bins.n_phi * order_columns * 3;
}

void write_tables(const std::filesystem::path& dir, std::span<const AnyNdf> ndfs, std::span<const CellRows> rows,
                  bool brdf) {
    std::vector<std::string> taken = albedo_columns;
    taken.insert(taken.end(), brdf_columns.begin(), brdf_columns.end());
    const output::NdfColumns columns = output::ndf_columns(ndfs, taken);
    std::ofstream albedo(dir / "albedo.csv", std::ios::binary);
    albedo << header(albedo_columns, columns.names) << "\n";
    std::optional<std::ofstream> brdf_file;
    if (brdf) brdf_file.emplace(dir / "brdf.csv", std::ios::binary) << header(brdf_columns, columns.names) << "\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
        std::string params;
        for (const std::string& cell : columns.cells(ndfs[i])) {
            params += ',';
            params += csv_field(cell);
        }
        write_rows(albedo, rows[i].albedo, params);
        if (brdf_file) write_rows(*brdf_file, rows[i].brdf, params);
    }
    output::finish(albedo, dir / "albedo.csv");
    if (brdf_file) output::finish(*brdf_file, dir / "brdf.csv");
}

}  // namespace smithlab::trace
