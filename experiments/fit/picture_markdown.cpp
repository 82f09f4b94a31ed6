#include "fit/picture_markdown.hpp"

#include <sstream>

#include "fit/picture_traces.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::fit {

namespace {

std::string fixed(double v, int digits) { return format_printf("%.*f", digits, v); }

void images(std::ostream& md, const std::vector<std::string>& labels, const std::string& prefix) {
    for (const std::string& l : labels) md << "![](pictures/" << prefix << file_stem(l) << ".png)\n\n";
}

void spheres_section(std::ostream& md, const FitScene::Pictures& p, const std::vector<std::string>& labels) {
    md << "\n\n### Lit spheres, as Hammon 2017 laid them out\n\n"
          "Columns alpha = 0, 0.25^2, 0.5^2, 0.75^2, 1 (alpha 0 traced and drawn at "
       << format_g17(p.sphere_alpha.front())
       << "); rows the light at 0, 90 and 135 degrees from the viewer, each row three spheres at albedo 0.75, 0.5 and "
          "0.25. Orthographic view along +z, a unit directional light; radiance f(l, v) cos theta_l, shown as pi times "
          "it (a white Lambertian facing the light is 1), clipped at 1, gamma 2.2, the same for every source. The "
          "simulation traces "
       << p.walks << " walks per pixel (the eval estimator with the viewer as wi, the light as wo: reciprocity), one "
       << "trace at albedo 1 split by diffuse events for all three albedos; a sphere is symmetric about the plane of "
          "view and light, so its lower half reuses the upper half's values (the same local geometry to the last "
          "bit). \"Diffuse only\": light that met a diffuse event (k >= 1); \"with spec\": all of it, the facets' "
          "Fresnel reflection included. Models: each fitted one, and Lambert, Disney and EON at their published "
          "constants.\n\n";
    images(md, labels, "spheres_");
}

void slices_section(std::ostream& md, const FitScene::Pictures& p, const std::vector<std::string>& labels) {
    std::string alphas;
    for (double x : p.slice_alpha) alphas += (alphas.empty() ? "" : ", ") + format_g17(x);
    md << "### BRDF slices (Burley 2012's BRDF Explorer layout)\n\n"
          "theta_h across, theta_d down (0 to 90 degrees), phi_d = 90 degrees, at alpha "
       << alphas << ", albedo " << slice_albedo
       << ": the BRDF f itself times pi/albedo (Lambert is 1), the simulation's "
       << "diffuse part (its eval estimate divided by cos theta_o) beside each model.\n\n";
    images(md, labels, "slices_");
}

// One row per NDF and alpha: the largest fraction over the incidences, at each albedo, where it is.
void missing_table(std::ostream& md, const std::vector<Missing>& missing) {
    md << "Hammon 2017: \"up to half the light was missing\" (GGX+Smith, numerically integrated, his largest over "
          "alpha "
          "and angles). Measured, the largest 1 - E_1/E over theta_i:\n\n| NDF | alpha |";
    for (double a : missing_albedos) md << " albedo " << format_g17(a) << " | at theta_i |";
    md << "\n|---|---|";
    for (std::size_t i = 0; i < std::size(missing_albedos); ++i) md << "---|---|";
    md << "\n";
    for (std::size_t i = 0; i < missing.size(); i += std::size(missing_albedos)) {
        md << "| " << missing[i].ndf << " | " << format_g17(missing[i].alpha) << " |";
        for (std::size_t k = 0; k < std::size(missing_albedos); ++k) {
            const Missing& m = missing[i + k];
            md << " " << fixed(m.fraction, 3) << " +- " << fixed(m.stderr_, 3) << " | " << format_g17(m.theta) << " |";
        }
        md << "\n";
    }
    const Missing* w = nullptr;
    for (const Missing& m : missing)
        if (m.albedo == 1.0 && m.fraction > (w ? w->fraction : 0.0)) w = &m;
    if (w)
        md << "\nMeasured: single scattering misses at most " << fixed(100.0 * w->fraction, 1) << " +- "
           << fixed(100.0 * w->stderr_, 1) << "% of the light (albedo 1, " << w->ndf << ", alpha "
           << format_g17(w->alpha) << ", theta_i " << format_g17(w->theta)
           << " degrees, of the incidences traced); Hammon 2017: \"up to half\".\n\n";
}

void missing_section(std::ostream& md, const FitScene::Pictures& p, const PictureReport& r) {
    md << "### Lambertian facets: single scattering, and the light it misses\n\n"
          "Hammon 2017 (slides \"Diffuse Microfacet BRDF\", \"Direct only\", \"Direct plus indirect\", \"Indirect "
          "only\") integrated rho_m = 1/pi facets on GGX+Smith numerically: \"Up to half the light was missing!\" "
          "Here the same microsurface with lambert(albedo = 1) facets is traced; every event is diffuse, so k is the "
          "scattering order: direct only is k = 1, indirect only k >= 2. The fraction missing is 1 - E_1/E of the "
          "directional albedo (sample estimator, "
       << missing_walks << " walks per incidence theta_i in {0, 30, 60, 80} degrees), at albedo 1 and 0.75.\n\n";
    images(md, r.labels, "lambert_spheres_");
    for (const LambertCheck& c : r.checks)
        md << "Check: " << c.ndf << " at alpha " << format_g17(c.alpha) << " with Lambertian facets is Lambert's law "
           << "(albedo/pi cos theta_l) within " << fixed(100.0 * c.worst, 2) << "% at every pixel with cos theta_l >= "
           << "0.1 (albedo 1; " << p.walks << " walks per pixel).\n\n";
    missing_table(md, r.missing);
    images(md, r.labels, "missing_");
}

}  // namespace

std::string pictures_markdown(const FitScene::Pictures& p, const PictureReport& r) {
    std::ostringstream md;
    md << "\n## Pictures\n\n";
    md << "The pictures hold " << fixed(static_cast<double>(r.walks) / 1e6, 1) << " million traced walks. Data as CSV "
       << "in `pictures/` (spheres.csv, slices.csv, missing.csv).";
    if (!r.drawn) md << " **The pictures were not drawn** (python3-matplotlib missing?); their data is there.";
    spheres_section(md, p, r.labels);
    slices_section(md, p, r.labels);
    missing_section(md, p, r);
    for (const std::string& stem : r.swept)
        md << "### The fitted constants: " << stem.substr(std::string("constants_vs_").size()) << "\n\nEach fitted "
           << "model's constants with their standard errors from the fit's covariance.\n\n![](pictures/" << stem
           << ".png)\n";
    return md.str();
}

}  // namespace smithlab::fit
