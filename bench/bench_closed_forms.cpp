// The closed forms and Dimov's spline, beside their straightforward evaluation (tests/closed_forms_plain.hpp: the
// formulas as printed, with hypot, log and a quadrature where the paper has one), in the same run on the same random
// inputs, one core.
//   - G1 and Lambda of GGX and of GTR at gamma = 0..4 from mu = cot(theta), and from c = cos(theta) (plain: the
//     conversion mu = c / sqrt((1 - c)(1 + c)) then the mu route);
//   - Lambda of the generated forms (gamma = 5, 10, 20, 31);
//   - Dimov's spline G1 at random (alpha, gamma, mu), gamma in [0, 4], called directly and through the variant
//     interface (`dimov-spline`, a std::function per NDF, the report's ns/eval).
// Inputs: 4096 points, alpha log-uniform in [1e-3, 1], c = cos(theta) uniform in (0, 1), mu = cot(theta) from it,
// gamma uniform in [0, 4]; each iteration evaluates one point, cycling through them.
// Run: build/bench/bench_closed_forms --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <random>
#include <smithlab/gtr.hpp>
#include <string>
#include <vector>

#include "closed_forms_plain.hpp"

namespace {

struct Points {
    std::vector<double> alpha, gamma, mu, c;
};

const Points& points() {
    static const Points p = [] {
        Points q;
        std::mt19937_64 rng(14);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        for (int i = 0; i < 4096; ++i) {
            const double c = 1e-6 + (1.0 - 2e-6) * u(rng);
            q.alpha.push_back(std::pow(10.0, -3.0 * u(rng)));
            q.gamma.push_back(4.0 * u(rng));
            q.c.push_back(c);
            q.mu.push_back(c / std::sqrt((1.0 - c) * (1.0 + c)));
        }
        return q;
    }();
    return p;
}

// f(i) for point i, one per iteration.
template <class F>
void each(benchmark::State& state, F f) {
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(f(i));
        i = (i + 1) & 4095;
    }
    state.SetItemsProcessed(state.iterations());
}

double mu_of_cos_plain(double c) { return c / std::sqrt((1.0 - c) * (1.0 + c)); }

using B = benchmark::State;

// GGX.
void register_ggx(const Points& p) {
    benchmark::RegisterBenchmark("G1/ggx/mu/plain", [&p](B& s) {
        each(s, [&](std::size_t i) { return 1.0 / (1.0 + smithlab_plain::Ggx_Lambda(p.alpha[i], p.mu[i])); });
    });
    benchmark::RegisterBenchmark("G1/ggx/mu/after", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab::Ggx{p.alpha[i]}.G1(p.mu[i]); });
    });
    benchmark::RegisterBenchmark("G1/ggx/cos/plain", [&p](B& s) {
        each(s, [&](std::size_t i) {
            return 1.0 / (1.0 + smithlab_plain::Ggx_Lambda(p.alpha[i], mu_of_cos_plain(p.c[i])));
        });
    });
    benchmark::RegisterBenchmark("G1/ggx/cos/after", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab::G1_from_cos(smithlab::Ggx{p.alpha[i]}, p.c[i]); });
    });
    benchmark::RegisterBenchmark("Lambda/ggx/mu/plain", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab_plain::Ggx_Lambda(p.alpha[i], p.mu[i]); });
    });
    benchmark::RegisterBenchmark("Lambda/ggx/mu/after", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab::Ggx{p.alpha[i]}.Lambda(p.mu[i]); });
    });
}

// GTR, gamma = 0..4: G1 from mu (the free functions; Gtr::Lambda is Lambda_gtr_closed behind a check of gamma),
// G1 through Gtr::Lambda, and G1 from cos.
void register_gtr_closed(const Points& p) {
    for (int g = 0; g <= 4; ++g) {
        const std::string gs = std::to_string(g);
        benchmark::RegisterBenchmark(("G1/gtr" + gs + "/mu/plain").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) {
                return 1.0 / (1.0 + smithlab_plain::Lambda_gtr_closed(p.alpha[i], g, p.mu[i]));
            });
        });
        benchmark::RegisterBenchmark(("G1/gtr" + gs + "/mu/after").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) { return smithlab::G1_gtr_closed(p.alpha[i], g, p.mu[i]); });
        });
        benchmark::RegisterBenchmark(("G1/gtr" + gs + "/mu/after-Gtr::Lambda").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) {
                const smithlab::Gtr ndf{p.alpha[i], double(g), 0.0};  // K unused by Lambda
                return 1.0 / (1.0 + ndf.Lambda(p.mu[i]));
            });
        });
        benchmark::RegisterBenchmark(("G1/gtr" + gs + "/cos/plain").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) {
                return 1.0 / (1.0 + smithlab_plain::Lambda_gtr_closed(p.alpha[i], g, mu_of_cos_plain(p.c[i])));
            });
        });
        benchmark::RegisterBenchmark(("G1/gtr" + gs + "/cos/after").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) {
                const smithlab::Gtr ndf{p.alpha[i], double(g), 0.0};
                return smithlab::G1_from_cos(ndf, p.c[i]);
            });
        });
        benchmark::RegisterBenchmark(("Lambda/gtr" + gs + "/mu/plain").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) { return smithlab_plain::Lambda_gtr_closed(p.alpha[i], g, p.mu[i]); });
        });
        benchmark::RegisterBenchmark(("Lambda/gtr" + gs + "/mu/after").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) { return smithlab::Lambda_gtr_closed(p.alpha[i], g, p.mu[i]); });
        });
    }
}

// The generated forms.
void register_gtr_generated(const Points& p) {
    for (int g : {5, 10, 20, 31}) {
        const std::string gs = std::to_string(g);
        benchmark::RegisterBenchmark(("Lambda/gtr" + gs + "/mu/plain").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) { return smithlab_plain::Lambda_gtr_closed(p.alpha[i], g, p.mu[i]); });
        });
        benchmark::RegisterBenchmark(("Lambda/gtr" + gs + "/mu/after").c_str(), [&p, g](B& s) {
            each(s, [&](std::size_t i) { return smithlab::Lambda_gtr_closed(p.alpha[i], g, p.mu[i]); });
        });
    }
}

// Dimov's spline at random (alpha, gamma, mu): V-Ray's use, no per-material preparation.
void register_dimov_spline(const Points& p) {
    benchmark::RegisterBenchmark("G1/dimov-spline/plain", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab_plain::G1_gtr_dimov_spline(p.alpha[i], p.gamma[i], p.mu[i]); });
    });
    benchmark::RegisterBenchmark("G1/dimov-spline/after", [&p](B& s) {
        each(s, [&](std::size_t i) { return smithlab::G1_gtr_dimov_spline(p.alpha[i], p.gamma[i], p.mu[i]); });
    });
    // Through the variant interface (the report's route): one NDF, gtr(0.3, 1.5), mu cycling over the points.
    benchmark::RegisterBenchmark("Lambda/dimov-spline/variant/gtr(0.3,1.5)", [&p](B& s) {
        const auto variants = smithlab::builtin_variants();
        const smithlab::LambdaOfMu Lambda_of = smithlab::prepare(
            variants.at("dimov-spline"), smithlab::builtin_registry().make("gtr(alpha=0.3, gamma=1.5)"));
        each(s, [&](std::size_t i) { return Lambda_of(p.mu[i]); });
    });
}

void register_all() {
    const Points& p = points();
    register_ggx(p);
    register_gtr_closed(p);
    register_gtr_generated(p);
    register_dimov_spline(p);
}

}  // namespace

int main(int argc, char** argv) {
    register_all();
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
