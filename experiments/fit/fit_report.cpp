#include "fit/fit_report.hpp"

#include <algorithm>
#include <fstream>

#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

// The bound of the split's last bin, as a share of the largest training value (fit/dataset.hpp: tail_bound).
double tail_share(const NdfData& d, const std::vector<double>& albedos) {
    double tail = 0.0;
    for (const fit::DataPoint& p : d.training)
        for (double a : albedos)
            if (const double y = fit::at_albedo(p.moments, {a}).value; y > 0.0)
                tail = std::max(tail, fit::tail_bound(p.moments, {a}) / y);
    return tail;
}

// One NDF's table of errors on the validation set, best first, and the bound of the split's last bin.
void write_errors_table(std::ostream& md, const NdfData& d, const std::vector<double>& albedos,
                        const std::vector<ErrorRow>& errors) {
    std::vector<ErrorRow> rows;
    for (const ErrorRow& e : errors)
        if (e.ndf == d.label) rows.push_back(e);
    std::sort(rows.begin(), rows.end(), [](const ErrorRow& a, const ErrorRow& b) { return a.rms_rel < b.rms_rel; });
    md << "\n## " << d.label << ": errors on the validation set (" << d.validation.size() << " points, "
       << d.albedo.size() << " directional albedos; never fitted)\n\n";
    md << "(The split's last bin, k >= " << fit::diffuse_bins - 1 << " diffuse events, weighted albedo^"
       << fit::diffuse_bins - 1 << ": at most " << tail_share(d, albedos)
       << " of any training value at these albedos.)\n\n";
    md << "| model | RMS rel. error of f cos | max rel. error | RMS error of the directional albedo | chi^2 / value "
       << "| largest albedo at albedo 1 (alpha, theta_i) | asymmetry | smallest f |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const ErrorRow& e : rows) {
        const char* bold = e.peak.albedo > 1.0 + 1e-3 ? "**" : "";
        const char* negative = e.grid.min_f < 0.0 ? "**" : "";
        md << format_printf("| %s | %.4f | %.4f | %.5f | %.3g | %s%.4f%s (%.3g, %.0f) | %.1e | %s%.3g%s |\n",
                            e.model.c_str(), e.rms_rel, e.max_rel, e.albedo_rms, e.chi2_dof, bold, e.peak.albedo, bold,
                            e.peak.alpha, e.peak.theta_i, e.grid.asymmetry, negative, e.grid.min_f, negative);
    }
}

void write_constants_table(std::ostream& md, const Results& r) {
    md << "\n## Fitted constants (standard errors scaled by sqrt(chi^2 / dof) where that is above 1)\n\n"
       << "| model | ndf | constants |\n|---|---|---|\n";
    for (std::size_t n = 0; n < r.data.size(); ++n)
        for (const Measured& m : r.fits[n]) {
            if (!m.fitted()) continue;
            md << "| " << m.name << " | " << r.data[n].label << " |";
            for (std::size_t i = 0; i < m.params.size(); ++i) {
                md << format_printf(" %s = %.5g +- %.2g", std::string(m.model->parameters[i]).c_str(), m.params[i],
                                    m.stderr_[i])
                   << (i + 1 < m.params.size() ? "," : "");
            }
            md << " |\n";
        }
}

}  // namespace

void write_report(const fs::path& dir, const ReportHeading& h, const Results& r, const std::vector<ErrorRow>& errors,
                  const std::string& flags, const std::string& sections) {
    std::ofstream md(dir / "report.md", std::ios::binary);
    md << "# " << h.title << "\n\nFacets `" << h.material << "`, traced at albedo 1 and split by diffuse events; "
       << "fitted and measured at albedo";
    for (double a : h.albedos) md << " " << format_shortest(a);
    md << " (the diffuse part: paths with at least one diffuse event), weights with a relative floor of "
       << format_shortest(h.floor) << ".\n";
    for (const NdfData& d : r.data) write_errors_table(md, d, h.albedos, errors);
    md << "\nLargest albedo: the directional albedo at albedo 1, largest over the training alphas and theta_i from 0 "
          "to 89 "
          "degrees (in bold where above 1: the model makes energy there). Asymmetry: the largest relative difference "
          "|f(l, v) - f(v, l)| / f over the training alphas and a grid of direction pairs (0 for a reciprocal BRDF). "
          "Smallest f: the least BRDF value on that grid at albedo 0.5 and 1 (bold where negative: not a BRDF there). "
          "chi^2 / value: on the validation set, with the fit's weights (the relative floor included, so a model "
          "within the floor scores below 1).\n";
    md << flags;
    write_constants_table(md, r);
    md << sections;
    output::finish(md, dir / "report.md");
}

}  // namespace smithlab::fit
