#include "report/sampling_experiment.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <utility>

#include "output/progress.hpp"
#include "output/staged_directory.hpp"
#include "smithlab/csv.hpp"
#include "smithlab/errors.hpp"
#include "smithlab/samplers.hpp"
#include "smithlab/smith.hpp"

namespace smithlab::report {

namespace {

constexpr double pi = std::numbers::pi;

// The integrand's pieces for one NDF seen from wo.
struct Conductor {
    AnyNdf ndf;
    Vec3 wo;
    double Lambda_o;
    double G2(const Vec3& wi) const {
        return G2_from_Lambdas(Lambda(ndf, cot_theta(wi)), Lambda_o, true, G2Form::height_correlated);
    }
    double D(const Vec3& m) const {
        const double s = tan2_theta(m);
        return D_from_P22(ndf.slope_density(s), s);
    }
};

}  // namespace

std::vector<AnyNdf> sampling_ndfs(const SamplingScene& s, const NdfRegistry& ndfs) {
    require(s.theta_o >= 0.0 && s.theta_o < 90.0, "sampling theta_o", "in [0, 90) degrees", s.theta_o);
    std::vector<AnyNdf> list;
    for (const std::string& family : s.families) {
        const NdfInfo* info = ndfs.find(family);
        if (!info) throw input_error("unknown ndf family '" + family + "'");
        if (info->parameters != std::vector<std::string>{"alpha"})
            throw input_error("'" + family + "' is not a family of one parameter, alpha");
        for (double a : s.alphas) {
            AnyNdf n = ndfs.make(family, {{"alpha", a}});
            if (!n.has_closed_Lambda()) throw input_error("'" + family + "' has no closed-form Lambda for G2");
            list.push_back(std::move(n));
        }
    }
    return list;
}

namespace {

// One sample of each strategy's weight (sampling_strategies' order) for ndf seen from wo.
std::vector<std::function<double(Rng&)>> strategy_weights(const AnyNdf& ndf, const Vec3& wo,
                                                          const std::vector<SamplerInfo>& samplers) {
    const auto c = std::make_shared<const Conductor>(Conductor{ndf, wo, Lambda(ndf, cot_theta(wo))});
    const BoundSampler dcos = prepare(find_sampler(samplers, "dcos"), ndf, wo);
    // Visible normals in closed form where the NDF offers one (its capability, ndf.hpp), else by rejection.
    const char* visible = !std::isnan(ggx_alpha(ndf)) ? "vndf-ggx"
        : !std::isnan(beckmann_alpha(ndf))            ? "vndf-beckmann"
                                                      : "vndf";
    const BoundSampler vndf = prepare(find_sampler(samplers, visible), ndf, wo);
    const double cos_o = wo.z();
    return {
        [c, cos_o](Rng& g) {  // Malley: a uniform disk point lifted to the hemisphere is cosine-distributed
            const double r = std::sqrt(uniform01(g)), phi = 2.0 * pi * uniform01(g);
            const Vec3 wi(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - r * r)));
            if (!(wi.z() > 0.0)) return 0.0;
            const Vec3 h = (wi + c->wo).normalized();
            return pi * c->G2(wi) * c->D(h) / (4.0 * cos_o * wi.z());
        },
        [c, cos_o, dcos](Rng& g) {
            const NormalSample m = dcos.sample(g);
            const double wom = c->wo.dot(m.m);
            const Vec3 wi = reflect(c->wo, m.m);
            if (!(wom > 0.0 && wi.z() > 0.0)) return 0.0;
            return c->G2(wi) * wom / (cos_o * m.m.z());
        },
        [c, vndf](Rng& g) {
            const Vec3 wi = reflect(c->wo, vndf.sample(g).m);
            if (!(wi.z() > 0.0)) return 0.0;
            return c->G2(wi) * (1.0 + c->Lambda_o);
        },
    };
}

