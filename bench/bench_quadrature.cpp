// The exact 1D route: Lambda by the reduced 1D integral at relative tolerance 1e-12, the fixed
// Gauss-Kronrod rule (lambda_fixed.hpp, method `fixed`) beside the adaptive routes it replaces (Lambda_1d with GSL
// QAG and with Boost tanh-sinh), on the same inputs in the same run, on the concrete NDF types (no virtual call).
// Cases: GGX, Beckmann, Blinn-Phong and GTR at ordinary (alpha, mu) and at stiff ones (mu ~ alpha = 1e-4, grazing
// mu = 1e-6, Beckmann at mu/alpha = 10, Blinn n = 0.1, GTR at gamma = 1 + 1e-9 and alpha = 1e-4).
// Counters: rel_err, the relative error of that route's Lambda against the closed form (GGX, Beckmann) or Boost's
// route at 1e-14 (the others); evals, the fixed rule's slope-density evaluations (the rule alone, before any
// fallback); fallback, 1 where its error estimate missed 1e-12 and the Boost route (the default backend) answered.
// Run: build/bench/bench_quadrature --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//      (one core; docs/performance.md quotes the medians)
#include <benchmark/benchmark.h>

#include <cmath>
#include <smithlab/gtr.hpp>
#include <string>

namespace {

using smithlab::Backend;

enum class Route { fixed, gsl, boost };

template <class N>
double lambda_by(Route r, const N& ndf, double mu) {
    switch (r) {
        case Route::fixed:
            return smithlab::Lambda_fixed(ndf, mu, {Backend::boost, 1e-12});
        case Route::gsl:
            return smithlab::Lambda_1d(ndf, mu, {Backend::gsl, 1e-12});
        case Route::boost:
            return smithlab::Lambda_1d(ndf, mu, {Backend::boost, 1e-12});
    }
    return 0.0;
}

template <class N>
void add(const std::string& name, const N& ndf, double mu, double reference) {
    for (Route r : {Route::fixed, Route::gsl, Route::boost}) {
        const char* rn = r == Route::fixed ? "fixed" : r == Route::gsl ? "gsl" : "boost";
        benchmark::RegisterBenchmark((name + "/" + rn).c_str(), [=](benchmark::State& state) {
            double value = 0.0;
            for (auto _ : state) {
                value = lambda_by(r, ndf, mu);
                benchmark::DoNotOptimize(value);
            }
            state.counters["rel_err"] = std::abs(value - reference) / reference;
            if (r == Route::fixed) {
                const smithlab::FixedLambda f = smithlab::Lambda_fixed_rule(ndf, mu, 1e-12);
                state.counters["evals"] = f.evaluations;
                state.counters["fallback"] = f.converged ? 0.0 : 1.0;
            }
        });
    }
}

template <class N>
void add_closed(const std::string& name, const N& ndf, double mu) {
    add(name + "/mu=" + std::to_string(mu).substr(0, 8), ndf, mu, ndf.Lambda(mu));
}

template <class N>
void add_quadrature(const std::string& name, const N& ndf, double mu) {
    add(name + "/mu=" + std::to_string(mu).substr(0, 8), ndf, mu,
        smithlab::Lambda_1d(ndf, mu, {Backend::boost, 1e-14}));
}

void register_all() {
    for (auto [a, mu] : {std::pair{0.1, 0.3}, {0.5, 1.0}, {0.1, 100.0}, {1e-4, 1e-4}, {0.5, 1e-6}})
        add_closed("ggx(" + std::to_string(a).substr(0, 6) + ")", smithlab::ggx(a), mu);
    for (auto [a, mu] : {std::pair{0.3, 1.0}, {0.1, 0.05}, {0.5, 0.3}, {0.1, 1.0}, {1e-3, 1e-6}})
        add_closed("beckmann(" + std::to_string(a).substr(0, 6) + ")", smithlab::beckmann(a), mu);
    for (auto [n, mu] : {std::pair{20.0, 1.0}, {1.0, 0.3}, {200.0, 0.05}, {0.1, 1.0}})
        add_quadrature("blinn(" + std::to_string(n).substr(0, 6) + ")", smithlab::blinn(n), mu);
    struct G {
        double alpha, gamma, mu;
    };
    for (G g : {G{0.3, 1.5, 1.0}, G{0.1, 0.5, 0.1}, G{0.3, 10.0, 2.0}, G{0.5, 2.5, 0.01}, G{1e-4, 1.0 + 1e-9, 1e-3},
                G{1e-4, 0.5, 1e-4}})
        add_quadrature(
            "gtr(" + std::to_string(g.alpha).substr(0, 6) + "," + std::to_string(g.gamma).substr(0, 11) + ")",
            smithlab::gtr(g.alpha, g.gamma), g.mu);
}

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    register_all();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
