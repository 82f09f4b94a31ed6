#include "fit/picture_tables.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "fit/fit_trends.hpp"
#include "fit/picture_traces.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

// The value of a diffuse-event split at an albedo: k >= min_k, or exactly k = 1 (min_k = -1, single scattering).
double split_value(const fit::SplitMoments& m, double albedo, int min_k) {
    if (min_k < 0) return fit::at_albedo(m, {albedo, 1}).value - fit::at_albedo(m, {albedo, 2}).value;
    return fit::at_albedo(m, {albedo, min_k}).value;
}

double model_f(const Measured& m, const Vec3& light, const Vec3& view, double alpha, double albedo) {
    return m.model->f(light, view, alpha, albedo, m.params.empty() ? nullptr : m.params.data());
}

// Six significant digits: the pictures' values (the spheres' CSV holds ~10^5 rows per NDF).
std::string short_g(double v) { return format_printf("%.6g", v); }

// 1 - E_1/E = E_{k>=2}/E_{k>=1} for Lambertian facets (every event diffuse: k is the scattering order), with its
// standard error by the delta method (the two means share their walks: fit::covariance).
std::pair<double, double> missing_fraction(const fit::SplitMoments& m, double albedo) {
    const fit::AlbedoPower all{albedo, 1}, multi{albedo, 2};
    const walk::Estimate e = fit::at_albedo(m, all), em = fit::at_albedo(m, multi);
    if (!(e.value > 0.0)) return {0.0, 0.0};
    const double r = em.value / e.value;
    const double var =
        (em.stderr_ * em.stderr_ - 2.0 * r * fit::covariance(m, all, multi) + r * r * e.stderr_ * e.stderr_) /
        (e.value * e.value);
    return {r, std::sqrt(std::max(0.0, var))};
}

const std::vector<std::string> spheres_header{"ndf", "source", "alpha", "light_deg", "albedo", "px", "py", "value"};
const std::vector<std::string> slices_header{"ndf", "source", "alpha", "theta_h", "theta_d", "value", "stderr"};
const std::vector<std::string> missing_header{"ndf", "alpha", "theta", "albedo", "E", "E1", "missing", "stderr"};
const std::vector<std::string> index_header{"ndf", "stem", "pixels"};

}  // namespace

std::vector<const Measured*> drawn_models(const std::vector<Measured>& fits) {
    std::vector<const Measured*> out;
    for (const char* base : {"lambert", "disney", "eon"})
        for (const Measured& m : fits)
            if (m.name == base) out.push_back(&m);
    for (const Measured& m : fits)
        if (m.fitted()) out.push_back(&m);
    return out;
}

std::string file_stem(const std::string& label) {
    std::string d;
    for (char c : label) d += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-' ? c : '_';
    while (!d.empty() && d.back() == '_') d.pop_back();
    return d;
}

PictureFiles::PictureFiles(const fs::path& d, const LabelColumns& columns)
    : dir_(d),
      spheres_columns_(columns.except(spheres_header)),
      slices_columns_(columns.except(slices_header)),
      missing_columns_(columns.except(missing_header)),
      index_columns_(columns.except(index_header)),
      spheres_(d / "spheres.csv", std::ios::binary),
      slices_(d / "slices.csv", std::ios::binary),
      missing_(d / "missing.csv", std::ios::binary),
      index_(d / "ndfs.csv", std::ios::binary) {
    write_csv_record(spheres_, spheres_columns_.header(spheres_header, 1));
    write_csv_record(slices_, slices_columns_.header(slices_header, 1));
    write_csv_record(missing_, missing_columns_.header(missing_header, 1));
    write_csv_record(index_, index_columns_.header(index_header, 1));
}

void PictureFiles::ndf(const std::string& label, int pixels) {
    write_csv_record(index_, index_columns_.row({label, file_stem(label), std::to_string(pixels)}, 1, label));
}

void PictureFiles::spheres(const std::string& label, double alpha, const SphereGroup& g,
                           const std::vector<fit::SplitMoments>& sim, const std::vector<fit::SplitMoments>& lam,
                           const std::vector<const Measured*>& models) {
    struct Source {
        std::string name;
        const std::vector<fit::SplitMoments>* m;
        int min_k;
    };
    const std::vector<Source> traced{{"simulation, diffuse only", &sim, 1},
                                     {"simulation with spec", &sim, 0},
                                     {"lambert facets: direct only", &lam, -1},
                                     {"lambert facets: direct plus indirect", &lam, 1},
                                     {"lambert facets: indirect only", &lam, 2}};
    const std::string a = format_g17(alpha);
    auto row = [&](const std::string& source, const Pixel& p, double albedo, double v) {
        write_csv_record(spheres_,
                         spheres_columns_.row({label, source, a, format_g17(light_degrees[p.light]), format_g17(albedo),
                                               std::to_string(p.px), std::to_string(p.py), short_g(v)},
                                              1, label));
    };
    for (const Source& s : traced)
        for (double albedo : sphere_albedos)
            for (std::size_t i = 0; i < g.pixels.size(); ++i)
                row(s.name, g.pixels[i], albedo, split_value((*s.m)[g.source[i]], albedo, s.min_k));
    for (const Measured* m : models)
        for (double albedo : sphere_albedos)
            for (const Pixel& p : g.pixels)
                row(m->name, p, albedo, model_f(*m, p.local.wo, p.local.wi, alpha, albedo) * p.cos_light);
}

