#include "report/work_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report/sampling_experiment.hpp"
#include "smithlab/errors.hpp"

namespace smithlab::report {

namespace {

bool any_match(const std::vector<std::string>& patterns, const std::string& name) {
    return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return glob_match(p, name); });
}

// As run_report selects them: included and not excluded.
double selected_variants(const Scene& scene, const VariantRegistry& variants) {
    return static_cast<double>(std::count_if(variants.list().begin(), variants.list().end(), [&](const LambdaVariant& v) {
        return any_match(scene.include, v.name) && !any_match(scene.exclude, v.name);
    }));
}

double selected_g2_variants(const Scene& scene) {
    const std::vector<G2Variant> all = builtin_G2_variants();
    return static_cast<double>(std::count_if(all.begin(), all.end(), [&](const G2Variant& v) { return any_match(scene.g2.include, v.name); }));
}

double grid_ndfs(const Scene& scene) {
    double n = 0.0;
    for (const NdfEntry& e : scene.ndfs) n += static_cast<double>(e.count(scene.alphas.size()));
    return n;
}

// Above x, with two significant digits: a limit that lets a scene of work x through.
double rounded_up(double x) {
    const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1.0);
    return std::ceil(x / unit) * unit;
}

std::string short_number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return text;
}

}  // namespace

Work estimate_work(const Scene& scene, const VariantRegistry& variants) {
    Work w;
    const double points = grid_ndfs(scene) * static_cast<double>(scene.mus.size());
    const double lambda_variants = selected_variants(scene, variants);
    w.lambda_evaluations = lambda_variants * points;
    w.references = std::min(lambda_variants, 3.0) * points;
    const double g2_variants = scene.g2.include.empty() ? 0.0 : selected_g2_variants(scene);
    if (g2_variants > 0.0) {
        const double g2_ndfs = static_cast<double>(scene.g2.families.size() * scene.alphas.size());
        const double g2_mus = static_cast<double>(scene.g2.mus.size());
        w.g2_evaluations = g2_variants * g2_ndfs * g2_mus * g2_mus;
        w.references += g2_ndfs * g2_mus;
    }
    w.samples = static_cast<double>(scene.sampling.families.size() * scene.sampling.alphas.size() * sampling_strategies.size()) *
                static_cast<double>(scene.sampling.samples);
    double walk_ndfs = 0.0, walk_alphas = 0.0;
    for (const NdfEntry& e : scene.walk.ndfs) walk_ndfs += static_cast<double>(e.count(1));
    for (double a : scene.walk.alphas) walk_alphas += std::max(1.0, a);  // a walk's length grows like alpha above 1
    w.walks = walk_ndfs * walk_alphas * static_cast<double>(scene.walk.materials.size() * scene.walk.theta_i.size()) *
              static_cast<double>(scene.walk.walks);
    return w;
}

std::string describe(const Work& work) {
    return short_number(work.total()) + " evaluations (Lambda " + short_number(work.lambda_evaluations) + ", G2 " +
           short_number(work.g2_evaluations) + ", references " + short_number(work.references) + ", samples " +
           short_number(work.samples) + (work.walks > 0.0 ? ", walks " + short_number(work.walks) : "") + ")";
}

void check_work(const Work& work, double max_work, const std::string& source) {
    if (work.total() <= max_work) return;
    throw input_error(source + ": the scene's work is estimated at " + describe(work) + ", above the limit of " +
                      short_number(max_work) + " evaluations; nothing was computed. Make the grid smaller, select fewer " +
                      "variants, samples or walks, or raise the limit: smithlab report --max-work " + short_number(rounded_up(work.total())));
}

}  // namespace smithlab::report
