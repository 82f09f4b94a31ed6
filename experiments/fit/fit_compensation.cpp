#include "fit/fit_compensation.hpp"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "fit/fit_data.hpp"
#include "output/ndf_columns.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/fit/compensation.hpp"

namespace smithlab::fitrun {

namespace fs = std::filesystem;

namespace {

using Tables = std::vector<std::pair<std::string, fit::CompensationTable>>;

// The section's table: E_avg per alpha (rows) and family (columns).
std::string markdown(const std::vector<FitFamily>& families, const std::vector<double>& alphas,
                     const std::vector<std::vector<double>>& avg) {
    std::ostringstream md;
    md << "\n## Energy compensation (Kulla and Conty 2017), single scattering off mirror facets\n\n"
       << "E_avg, the cosine-weighted average of the directional albedo E(mu) (compensation.csv: E over cos theta; "
       << "the C headers smithlab_NDF.h: E over (alpha, mu) and E_avg over alpha for a renderer):\n\n| alpha |";
    for (const FitFamily& f : families) md << " " << family_label(f) << " |";
    md << "\n|---:|";
    for (std::size_t n = 0; n < families.size(); ++n) md << "---:|";
    md << "\n";
    for (std::size_t i = 0; i < alphas.size(); ++i) {
        char a[32];
        std::snprintf(a, sizeof a, "%.4g", alphas[i]);
        md << "| " << a << " |";
        for (std::size_t n = 0; n < families.size(); ++n)
            md << " " << std::fixed << std::setprecision(4) << avg[n][i] << " |";
        md << std::defaultfloat << "\n";
    }
    return md.str();
}

// Both CSVs, the ndf column followed by one column per NDF parameter.
void write_csvs(const fs::path& dir, const Tables& tables, const std::vector<AnyNdf>& ndfs) {
    auto columns = [&](const std::vector<std::string>& own) {
        const output::NdfColumns c = output::ndf_columns(ndfs, own);
        fit::SpecColumns out{c.names, {}};
        for (const AnyNdf& n : ndfs) out.cells.push_back(c.cells(n));
        return out;
    };
    std::ofstream csv(dir / "compensation.csv", std::ios::binary);
    fit::write_compensation_csv(csv, tables, columns({"ndf", "cos_theta", "E"}));
    output::finish(csv, dir / "compensation.csv");
    std::ofstream avg_csv(dir / "compensation_avg.csv", std::ios::binary);
    fit::write_compensation_avg_csv(avg_csv, tables, columns({"ndf", "E_avg"}));
    output::finish(avg_csv, dir / "compensation_avg.csv");
}

}  // namespace

std::string write_compensation(const fs::path& dir, const std::vector<FitFamily>& families,
                               const FitScene::Compensation& c, const NdfRegistry& registry) {
    if (c.alpha.empty()) return "";
    Tables all;
    std::vector<AnyNdf> ndfs;
    std::vector<std::vector<double>> avg(families.size());
    for (std::size_t n = 0; n < families.size(); ++n) {
        std::vector<std::vector<double>> E;
        for (double a : c.alpha) {
            ndfs.push_back(make_ndf(registry, families[n], a));
            fit::CompensationTable t = fit::compensation_table(ndfs.back(), static_cast<int>(c.mu));
            E.push_back(t.E);
            avg[n].push_back(t.E_avg);
            all.emplace_back(ndfs.back().spec(), std::move(t));
        }
        const std::string label = family_label(families[n]);
        const fs::path header_path = dir / (fit::compensation_header_name(label) + ".h");
        std::ofstream header(header_path, std::ios::binary);
        fit::write_compensation_header(header, label, c.alpha, all.back().second.mus, E, avg[n]);
        output::finish(header, header_path);
    }
    write_csvs(dir, all, ndfs);
    return markdown(families, c.alpha, avg);
}

}  // namespace smithlab::fitrun
