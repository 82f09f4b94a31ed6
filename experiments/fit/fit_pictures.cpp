#include "fit/fit_pictures.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <sstream>

#include "fit/fit_data.hpp"
#include "fit/fit_trends.hpp"
#include "output/plot_script.hpp"
#include "output/progress.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::fitrun {

namespace fs = std::filesystem;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180.0;

// Hammon 2017, slides "Direct only" ... "Approximate diffuse only" (shared/refs, lines 700-760 and 1715-1755): rows
// the light at 0, 90 and 135 degrees from the viewer, each row three spheres at albedo 0.75, 0.5, 0.25.
constexpr double light_degrees[] = {0.0, 90.0, 135.0};
constexpr double sphere_albedos[] = {0.75, 0.5, 0.25};
constexpr double slice_albedo = 0.75;
// The light single scattering misses: directional albedos (the sample estimator) at these incidences.
constexpr double missing_theta[] = {0.0, 30.0, 60.0, 80.0};
constexpr double missing_albedos[] = {1.0, 0.75};
constexpr std::int64_t missing_walks = 100000;

// The pictures' Philox streams: set << 56 | ndf << 44 | group << 32 | point. fit_data.cpp's streams are
// set << 48 | ndf << 32 | group << 16 | point with set <= 2 and ndf < 2^16, all below 2^50; these have set >= 3 in
// bits 56.., so none collides with them, and a group may hold 2^32 points (a 1024-pixel sphere has 2^20 per light).
enum PictureSet : std::uint64_t { sphere_set = 3, slice_set = 4, lambert_sphere_set = 5, lambert_albedo_set = 6 };

std::uint64_t stream(PictureSet set, std::uint64_t ndf, std::uint64_t group, std::uint64_t point) {
    if (ndf >= (1u << 12) || group >= (1u << 12) || point >= (std::uint64_t{1} << 32))
        throw input_error("fit: pictures: too many NDFs, alphas or pixels for the pictures' random streams");
    return set << 56 | ndf << 44 | group << 32 | point;
}

// A point to trace, in the macrosurface's frame: the eval estimator's wi and wo (the albedo estimator uses wi only).
struct Pair {
    Vec3 wi, wo;
};

// One lit pixel of a sphere: its place, the light's row, and where its value comes from (`mirror_of`: the index of
// the pixel in the upper half with the same local geometry, or -1 when traced itself).
struct Pixel {
    int px, py, light;
    Pair local;  // wi the viewer, wo the light (traced so: reciprocity, see sphere_pixels)
    double cos_light;
};

// The lit pixels of a sphere of P pixels across, seen orthographically along +z, the light in the xz-plane at
// `light` degrees from the viewer. Pixel (i, j) (j down) has its center at x = (2i + 1 - P)/P, y = (P - 1 - 2j)/P,
// exact multiples of 1/P, so rows j and P-1-j have y of opposite sign, bit for bit. At each pixel the sphere's
// normal n is the macrosurface normal; the local directions are built from n.v, n.l and the azimuth between their
// projections on the tangent plane, all even in y: mirror pixels get the same local geometry to the last bit.
//
// The eval estimator gives f(wi, wo) cos theta_o. Tracing the viewer as wi and the light as wo gives
// f(view, light) cos theta_light = f(light, view) cos theta_light (reciprocity), the radiance towards the viewer
// from a unit directional light.
std::vector<Pixel> sphere_pixels(int P, int light) {
    const double t = light_degrees[light] * deg;
    const Vec3 l(std::sin(t), 0.0, std::cos(t)), v(0.0, 0.0, 1.0);
    std::vector<Pixel> out;
    for (int j = 0; j < P; ++j)
        for (int i = 0; i < P; ++i) {
            const double x = static_cast<double>(2 * i + 1 - P) / P, y = static_cast<double>(P - 1 - 2 * j) / P;
            const double r2 = x * x + y * y;
            if (!(r2 < 1.0)) continue;
            const Vec3 n(x, y, std::sqrt(1.0 - r2));
            const double nv = n.dot(v), nl = n.dot(l);
            if (!(nl > 1e-9) || !(nv > 1e-9)) continue;  // unlit (n.l <= 0): zero, drawn as background
            const Vec3 vt = v - nv * n, lt = l - nl * n;
            const double sv = vt.norm(), sl = lt.norm();
            double c = sv > 1e-12 && sl > 1e-12 ? vt.dot(lt) / (sv * sl) : 1.0;
            c = std::clamp(c, -1.0, 1.0);
            const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
            const double stv = std::sqrt(std::max(0.0, 1.0 - nv * nv)), stl = std::sqrt(std::max(0.0, 1.0 - nl * nl));
            out.push_back({i, j, light, {Vec3(stv, 0.0, nv), Vec3(stl * c, stl * s, nl)}, nl});
        }
    return out;
}

