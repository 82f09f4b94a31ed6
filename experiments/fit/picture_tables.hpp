// The pictures' CSV files (what experiments/plots/fit_plots.py draws from), each with one column per NDF parameter
// after its ndf column (fit/label_columns.hpp), and the checks they carry.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fit/fit_results.hpp"
#include "fit/label_columns.hpp"
#include "fit/picture_geometry.hpp"
#include "smithlab/fit/dataset.hpp"

namespace smithlab::fit {

// The models drawn: every fitted one, and the baselines Lambert, Disney and EON at their published constants (those
// the scene measured).
std::vector<const Measured*> drawn_models(const std::vector<Measured>& fits);

// A label as a file stem: letters, digits, '.', '=' and '-' kept, anything else '_', no trailing '_'.
std::string file_stem(const std::string& label);

// The largest fraction of the light single scattering misses over the incidences, for one NDF, alpha and albedo.
struct Missing {
    std::string ndf;
    double alpha, albedo, fraction, stderr_, theta;
};

// The pictures' CSV files, opened with their headers, checked when finished: spheres.csv, slices.csv, missing.csv
// and ndfs.csv (the NDFs, their file stems and the spheres' diameter).
class PictureFiles {
public:
    PictureFiles(const std::filesystem::path& dir, const LabelColumns& columns);
    void ndf(const std::string& label, int pixels);
    // Every source of one sphere group: the traced diffuse part and total (sim), Lambertian facets' direct, direct
    // plus indirect and indirect light (lam), and each model; radiance f(l, v) cos theta_l per lit pixel.
    void spheres(const std::string& label, double alpha, const SphereGroup& g,
                 const std::vector<fit::SplitMoments>& sim, const std::vector<fit::SplitMoments>& lam,
                 const std::vector<const Measured*>& models);
    // The slice's BRDF f itself (the eval estimate divided by cos theta_o: its diffuse part) and each model's.
    void slices(const std::string& label, double alpha, int n, const std::vector<Pair>& points,
                const std::vector<fit::SplitMoments>& sim, const std::vector<const Measured*>& models);
    // missing.csv's rows of one NDF and alpha (each incidence, each albedo); returns the largest fraction per albedo.
    std::vector<Missing> missing(const std::string& label, double alpha, const std::vector<fit::SplitMoments>& albedo);
    void finish();

private:
    std::filesystem::path dir_;
    LabelColumns spheres_columns_, slices_columns_, missing_columns_, index_columns_;
    std::ofstream spheres_, slices_, missing_, index_;
};

// The check of the whole chain (pixel geometry, local frame, reciprocity, tracing): Lambertian facets on a nearly flat
// microsurface are Lambert's law, radiance albedo/pi cos theta_l. The largest |traced / Lambert - 1| over the pixels
// with cos theta_l >= 0.1 at albedo 1.
double lambert_check(const SphereGroup& g, const std::vector<fit::SplitMoments>& lam);

// For each family swept in one parameter over two values or more (fit/fit_trends.hpp): its constants against that
// parameter, DIR/constants_vs_FAMILY_PARAMETER.csv; returns the files' stems.
std::vector<std::string> write_constants_vs_parameter(const std::filesystem::path& dir, const Results& results,
                                                      const LabelColumns& columns);

}  // namespace smithlab::fit
