#include "fit/fit_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "fit/fit_data.hpp"
#include "fit/fit_pictures.hpp"
#include "fit/fit_results.hpp"
#include "fit/fit_shaders.hpp"
#include "fit/fit_trends.hpp"
#include "cluster/mpi_world.hpp"
#include "cluster/traffic_json.hpp"
#include "output/progress.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/fit/compensation.hpp"
#include "smithlab/fit/fit_model.hpp"
#include "smithlab/util/parallel.hpp"
#include "output/staged_directory.hpp"

namespace smithlab::fitrun {

namespace fs = std::filesystem;

namespace {

std::vector<const fit::DiffuseModel*> selected_models(const FitScene& s) {
    std::vector<const fit::DiffuseModel*> out;
    if (s.models.empty())
        for (const fit::DiffuseModel& m : fit::diffuse_models()) out.push_back(&m);
    else
        for (const std::string& name : s.models) out.push_back(&fit::find_diffuse_model(name));
    return out;
}

// Every model at its published constants, and each one with free constants fitted.
std::vector<Measured> fit_all(const FitScene& s, const NdfData& d) {
    const fit::FitData training{d.training, s.albedos, s.floor,
                                s.energy_bound ? s.training.alpha : std::vector<double>{}};
    std::vector<Measured> out;
    for (const fit::DiffuseModel* m : selected_models(s)) {
        out.push_back({std::string(m->name), m, m->published, {}});
        if (m->parameters.empty()) continue;
        const fit::LeastSquaresFit f = fit::fit_model(*m, training, d.label);
        out.push_back({std::string(m->name) + "-fitted", m, f.params, f.stderr_, f.chi2_dof(), f.iterations});
    }
    return out;
}

ErrorRow measure(const FitScene& s, const NdfData& d, const Measured& m) {
    const fit::FitData validation{d.validation, s.albedos, s.floor, {}};
    const fit::RelativeErrors rel = fit::relative_errors(*m.model, m.params, validation);
    const std::vector<double> thetas{0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 80.0, 85.0, 89.0};
    return {m.name,
            d.label,
            rel.rms,
            rel.max,
            fit::albedo_rms(*m.model, m.params, d.albedo, s.albedos),
            fit::chi2_per_value(*m.model, m.params, validation),
            fit::max_albedo(*m.model, m.params, s.training.alpha, thetas),
            fit::check_on_grid(*m.model, m.params, s.training.alpha)};
}

void write_constants(const fs::path& dir, const Results& r) {
    const auto& [data, fits] = r;
    std::ofstream csv(dir / "constants.csv", std::ios::binary);
    write_csv_record(csv, {"model", "ndf", "parameter", "value", "stderr"});
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    for (std::size_t n = 0; n < data.size(); ++n)
        for (const Measured& m : fits[n]) {
            if (!m.fitted()) continue;
            nlohmann::ordered_json params = nlohmann::ordered_json::object();
            for (std::size_t i = 0; i < m.params.size(); ++i) {
                const std::string p(m.model->parameters[i]);
                write_csv_record(csv, {m.name, data[n].label, p, format_g17(m.params[i]), format_g17(m.stderr_[i])});
                params[p] = {{"value", m.params[i]}, {"stderr", m.stderr_[i]}};
            }
            json.push_back({{"model", m.name}, {"ndf", data[n].label}, {"parameters", params},
                            {"chi2_dof_training", m.chi2_dof_training}, {"iterations", m.iterations}});
        }
    output::finish(csv, dir / "constants.csv");
    output::write_file(dir / "constants.json", json.dump(2) + "\n");
}

void write_errors(const fs::path& dir, const std::vector<ErrorRow>& rows) {
    std::ofstream csv(dir / "errors.csv", std::ios::binary);
    write_csv_record(csv, {"model", "ndf", "rms_rel", "max_rel", "albedo_rms", "chi2_dof"});
    for (const ErrorRow& r : rows)
        write_csv_record(csv, {r.model, r.ndf, format_g17(r.rms_rel), format_g17(r.max_rel), format_g17(r.albedo_rms),
                               format_g17(r.chi2_dof)});
    output::finish(csv, dir / "errors.csv");
}

// The traced values of a set beside every model's, one row per point and albedo (the residual maps' data).
void write_values(const fs::path& file, const FitScene& s, const Results& r, bool validation) {
    const auto& [data, fits] = r;
    std::ofstream csv(file, std::ios::binary);
    std::vector<std::string> header{"ndf", "alpha", "theta_i", "theta_o", "phi", "albedo", "value", "stderr"};
    for (const Measured& m : fits.front()) header.push_back(m.name);
    write_csv_record(csv, header);
    for (std::size_t n = 0; n < data.size(); ++n)
        for (const fit::DataPoint& p : validation ? data[n].validation : data[n].training)
            for (double a : s.albedos) {
                const walk::Estimate y = fit::at_albedo(p.moments, {a});
                std::vector<std::string> row{data[n].label,        format_g17(p.alpha), format_g17(p.dir.theta_i),
                                             format_g17(p.dir.theta_o), format_g17(p.dir.phi), format_g17(a),
                                             format_g17(y.value),  format_g17(y.stderr_)};
                for (const Measured& m : fits[n]) row.push_back(format_g17(fit::model_value(*m.model, m.params, p, a)));
                write_csv_record(csv, row);
            }
    output::finish(csv, file);
}

// Kulla-Conty energy compensation for each NDF family of the scene over compensation.alpha (no tracing: quadrature of
// the single-scattering BRDF of mirror facets): compensation.csv, compensation_avg.csv and a C header per family.
// Returns the Markdown table of E_avg.
std::string write_compensation(const fs::path& dir, const FitScene& s, const NdfRegistry& registry) {
    if (s.compensation.alpha.empty()) return "";
    std::vector<std::pair<std::string, fit::CompensationTable>> all;
    std::ostringstream md;
    md << "\n## Energy compensation (Kulla and Conty 2017), single scattering off mirror facets\n\n"
       << "E_avg, the cosine-weighted average of the directional albedo E(mu) (compensation.csv: E over cos theta; "
       << "the C headers smithlab_NDF.h: E over (alpha, mu) and E_avg over alpha for a renderer):\n\n| alpha |";
    for (const FitFamily& f : s.ndfs) md << " " << family_label(f) << " |";
    md << "\n|---:|";
    for (std::size_t n = 0; n < s.ndfs.size(); ++n) md << "---:|";
    md << "\n";
    std::vector<std::vector<double>> avg(s.ndfs.size());
    for (std::size_t n = 0; n < s.ndfs.size(); ++n) {
        std::vector<std::vector<double>> E;
        for (double a : s.compensation.alpha) {
            const AnyNdf ndf = make_ndf(registry, s.ndfs[n], a);
            fit::CompensationTable t = fit::compensation_table(ndf, static_cast<int>(s.compensation.mu));
            E.push_back(t.E);
            avg[n].push_back(t.E_avg);
            all.emplace_back(ndf.spec(), std::move(t));
        }
        const std::string label = family_label(s.ndfs[n]);
        const fs::path header_path = dir / (fit::compensation_header_name(label) + ".h");
        std::ofstream header(header_path, std::ios::binary);
        fit::write_compensation_header(header, label, s.compensation.alpha, all.back().second.mus, E, avg[n]);
        output::finish(header, header_path);
    }
    for (std::size_t i = 0; i < s.compensation.alpha.size(); ++i) {
        char a[32];
        std::snprintf(a, sizeof a, "%.4g", s.compensation.alpha[i]);
        md << "| " << a << " |";
        for (std::size_t n = 0; n < s.ndfs.size(); ++n) md << " " << std::fixed << std::setprecision(4) << avg[n][i] << " |";
        md << std::defaultfloat << "\n";
    }
    std::ofstream csv(dir / "compensation.csv", std::ios::binary);
    fit::write_compensation_csv(csv, all);
    output::finish(csv, dir / "compensation.csv");
    std::ofstream avg_csv(dir / "compensation_avg.csv", std::ios::binary);
    fit::write_compensation_avg_csv(avg_csv, all);
    output::finish(avg_csv, dir / "compensation_avg.csv");
    return md.str();
}

// One NDF's table of errors on the validation set, best first, and the bound of the split's last bin.
void write_errors_table(std::ostream& md, const FitScene& s, const NdfData& d, const std::vector<ErrorRow>& errors) {
    std::vector<ErrorRow> rows;
    for (const ErrorRow& e : errors)
        if (e.ndf == d.label) rows.push_back(e);
    std::sort(rows.begin(), rows.end(), [](const ErrorRow& a, const ErrorRow& b) { return a.rms_rel < b.rms_rel; });
    double tail = 0.0;  // the last diffuse-event bin's bound, as a share of the value (fit/dataset.hpp)
    for (const fit::DataPoint& p : d.training)
        for (double a : s.albedos)
            if (const double y = fit::at_albedo(p.moments, {a}).value; y > 0.0)
                tail = std::max(tail, fit::tail_bound(p.moments, {a}) / y);
    md << "\n## " << d.label << ": errors on the validation set (" << d.validation.size() << " points, "
       << d.albedo.size() << " directional albedos; never fitted)\n\n";
    md << "(The split's last bin, k >= " << fit::diffuse_bins - 1 << " diffuse events, weighted albedo^"
       << fit::diffuse_bins - 1 << ": at most " << tail << " of any training value at these albedos.)\n\n";
    md << "| model | RMS rel. error of f cos | max rel. error | RMS error of the directional albedo | chi^2 / value "
       << "| largest albedo at albedo 1 (alpha, theta_i) | asymmetry | smallest f |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    char line[512];
    for (const ErrorRow& e : rows) {
        const char* bold = e.peak.albedo > 1.0 + 1e-3 ? "**" : "";
        const char* negative = e.grid.min_f < 0.0 ? "**" : "";
        std::snprintf(line, sizeof line,
                      "| %s | %.4f | %.4f | %.5f | %.3g | %s%.4f%s (%.3g, %.0f) | %.1e | %s%.3g%s |\n",
                      e.model.c_str(), e.rms_rel, e.max_rel, e.albedo_rms, e.chi2_dof, bold, e.peak.albedo, bold,
                      e.peak.alpha, e.peak.theta_i, e.grid.asymmetry, negative, e.grid.min_f, negative);
        md << line;
    }
}

// report.md: the errors of every model on the validation set, NDF by NDF, best first; the fitted constants; then the
// compensation and picture sections.
void write_report(const fs::path& dir, const FitScene& s, const Results& r, const std::vector<ErrorRow>& errors,
                  const std::string& sections) {
    std::ofstream md(dir / "report.md", std::ios::binary);
    md << "# " << s.title << "\n\nFacets `" << s.material << "`, traced at albedo 1 and split by diffuse events; "
       << "fitted and measured at albedo";
    for (double a : s.albedos) md << " " << format_shortest(a);
    md << " (the diffuse part: paths with at least one diffuse event), weights with a relative floor of "
       << format_shortest(s.floor) << ".\n";
    for (const NdfData& d : r.data) write_errors_table(md, s, d, errors);
    md << "\nLargest albedo: the directional albedo at albedo 1, largest over the training alphas and theta_i from 0 to 89 "
          "degrees (in bold where above 1: the model makes energy there). Asymmetry: the largest relative difference "
          "|f(l, v) - f(v, l)| / f over the training alphas and a grid of direction pairs (0 for a reciprocal BRDF). "
          "Smallest f: the least BRDF value on that grid at albedo 0.5 and 1 (bold where negative: not a BRDF there). "
          "chi^2 / value: on the validation set, with the fit's weights (the relative floor included, so a model "
          "within the floor scores below 1).\n";
    md << "\n## Fitted constants (standard errors scaled by sqrt(chi^2 / dof) where that is above 1)\n\n"
       << "| model | ndf | constants |\n|---|---|---|\n";
    for (std::size_t n = 0; n < r.data.size(); ++n)
        for (const Measured& m : r.fits[n]) {
            if (!m.fitted()) continue;
            md << "| " << m.name << " | " << r.data[n].label << " |";
            for (std::size_t i = 0; i < m.params.size(); ++i) {
                char v[96];
                std::snprintf(v, sizeof v, " %s = %.5g +- %.2g", std::string(m.model->parameters[i]).c_str(),
                              m.params[i], m.stderr_[i]);
                md << v << (i + 1 < m.params.size() ? "," : "");
            }
            md << " |\n";
        }
    md << sections;
    output::finish(md, dir / "report.md");
}

}  // namespace

FitSummary run_fit(const FitScene& s, const std::string& source, const std::string& scene_text,
                   const NdfRegistry& registry, const fs::path& out, unsigned threads) {
    const auto t0 = std::chrono::steady_clock::now();
    std::optional<output::StagedDirectory> stage;
    output::ProgressLine line;
    auto progress = [&](std::int64_t done, std::int64_t total) {
        line(static_cast<double>(done) / static_cast<double>(total),
             [&] { return "fit: traced " + std::to_string(done) + " of " + std::to_string(total) + " points"; });
    };
    // Under MPI every rank checks the scene's NDFs alike, then the ranks trace together; rank 0 alone owns OUT, and
    // fits, measures and draws (the pictures' few traces on its threads) while the others are done.
    cluster::Traffic traffic;
    Results r{gather(
                  s, registry, out / "cache", threads, progress,
                  [&] {
                      if (mpi::size() > 1) mpi::set_talking();
                      if (mpi::rank() == 0) stage.emplace(out, "fit");  // refuses a bad OUT before any work
                  },
                  &traffic),
              {}};
    if (mpi::rank() != 0) return {};
    const double trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    FitSummary sum;
    std::int64_t walks = 0;
    for (const NdfData& d : r.data) {
        walks += d.walks_traced;
        sum.traced += d.traced;
        sum.reused += d.reused;
        r.fits.push_back(fit_all(s, d));
        for (const Measured& m : r.fits.back()) sum.errors.push_back(measure(s, d, m));
    }
    sum.points = sum.traced + sum.reused;
    if (sum.traced)
        std::fprintf(stderr, "fit: traced %lld points, %.4g walks, in %.1f s (%.0f ns a walk on %u threads x %d ranks)\n",
                     static_cast<long long>(sum.traced), static_cast<double>(walks), trace_seconds,
                     trace_seconds / static_cast<double>(walks) * 1e9,
                     util::thread_count(threads), mpi::size());
    write_constants(stage->path(), r);
    write_errors(stage->path(), sum.errors);
    write_values(stage->path() / "training.csv", s, r, false);
    write_values(stage->path() / "validation.csv", s, r, true);
    write_shaders(stage->path(), r);
    const std::string compensation = write_compensation(stage->path(), s, registry);
    const std::string pictures = write_pictures(stage->path(), s, r, registry, threads);
    const std::string trends = write_parameter_trends(stage->path(), r);
    write_report(stage->path(), s, r, sum.errors, trends + compensation + pictures);
    sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::ordered_json meta = {
        {"title", s.title},      {"source", source},         {"scene", scene_text},
        {"version", SMITHLAB_VERSION}, {"seed", s.seed},      {"points_traced", sum.traced},
        {"points_reused", sum.reused}, {"walks_traced", walks}, {"seconds", sum.seconds}, {"trace_seconds", trace_seconds},
        {"threads", util::thread_count(threads)}};
    if (mpi::size() > 1) meta["mpi"] = cluster::traffic_json(traffic);  // and threads is per rank
    output::write_file(stage->path() / "meta.json", meta.dump(2) + "\n");
    stage->publish();
    return sum;
}

}  // namespace smithlab::fitrun
