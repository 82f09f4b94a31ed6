#include "fit/fit_pictures.hpp"

#include <cstdio>

#include "fit/picture_geometry.hpp"
#include "fit/picture_markdown.hpp"
#include "fit/picture_tables.hpp"
#include "output/plot_script.hpp"

namespace smithlab::fit {

namespace fs = std::filesystem;

namespace {

// The walks the pictures hold, whether traced by this run or read from the cache.
std::int64_t picture_walks(const FitScene::Pictures& p, const SphereGroup& spheres, const std::vector<Pair>& slices,
                           std::size_t ndfs) {
    const std::int64_t per_ndf = static_cast<std::int64_t>(p.sphere_alpha.size()) *
            (2 * static_cast<std::int64_t>(spheres.traced.size()) * p.walks +
             static_cast<std::int64_t>(std::size(missing_theta)) * missing_walks) +
        static_cast<std::int64_t>(p.slice_alpha.size()) * static_cast<std::int64_t>(slices.size()) * p.walks;
    return per_ndf * static_cast<std::int64_t>(ndfs);
}

// Every NDF's rows of the pictures' CSV files, from its traces; the missing light and the checks into the report.
void write_tables(PictureFiles& f, const FitScene::Pictures& p, const Results& r,
                  const std::vector<PictureData>& traced, const SphereGroup& spheres, const std::vector<Pair>& slices,
                  PictureReport& report) {
    const int P = static_cast<int>(p.pixels);
    for (std::size_t n = 0; n < r.data.size(); ++n) {
        const std::string& label = r.data[n].label;
        const PictureData& t = traced[n];
        f.ndf(label, P);
        const std::vector<const Measured*> models = drawn_models(r.fits[n]);
        for (std::size_t a = 0; a < p.sphere_alpha.size(); ++a) {
            const double alpha = p.sphere_alpha[a];
            f.spheres(label, alpha, spheres, t.spheres[a], t.lambert_spheres[a], models);
            if (a == 0 && alpha <= 0.01)
                report.checks.push_back({label, alpha, lambert_check(spheres, t.lambert_spheres[a])});
            for (Missing& m : f.missing(label, alpha, t.lambert_albedo[a])) report.missing.push_back(std::move(m));
        }
        for (std::size_t a = 0; a < p.slice_alpha.size(); ++a)
            f.slices(label, p.slice_alpha[a], static_cast<int>(p.slice_n), slices, t.slices[a], models);
    }
}

}  // namespace

std::string write_pictures(const fs::path& dir, const fs::path& cache, const PictureSpec& s, const Results& r,
                           const LabelColumns& columns, const NdfRegistry& registry, unsigned threads) {
    const FitScene::Pictures& p = s.pictures;
    if (!p.enabled) return "";
    const fs::path out = dir / "pictures";
    fs::create_directories(out);
    const SphereGroup spheres = sphere_group(static_cast<int>(p.pixels));
    const std::vector<Pair> slices = slice_points(static_cast<int>(p.slice_n));
    std::int64_t walks_traced = 0;
    const std::vector<PictureData> traced =
        trace_pictures(s, r.data, spheres, slices, registry, cache, threads, walks_traced);

    PictureReport report;
    for (const NdfData& d : r.data) report.labels.push_back(d.label);
    report.walks = picture_walks(p, spheres, slices, r.data.size());
    PictureFiles f(out, columns);
    write_tables(f, p, r, traced, spheres, slices, report);
    f.finish();
    report.swept = write_constants_vs_parameter(out, r, columns);
    report.drawn = output::run_plot_script("fit_plots.py", SMITHLAB_FIT_PLOT_SCRIPT, out, "fit: pictures");
    return pictures_markdown(p, report);
}

}  // namespace smithlab::fit
