#include "fit/fit_tables.hpp"

#include <fstream>
#include <nlohmann/json.hpp>

#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

void write_constants(const fs::path& dir, const Results& r, const LabelColumns& all) {
    const auto& [data, fits] = r;
    const std::vector<std::string> own{"model", "ndf", "parameter", "value", "stderr"};
    const LabelColumns columns = all.except(own);
    std::ofstream csv(dir / "constants.csv", std::ios::binary);
    write_csv_record(csv, columns.header(own, 2));
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    for (std::size_t n = 0; n < data.size(); ++n)
        for (const Measured& m : fits[n]) {
            if (!m.fitted()) continue;
            nlohmann::ordered_json params = nlohmann::ordered_json::object();
            for (std::size_t i = 0; i < m.params.size(); ++i) {
                const std::string p(m.model->parameters[i]);
                write_csv_record(
                    csv,
                    columns.row({m.name, data[n].label, p, format_g17(m.params[i]), format_g17(m.stderr_[i])}, 2,
                                data[n].label));
                params[p] = {{"value", m.params[i]}, {"stderr", m.stderr_[i]}};
            }
            json.push_back({{"model", m.name},
                            {"ndf", data[n].label},
                            {"parameters", params},
                            {"chi2_dof_training", m.chi2_dof_training},
                            {"iterations", m.iterations}});
        }
    output::finish(csv, dir / "constants.csv");
    output::write_file(dir / "constants.json", json.dump(2) + "\n");
}

void write_errors(const fs::path& dir, const std::vector<ErrorRow>& rows, const LabelColumns& all) {
    const std::vector<std::string> own{"model", "ndf", "rms_rel", "max_rel", "albedo_rms", "chi2_dof"};
    const LabelColumns columns = all.except(own);
    std::ofstream csv(dir / "errors.csv", std::ios::binary);
    write_csv_record(csv, columns.header(own, 2));
    for (const ErrorRow& r : rows)
        write_csv_record(csv,
                         columns.row({r.model, r.ndf, format_g17(r.rms_rel), format_g17(r.max_rel),
                                      format_g17(r.albedo_rms), format_g17(r.chi2_dof)},
                                     2, r.ndf));
    output::finish(csv, dir / "errors.csv");
}

void write_values(const fs::path& file, const Results& r, ValueSet set, const std::vector<double>& albedos,
                  const LabelColumns& all) {
    const auto& [data, fits] = r;
    std::vector<std::string> own{"ndf", "alpha", "theta_i", "theta_o", "phi", "albedo", "value", "stderr"};
    for (const Measured& m : fits.front()) own.push_back(m.name);
    const LabelColumns columns = all.except(own);
    std::ofstream csv(file, std::ios::binary);
    write_csv_record(csv, columns.header(own, 1));
    for (std::size_t n = 0; n < data.size(); ++n)
        for (const fit::DataPoint& p : set == ValueSet::validation ? data[n].validation : data[n].training)
            for (double a : albedos) {
                const walk::Estimate y = fit::at_albedo(p.moments, {a});
                std::vector<std::string> row{
                    data[n].label,         format_g17(p.alpha), format_g17(p.dir.theta_i), format_g17(p.dir.theta_o),
                    format_g17(p.dir.phi), format_g17(a),       format_g17(y.value),       format_g17(y.stderr_)};
                for (const Measured& m : fits[n]) row.push_back(format_g17(fit::model_value(*m.model, m.params, p, a)));
                write_csv_record(csv, columns.row(std::move(row), 1, data[n].label));
            }
    output::finish(csv, file);
}

}  // namespace smithlab::fit
