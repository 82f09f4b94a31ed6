// The sampling-efficiency experiment (the sampling blog's point, made quantitative). The directional albedo
// of a white conductor (F = 1, height-correlated G2) seen from theta_o under a uniform white environment,
//     A = integral f(wi, wo) cos(theta_i) d wi,   f = G2 D(h) / (4 cos_i cos_o)    (Walter 2007 eq. 20),
// estimated by sampling wi three ways; each weight f cos_i / pdf(wi):
//     cosine hemisphere  pdf = cos_i / pi                 weight = pi G2 D(h) / (4 cos_o cos_i)
//     D cos normals      pdf = D(m) cos_m / (4 wo.m)      weight = G2 (wo.m) / (cos_o cos_m)
//     visible normals    pdf = D_wo(m) / (4 wo.m)         weight = G2 / G1(wo)       (Heitz 2014, sec. 5)
// with wi = reflect(wo, m) and weight 0 when wi falls below the surface. All three estimate the same A; the
// report gives their variance, time per sample (Google Benchmark) and efficiency 1 / (variance x time).
// The section that runs it: sections/sampling.cpp.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "report/timing.hpp"
#include "smithlab/registry.hpp"
#include "smithlab/rng.hpp"

namespace smithlab::report {

// The scene's [sampling]: absent (families empty) unless named.
struct SamplingScene {
    std::vector<std::string> families;
    std::vector<double> alphas;
    double theta_o = 45.0;         // degrees
    std::size_t samples = 100000;  // per estimate
    unsigned long long seed = 1;
};

struct SamplingRow {
    std::string family, strategy;
    double alpha = 0.0;
    std::size_t samples = 0;
    double mean = 0.0, variance = 0.0;   // of the per-sample weight
    double ns = 0.0;                     // per sample, set by the timing
    std::function<double(Rng&)> weight;  // one sample of the estimator (for the timing)
};

// The strategies, in the order of the table.
inline constexpr std::array<std::string_view, 3> sampling_strategies = {"cosine", "dcos", "vndf"};

// The experiment's NDFs (families x alphas), checked: each family of one parameter, alpha, with a closed-form Lambda
// (for G2); theta_o in [0, 90). input_error otherwise, naming the family (the scene's reader adds the key and its
// FILE:LINE).
std::vector<AnyNdf> sampling_ndfs(const SamplingScene& s, const NdfRegistry& ndfs);

// One row per (NDF, strategy), estimated with s.samples samples each (a progress line on stderr past a few seconds).
std::vector<SamplingRow> run_sampling_experiment(const std::vector<AnyNdf>& ndfs, const SamplingScene& s);

// One item per row: one sample of its estimator, from a stream of its own.
void add_sampling_timing(std::vector<SamplingRow>& rows, const SamplingScene& s, Timing& timing);

// DIR/sampling.csv and the section appended to DIR/report.md: per (family, alpha) the strategies side by side.
void write_sampling_section(const std::vector<SamplingRow>& rows, const SamplingScene& s,
                            const std::filesystem::path& dir);

}  // namespace smithlab::report
