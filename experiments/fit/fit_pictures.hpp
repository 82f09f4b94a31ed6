// The fit's pictures (PNG, drawn by experiments/plots/fit_plots.py from CSV written here): lit spheres as Hammon laid
// them out, Disney-style BRDF slices, the light single scattering misses, and the fitted constants against a swept
// parameter.
#pragma once

#include <filesystem>
#include <string>

#include "fit/fit_results.hpp"
#include "fit/label_columns.hpp"
#include "fit/picture_traces.hpp"
#include "smithlab/registry.hpp"

namespace smithlab::fit {

// Writes the pictures' data and PNGs into dir/pictures when the scene asks (spec.pictures.enabled; otherwise traces
// nothing and returns ""), and returns the Markdown that shows them in report.md (links relative to dir). Per NDF
// family of results.data, at the scene's seed on Philox streams of their own (fit/picture_traces.hpp), the same bits
// for any `threads`, cached in `cache` (a second run traces nothing):
//   spheres.csv   Hammon 2017's lit spheres (sphere_alpha x light 0/90/135 degrees x albedo 0.75/0.5/0.25), per lit
//                 pixel: the traced diffuse part and total (the scene's material), Lambertian facets' direct, direct
//                 plus indirect and indirect light, and every fitted model with lambert, disney and eon as measured;
//   slices.csv    Burley 2012's BRDF slices (theta_h, theta_d at phi_d = 90) at slice_alpha, albedo 0.75: f itself;
//   missing.csv   1 - E_1/E of Lambertian facets per sphere alpha and theta_i (0, 30, 60, 80), albedo 1 and 0.75;
//   constants_vs_FAMILY_PARAMETER.csv  the fitted constants of a family swept in one parameter (fit_trends.hpp), with
//                 two values or more;
// and spheres_NDF.png, lambert_spheres_NDF.png, slices_NDF.png, missing_NDF.png, constants_vs_*.png drawn by
// experiments/plots/fit_plots.py (a warning, and a note in the Markdown, when it cannot run).
std::string write_pictures(const std::filesystem::path& dir, const std::filesystem::path& cache,
                           const PictureSpec& spec, const Results& results, const LabelColumns& columns,
                           const NdfRegistry& registry, unsigned threads);

}  // namespace smithlab::fit