// A sphere group (one alpha): every light's lit pixels, and the traced ones (the upper half, y >= 0, and the middle
// row: the lower half mirrors them).
struct SphereGroup {
    std::vector<Pixel> pixels;
    std::vector<std::size_t> source;  // per pixel: its index in `traced`
    std::vector<Pair> traced;
};

SphereGroup sphere_group(int P) {
    SphereGroup g;
    for (int light = 0; light < 3; ++light) {
        const std::vector<Pixel> px = sphere_pixels(P, light);
        const std::size_t first = g.pixels.size();
        std::vector<long> index(static_cast<std::size_t>(P) * P, -1);  // pixel (i, j) -> position in g.pixels
        for (const Pixel& p : px) {
            index[static_cast<std::size_t>(p.py) * P + p.px] = static_cast<long>(g.pixels.size());
            g.pixels.push_back(p);
            const int mj = P - 1 - p.py;
            if (p.py <= mj) {  // upper half (y >= 0): traced
                g.source.push_back(g.traced.size());
                g.traced.push_back(p.local);
            } else {
                const long m = index[static_cast<std::size_t>(mj) * P + p.px];
                // The mirror is lit whenever this pixel is (n.l is even in y) and came first (smaller j).
                if (m < static_cast<long>(first)) throw std::logic_error("fit: pictures: a sphere pixel has no mirror");
                g.source.push_back(g.source[static_cast<std::size_t>(m)]);
            }
        }
    }
    return g;
}

// Walks traced of walks to trace, for the progress line.
struct Progress {
    output::ProgressLine line;
    std::int64_t done = 0, total = 0;
    void report(std::int64_t now_done) {
        line(static_cast<double>(now_done) / static_cast<double>(total), [&] {
            return "fit: pictures: traced " + std::to_string(now_done / 1000000) + " of " +
                   std::to_string(total / 1000000) + " walks (millions)";
        });
    }
};

// Traces the points (fit_data.hpp, trace_points), point j from stream(set, ndf, group, j).
std::vector<fit::SplitMoments> trace_points(const AnyNdf& ndf, const walk::Material& material,
                                            const std::vector<Pair>& points, bool albedo, std::uint64_t seed,
                                            PictureSet set, std::uint64_t ndf_index, std::uint64_t group,
                                            std::int64_t walks, unsigned threads, Progress& progress) {
    std::vector<TracePoint> traced;
    for (std::size_t j = 0; j < points.size(); ++j)
        traced.push_back({points[j].wi, points[j].wo, stream(set, ndf_index, group, j)});
    const std::int64_t before = progress.done;
    std::vector<fit::SplitMoments> out =
        fitrun::trace_points(ndf, material, traced, albedo ? Estimator::albedo : Estimator::eval, seed, walks, threads,
                             [&](std::uint64_t k) { progress.report(before + static_cast<std::int64_t>(k) * walks); });
    progress.done += static_cast<std::int64_t>(points.size()) * walks;
    return out;
}

// The value of a diffuse-event split at an albedo: k >= min_k, or exactly k = 1 (min_k = -1, single scattering).
double split_value(const fit::SplitMoments& m, double albedo, int min_k) {
    if (min_k < 0) return fit::at_albedo(m, {albedo, 1}).value - fit::at_albedo(m, {albedo, 2}).value;
    return fit::at_albedo(m, {albedo, min_k}).value;
}