void PictureFiles::slices(const std::string& label, double alpha, int n, const std::vector<Pair>& pts,
                          const std::vector<fit::SplitMoments>& sim, const std::vector<const Measured*>& models) {
    const std::string a = format_g17(alpha);
    for (std::size_t k = 0; k < pts.size(); ++k) {
        const Pair& p = pts[k];
        if (!(p.wi.z() > 1e-9) || !(p.wo.z() > 1e-9)) continue;  // below the horizon: no value
        const std::string th = format_g17((static_cast<double>(k % n) + 0.5) * 90.0 / n),
                          td = format_g17((static_cast<double>(k / n) + 0.5) * 90.0 / n);
        const walk::Estimate y = fit::at_albedo(sim[k], {slice_albedo, 1});
        write_csv_record(slices_,
                         slices_columns_.row({label, "simulation, diffuse only", a, th, td,
                                              format_g17(y.value / p.wo.z()), format_g17(y.stderr_ / p.wo.z())},
                                             1, label));
        for (const Measured* md : models)
            write_csv_record(slices_,
                             slices_columns_.row({label, md->name, a, th, td,
                                                  format_g17(model_f(*md, p.wi, p.wo, alpha, slice_albedo)), ""},
                                                 1, label));
    }
}

std::vector<Missing> PictureFiles::missing(const std::string& label, double alpha,
                                           const std::vector<fit::SplitMoments>& alb) {
    std::vector<Missing> out;
    for (double albedo : missing_albedos) {
        Missing worst{label, alpha, albedo, -1.0, 0.0, 0.0};
        for (std::size_t t = 0; t < alb.size(); ++t) {
            const auto [frac, se] = missing_fraction(alb[t], albedo);
            const double e = fit::at_albedo(alb[t], {albedo, 1}).value;
            write_csv_record(
                missing_,
                missing_columns_.row({label, format_g17(alpha), format_g17(missing_theta[t]), format_g17(albedo),
                                      format_g17(e), format_g17(e * (1.0 - frac)), format_g17(frac), format_g17(se)},
                                     1, label));
            if (frac > worst.fraction) worst = {label, alpha, albedo, frac, se, missing_theta[t]};
        }
        out.push_back(worst);
    }
    return out;
}

void PictureFiles::finish() {
    output::finish(spheres_, dir_ / "spheres.csv");
    output::finish(slices_, dir_ / "slices.csv");
    output::finish(missing_, dir_ / "missing.csv");
    output::finish(index_, dir_ / "ndfs.csv");
}

double lambert_check(const SphereGroup& g, const std::vector<fit::SplitMoments>& lam) {
    double worst = 0.0;
    for (std::size_t i = 0; i < g.pixels.size(); ++i)
        if (g.pixels[i].cos_light >= 0.1)
            worst = std::max(
                worst,
                std::abs(fit::at_albedo(lam[g.source[i]], {1.0, 1}).value / (g.pixels[i].cos_light / std::numbers::pi) -
                         1.0));
    return worst;
}

std::vector<std::string> write_constants_vs_parameter(const fs::path& dir, const Results& r, const LabelColumns& all) {
    std::vector<std::string> stems;
    for (const ParameterSweep& sweep : parameter_sweeps(r, 2)) {
        stems.push_back("constants_vs_" + sweep.family + "_" + sweep.parameter);
        const fs::path file = dir / (stems.back() + ".csv");
        const std::vector<std::string> own{"ndf", "model", "parameter", sweep.parameter, "value", "stderr"};
        const LabelColumns columns = all.except(own);
        std::ofstream csv(file, std::ios::binary);
        write_csv_record(csv, columns.header(own, 1));
        for (std::size_t k = 0; k < sweep.fits.size(); ++k) {
            const std::string& label = r.data[sweep.fits[k]].label;
            for (const Measured& m : r.fits[sweep.fits[k]]) {
                if (!m.fitted()) continue;
                for (std::size_t i = 0; i < m.params.size(); ++i)
                    write_csv_record(
                        csv,
                        columns.row({label, m.name, std::string(m.model->parameters[i]), format_g17(sweep.values[k]),
                                     format_g17(m.params[i]), format_g17(m.stderr_[i])},
                                    1, label));
            }
        }
        output::finish(csv, file);
    }
    return stems;
}

}  // namespace smithlab::fit