// The mean and (sample) variance of n draws of weight, by Welford's running update.
std::pair<double, double> mean_and_variance(const std::function<double(Rng&)>& weight, Rng g, std::size_t n) {
    double mean = 0.0, m2 = 0.0;
    for (std::size_t i = 1; i <= n; ++i) {
        const double w = weight(g);
        const double d = w - mean;
        mean += d / static_cast<double>(i);
        m2 += d * (w - mean);
    }
    return {mean, m2 / static_cast<double>(n - 1)};
}

}  // namespace

std::vector<SamplingRow> run_sampling_experiment(const std::vector<AnyNdf>& list, const SamplingScene& s) {
    const std::vector<SamplerInfo> samplers = builtin_samplers();
    const Vec3 wo = direction_from_theta_deg(s.theta_o);
    const std::size_t estimates = list.size() * sampling_strategies.size();
    output::ProgressLine progress;
    std::vector<SamplingRow> rows;
    for (const AnyNdf& ndf : list) {
        progress(static_cast<double>(rows.size()) / static_cast<double>(estimates), [&] {
            return "report: sampling experiment, " + std::to_string(rows.size()) + "/" + std::to_string(estimates) +
                " estimates";
        });
        const std::vector<std::function<double(Rng&)>> weights = strategy_weights(ndf, wo, samplers);
        for (std::size_t k = 0; k < weights.size(); ++k) {
            const auto [mean, variance] = mean_and_variance(weights[k], make_rng(s.seed, rows.size()), s.samples);
            rows.push_back({ndf.family(), std::string(sampling_strategies[k]), ndf.param("alpha"), s.samples, mean,
                            variance, NAN, weights[k]});
        }
    }
    return rows;
}

void add_sampling_timing(std::vector<SamplingRow>& rows, const SamplingScene& s, Timing& timing) {
    for (SamplingRow& r : rows) {
        auto g = std::make_shared<Rng>(make_rng(s.seed, 1u << 20));
        // One point, nothing in it: each call draws from the row's own stream.
        timing.add(
            "sampling/" + r.family + "(" + format_g17(r.alpha) + ")/" + r.strategy, std::vector<char>(1),
            [w = r.weight, g](char) { return w(*g); }, &r.ns);
    }
}

void write_sampling_section(const std::vector<SamplingRow>& rows, const SamplingScene& s,
                            const std::filesystem::path& dir) {
    std::ofstream csv(dir / "sampling.csv");
    write_csv_record(
        csv, {"family", "alpha", "strategy", "samples", "mean", "stderr", "variance", "ns_per_sample", "efficiency"});
    std::ofstream md(dir / "report.md", std::ios::app);
    md << format_printf(
              "\n## Sampling efficiency: cosine, D cos and visible-normal sampling\n\nDirectional albedo of a white "
              "conductor (F = 1, height-correlated G2) seen from theta_o = %g deg under a uniform white environment, "
              "%zu samples per estimate. Efficiency = 1 / (variance x seconds per sample); time per sample by Google "
              "Benchmark on one core. The three means estimate the same albedo.\n\n![](sampling_efficiency.png)\n\n",
              s.theta_o, s.samples)
       << "| ndf | strategy | albedo (mean +- stderr) | variance | ns/sample | efficiency (1/s) |\n"
       << "|---|---|---|---:|---:|---:|\n";
    for (const SamplingRow& r : rows) {
        const double se = std::sqrt(r.variance / static_cast<double>(r.samples)), eff = 1e9 / (r.variance * r.ns);
        write_csv_record(csv,
                         {r.family, format_g17(r.alpha), r.strategy, std::to_string(r.samples), format_g17(r.mean),
                          format_g17(se), format_g17(r.variance), format_g17(r.ns), format_g17(eff)});
        md << format_printf("| %s(%g) | %s | %.5f +- %.5f | %.3e | %.0f | %.3e |\n", r.family.c_str(), r.alpha,
                            r.strategy.c_str(), r.mean, se, r.variance, r.ns, eff);
    }
    output::finish(csv, dir / "sampling.csv");
    output::finish(md, dir / "report.md");
}

}  // namespace smithlab::report