// The models drawn: every fitted one, and the baselines Lambert, Disney and EON at their published constants (those
// the scene measured).
std::vector<const Measured*> drawn_models(const std::vector<Measured>& fits) {
    std::vector<const Measured*> out;
    for (const char* base : {"lambert", "disney", "eon"})
        for (const Measured& m : fits)
            if (m.name == base) out.push_back(&m);
    for (const Measured& m : fits)
        if (m.fitted()) out.push_back(&m);
    return out;
}

double model_f(const Measured& m, const Vec3& light, const Vec3& view, double alpha, double albedo) {
    return m.model->f(light, view, alpha, albedo, m.params.empty() ? nullptr : m.params.data());
}

std::string file_stem(const std::string& label) {
    std::string d;
    for (char c : label) d += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-' ? c : '_';
    while (!d.empty() && d.back() == '_') d.pop_back();
    return d;
}

// Six significant digits: the pictures' values (the spheres' CSV holds ~10^5 rows per NDF).
std::string short_g(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

// The maximum of the missing fraction over incidences for one NDF, alpha and albedo.
struct Missing {
    std::string ndf;
    double alpha, albedo, fraction, stderr_, theta;
};

// The pictures' CSV files, opened with their headers, checked when finished.
struct Files {
    fs::path dir;
    std::ofstream spheres, slices, missing, index;
    explicit Files(const fs::path& d)
        : dir(d), spheres(d / "spheres.csv", std::ios::binary), slices(d / "slices.csv", std::ios::binary),
          missing(d / "missing.csv", std::ios::binary), index(d / "ndfs.csv", std::ios::binary) {
        write_csv_record(spheres, {"ndf", "source", "alpha", "light_deg", "albedo", "px", "py", "value"});
        write_csv_record(slices, {"ndf", "source", "alpha", "theta_h", "theta_d", "value", "stderr"});
        write_csv_record(missing, {"ndf", "alpha", "theta", "albedo", "E", "E1", "missing", "stderr"});
        write_csv_record(index, {"ndf", "stem", "pixels"});
    }
    void finish() {
        output::finish(spheres, dir / "spheres.csv");
        output::finish(slices, dir / "slices.csv");
        output::finish(missing, dir / "missing.csv");
        output::finish(index, dir / "ndfs.csv");
    }
};

void write_spheres(Files& f, const std::string& label, double alpha, const SphereGroup& g,
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
        write_csv_record(f.spheres, {label, source, a, format_g17(light_degrees[p.light]), format_g17(albedo),
                                     std::to_string(p.px), std::to_string(p.py), short_g(v)});
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

// Burley 2012, "Physically-Based Shading at Disney", sec. 2 and fig. "BRDF Explorer slices": the BRDF over
// (theta_h, theta_d) at phi_d = 90 degrees (Rusinkiewicz 1998's half/difference angles, phi_h = 0):
//     wi = (cos td sin th, sin td, cos td cos th),  wo = (cos td sin th, -sin td, cos td cos th),
// both at cos theta = cos td cos th > 0 for cell centers in (0, 90). Cell (i, j): theta_h = (i + 1/2) 90/n across,
// theta_d = (j + 1/2) 90/n down.
std::vector<Pair> slice_points(int n) {
    std::vector<Pair> out;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double th = (i + 0.5) * 90.0 / n * deg, td = (j + 0.5) * 90.0 / n * deg;
            out.push_back({Vec3(std::cos(td) * std::sin(th), std::sin(td), std::cos(td) * std::cos(th)),
                           Vec3(std::cos(td) * std::sin(th), -std::sin(td), std::cos(td) * std::cos(th))});
        }
    return out;
}

void write_slices(Files& f, const std::string& label, double alpha, int n, const std::vector<Pair>& pts,
                  const std::vector<fit::SplitMoments>& sim, const std::vector<const Measured*>& models) {
    const std::string a = format_g17(alpha);
    for (std::size_t k = 0; k < pts.size(); ++k) {
        const Pair& p = pts[k];
        if (!(p.wi.z() > 1e-9) || !(p.wo.z() > 1e-9)) continue;  // below the horizon: no value
        const std::string th = format_g17((static_cast<double>(k % n) + 0.5) * 90.0 / n),
                          td = format_g17((static_cast<double>(k / n) + 0.5) * 90.0 / n);
        // The eval estimate is f cos theta_o: divided by cos theta_o, the BRDF itself (its diffuse part).
        const fit::SplitMoments& m = sim[k];
        const walk::Estimate y = fit::at_albedo(m, {slice_albedo, 1});
        write_csv_record(f.slices, {label, "simulation, diffuse only", a, th, td, format_g17(y.value / p.wo.z()),
                                    format_g17(y.stderr_ / p.wo.z())});
        for (const Measured* md : models)
            write_csv_record(f.slices, {label, md->name, a, th, td, format_g17(model_f(*md, p.wi, p.wo, alpha,
                                                                                       slice_albedo)),
                                        ""});
    }
}

// The check of the whole chain (pixel geometry, local frame, reciprocity, tracing): Lambertian facets on a nearly flat
// microsurface are Lambert's law, radiance albedo/pi cos theta_l. The largest |traced / Lambert - 1| over the pixels
// with cos theta_l >= 0.1 at albedo 1.
double lambert_check(const SphereGroup& g, const std::vector<fit::SplitMoments>& lam) {
    double worst = 0.0;
    for (std::size_t i = 0; i < g.pixels.size(); ++i)
        if (g.pixels[i].cos_light >= 0.1)
            worst = std::max(worst, std::abs(fit::at_albedo(lam[g.source[i]], {1.0, 1}).value /
                                                 (g.pixels[i].cos_light / pi) - 1.0));
    return worst;
}

// 1 - E_1/E = E_{k>=2}/E_{k>=1} for Lambertian facets (every event diffuse: k is the scattering order), with its
// standard error by the delta method (the two means share their walks: fit::covariance).
std::pair<double, double> missing_fraction(const fit::SplitMoments& m, double albedo) {
    const fit::AlbedoPower all{albedo, 1}, multi{albedo, 2};
    const walk::Estimate e = fit::at_albedo(m, all), em = fit::at_albedo(m, multi);
    if (!(e.value > 0.0)) return {0.0, 0.0};
    const double r = em.value / e.value;
    const double var = (em.stderr_ * em.stderr_ - 2.0 * r * fit::covariance(m, all, multi) +
                        r * r * e.stderr_ * e.stderr_) / (e.value * e.value);
    return {r, std::sqrt(std::max(0.0, var))};
}

// missing.csv's rows of one NDF and alpha (each incidence, each albedo), and the largest fraction per albedo.
void record_missing(Files& f, std::vector<Missing>& missing, const std::string& label, double alpha,
                    const std::vector<fit::SplitMoments>& alb) {
    for (double albedo : missing_albedos) {
        Missing worst{label, alpha, albedo, -1.0, 0.0, 0.0};
        for (std::size_t t = 0; t < alb.size(); ++t) {
            const auto [frac, se] = missing_fraction(alb[t], albedo);
            const double e = fit::at_albedo(alb[t], {albedo, 1}).value;
            write_csv_record(f.missing, {label, format_g17(alpha), format_g17(missing_theta[t]), format_g17(albedo),
                                         format_g17(e), format_g17(e * (1.0 - frac)), format_g17(frac), format_g17(se)});
            if (frac > worst.fraction) worst = {label, alpha, albedo, frac, se, missing_theta[t]};
        }
        missing.push_back(worst);
    }
}

// For each family swept in one parameter over two values or more (fit_trends.hpp): its constants against that
// parameter, DIR/constants_vs_FAMILY_PARAMETER.csv; returns the files' stems.
std::vector<std::string> write_constants_vs_parameter(const fs::path& dir, const Results& r) {
    std::vector<std::string> stems;
    for (const ParameterSweep& sweep : parameter_sweeps(r, 2)) {
        stems.push_back("constants_vs_" + sweep.family + "_" + sweep.parameter);
        const fs::path file = dir / (stems.back() + ".csv");
        std::ofstream csv(file, std::ios::binary);
        write_csv_record(csv, {"ndf", "model", "parameter", sweep.parameter, "value", "stderr"});
        for (std::size_t k = 0; k < sweep.fits.size(); ++k)
            for (const Measured& m : r.fits[sweep.fits[k]]) {
                if (!m.fitted()) continue;
                for (std::size_t i = 0; i < m.params.size(); ++i)
                    write_csv_record(csv, {r.data[sweep.fits[k]].label, m.name, std::string(m.model->parameters[i]),
                                           format_g17(sweep.values[k]), format_g17(m.params[i]),
                                           format_g17(m.stderr_[i])});
            }
        output::finish(csv, file);
    }
    return stems;
}

std::string fixed(double v, int digits) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

// A check's result: the largest relative difference per NDF at the smallest sphere alpha.
struct Check {
    std::string ndf;
    double alpha, worst;
};

std::string markdown(const Results& r, const FitScene& s, const std::vector<Missing>& missing,
                     const std::vector<Check>& checks, const std::vector<std::string>& swept, bool drawn,
                     double seconds, std::int64_t walks) {
    const FitScene::Pictures& p = s.pictures;
    std::ostringstream md;
    md << "\n## Pictures\n\n";
    md << "Traced " << fixed(walks / 1e6, 1) << " million walks for the pictures in " << fixed(seconds, 1)
       << " s. Data as CSV in `pictures/` (spheres.csv, slices.csv, missing.csv).";
    if (!drawn) md << " **The pictures were not drawn** (python3-matplotlib missing?); their data is there.";
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
    for (const NdfData& d : r.data) md << "![](pictures/spheres_" << file_stem(d.label) << ".png)\n\n";
    md << "### BRDF slices (Burley 2012's BRDF Explorer layout)\n\n"
          "theta_h across, theta_d down (0 to 90 degrees), phi_d = 90 degrees, at alpha "
       << [&] {
              std::string a;
              for (double x : p.slice_alpha) a += (a.empty() ? "" : ", ") + format_g17(x);
              return a;
          }()
       << ", albedo " << slice_albedo << ": the BRDF f itself times pi/albedo (Lambert is 1), the simulation's "
       << "diffuse part (its eval estimate divided by cos theta_o) beside each model.\n\n";
    for (const NdfData& d : r.data) md << "![](pictures/slices_" << file_stem(d.label) << ".png)\n\n";
    md << "### Lambertian facets: single scattering, and the light it misses\n\n"
          "Hammon 2017 (slides \"Diffuse Microfacet BRDF\", \"Direct only\", \"Direct plus indirect\", \"Indirect "
          "only\") integrated rho_m = 1/pi facets on GGX+Smith numerically: \"Up to half the light was missing!\" "
          "Here the same microsurface with lambert(albedo = 1) facets is traced; every event is diffuse, so k is the "
          "scattering order: direct only is k = 1, indirect only k >= 2. The fraction missing is 1 - E_1/E of the "
          "directional albedo (sample estimator, "
       << missing_walks << " walks per incidence theta_i in {0, 30, 60, 80} degrees), at albedo 1 and 0.75.\n\n";
    for (const NdfData& d : r.data) md << "![](pictures/lambert_spheres_" << file_stem(d.label) << ".png)\n\n";
    for (const Check& c : checks)
        md << "Check: " << c.ndf << " at alpha " << format_g17(c.alpha) << " with Lambertian facets is Lambert's law "
           << "(albedo/pi cos theta_l) within " << fixed(100.0 * c.worst, 2) << "% at every pixel with cos theta_l >= "
           << "0.1 (albedo 1; " << p.walks << " walks per pixel).\n\n";
    // One row per NDF and alpha: the largest fraction over the incidences, at each albedo, where it is.
    md << "Hammon 2017: \"up to half the light was missing\" (GGX+Smith, numerically integrated, his largest over alpha "
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
    double worst = 0.0;
    const Missing* w = nullptr;
    for (const Missing& m : missing)
        if (m.albedo == 1.0 && m.fraction > worst) worst = m.fraction, w = &m;
    if (w)
        md << "\nMeasured: single scattering misses at most " << fixed(100.0 * w->fraction, 1) << " +- "
           << fixed(100.0 * w->stderr_, 1) << "% of the light (albedo 1, " << w->ndf << ", alpha "
           << format_g17(w->alpha) << ", theta_i " << format_g17(w->theta)
           << " degrees, of the incidences traced); Hammon 2017: \"up to half\".\n\n";
    for (const NdfData& d : r.data) md << "![](pictures/missing_" << file_stem(d.label) << ".png)\n\n";
    for (const std::string& stem : swept)
        md << "### The fitted constants: " << stem.substr(std::string("constants_vs_").size()) << "\n\nEach fitted "
           << "model's constants with their standard errors from the fit's covariance.\n\n![](pictures/" << stem
           << ".png)\n";
    return md.str();
}

}  // namespace

std::string write_pictures(const fs::path& dir, const FitScene& s, const Results& r, const NdfRegistry& registry,
                           unsigned threads) {
    if (!s.pictures.enabled) return "";
    const auto t0 = std::chrono::steady_clock::now();
    const FitScene::Pictures& p = s.pictures;
    const fs::path out = dir / "pictures";
    fs::create_directories(out);
    const walk::Material material = walk::parse_material(s.material), lambert = walk::parse_material("lambert(albedo=1)");
    const int P = static_cast<int>(p.pixels), n_slice = static_cast<int>(p.slice_n);
    const SphereGroup spheres = sphere_group(P);
    const std::vector<Pair> slices = slice_points(n_slice);
    std::vector<Pair> albedo_points;
    for (double t : missing_theta) albedo_points.push_back({direction_from_theta_deg(t), Vec3(0.0, 0.0, 1.0)});

    Progress progress;
    const std::int64_t per_ndf =
        static_cast<std::int64_t>(p.sphere_alpha.size()) *
            (2 * static_cast<std::int64_t>(spheres.traced.size()) * p.walks +
             static_cast<std::int64_t>(albedo_points.size()) * missing_walks) +
        static_cast<std::int64_t>(p.slice_alpha.size()) * static_cast<std::int64_t>(slices.size()) * p.walks;
    progress.total = per_ndf * static_cast<std::int64_t>(r.data.size());

    Files f(out);
    std::vector<Missing> missing;
    std::vector<Check> checks;

    for (std::size_t n = 0; n < r.data.size(); ++n) {
        const NdfData& d = r.data[n];
        write_csv_record(f.index, {d.label, file_stem(d.label), std::to_string(P)});
        const std::vector<const Measured*> models = drawn_models(r.fits[n]);
        for (std::size_t a = 0; a < p.sphere_alpha.size(); ++a) {
            const double alpha = p.sphere_alpha[a];
            const AnyNdf ndf = make_ndf(registry, d.family, alpha);
            std::fprintf(stderr, "fit: pictures: %s, alpha %g: spheres\n", d.label.c_str(), alpha);
            const std::vector<fit::SplitMoments> sim = trace_points(
                ndf, material, spheres.traced, false, s.seed, sphere_set, n, a, p.walks, threads, progress);
            const std::vector<fit::SplitMoments> lam = trace_points(
                ndf, lambert, spheres.traced, false, s.seed, lambert_sphere_set, n, a, p.walks, threads, progress);
            write_spheres(f, d.label, alpha, spheres, sim, lam, models);
            if (a == 0 && alpha <= 0.01) checks.push_back({d.label, alpha, lambert_check(spheres, lam)});
            const std::vector<fit::SplitMoments> alb = trace_points(
                ndf, lambert, albedo_points, true, s.seed, lambert_albedo_set, n, a, missing_walks, threads, progress);
            record_missing(f, missing, d.label, alpha, alb);
        }
        for (std::size_t a = 0; a < p.slice_alpha.size(); ++a) {
            const double alpha = p.slice_alpha[a];
            std::fprintf(stderr, "fit: pictures: %s, alpha %g: slices\n", d.label.c_str(), alpha);
            const std::vector<fit::SplitMoments> sim =
                trace_points(make_ndf(registry, d.family, alpha), material, slices, false, s.seed, slice_set, n, a,
                             p.walks, threads, progress);
            write_slices(f, d.label, alpha, n_slice, slices, sim, models);
        }
    }
    f.finish();
    const std::vector<std::string> swept = write_constants_vs_parameter(out, r);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "fit: pictures: traced in %.1f s\n", seconds);
    const bool drawn = output::run_plot_script("fit_plots.py", SMITHLAB_FIT_PLOT_SCRIPT, out, "fit: pictures");
    return markdown(r, s, missing, checks, swept, drawn, seconds, progress.total);
}

}  // namespace smithlab::fitrun
