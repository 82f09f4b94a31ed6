// G1 of GTR for random (alpha, gamma, mu) streams: the family evaluator (gtr/family.hpp, two charts
// for every material) beside the routes a renderer has on the same inputs: the per-material LambdaTable (built once
// per (alpha, gamma): its build is not timed), Dimov's spline (dimov-spline), and the exact 1D quadrature (the fixed
// rule of lambda_fixed.hpp, and the adaptive GSL route). 64 materials (alpha log-uniform in [1e-4, 1], gamma uniform
// in [0, 20]) and 4096 (material, mu) pairs, mu log-uniform in [1e-3, 1e3]; each iteration is one G1.
// family/scattered times the same evaluator on 4096 points each of its own (alpha, gamma), mu log-uniform in
// [1e-8, 1e8]: both charts' trees in use.
// Run: build/bench/bench_family --benchmark_min_time=0.2   (one core)
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <smithlab/gtr.hpp>
#include <smithlab/gtr/family.hpp>
#include <smithlab/gtr/family_stream.hpp>
#include <string>
#include <vector>

namespace {

struct Stream {
    std::vector<double> alpha, gamma, mu;
    std::vector<int> material;
};

constexpr int n_materials = 64, n_points = 4096;

const Stream& stream() {
    static const Stream s = [] {
        Stream t;
        std::mt19937_64 rng(14);
        std::uniform_real_distribution<double> la(std::log(1e-4), 0.0), g(0.0, 20.0), lm(std::log(1e-3), std::log(1e3));
        std::vector<double> ma, mg;
        for (int m = 0; m < n_materials; ++m) ma.push_back(std::exp(la(rng))), mg.push_back(g(rng));
        for (int i = 0; i < n_points; ++i) {
            const int m = static_cast<int>(rng() % n_materials);
            t.material.push_back(m);
            t.alpha.push_back(ma[m]);
            t.gamma.push_back(mg[m]);
            t.mu.push_back(std::exp(lm(rng)));
        }
        return t;
    }();
    return s;
}

// Every point its own material: alpha log-uniform in [1e-4, 1], gamma uniform in [0, 20], mu log-uniform in
// [1e-8, 1e8] (both charts' trees in use, no two calls alike).
const Stream& scattered_stream() {
    static const Stream s = [] {
        Stream t;
        std::mt19937_64 rng(15);
        std::uniform_real_distribution<double> la(std::log(1e-4), 0.0), g(0.0, 20.0), lm(std::log(1e-8), std::log(1e8));
        for (int i = 0; i < n_points; ++i) {
            t.alpha.push_back(std::exp(la(rng))), t.gamma.push_back(g(rng)), t.mu.push_back(std::exp(lm(rng)));
            t.material.push_back(0);
        }
        return t;
    }();
    return s;
}

// n_points is a power of two: the next point is i & (n_points - 1), not i % n (a 64-bit division in every iteration,
// which cost each row here 2-5 ns)
static_assert((n_points & (n_points - 1)) == 0);
// The one-call rows are compiled for baseline x86-64 (glibc's libm picks its own FMA variants of log and exp at run
// time); their label says so, as the stream rows' name their route.
template <class F>
void run(benchmark::State& state, const Stream& s, const F& G1) {
    if (s.mu.size() != static_cast<std::size_t>(n_points))
        state.SkipWithError("a stream of other than n_points points");
    state.SetLabel("x86-64 baseline");
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(G1(i & (n_points - 1)));
        ++i;
    }
    state.SetItemsProcessed(state.iterations());
}

void BM_family(benchmark::State& state) {
    const smithlab::GtrFamily& f = smithlab::GtrFamily::get();
    const Stream& s = stream();
    run(state, s, [&](std::size_t i) { return f.G1_up(s.alpha[i], s.gamma[i], s.mu[i]); });
}
void BM_family_scattered(benchmark::State& state) {
    const smithlab::GtrFamily& f = smithlab::GtrFamily::get();
    const Stream& s = scattered_stream();
    run(state, s, [&](std::size_t i) { return f.G1_up(s.alpha[i], s.gamma[i], s.mu[i]); });
}
// The stream route (family_stream.hpp): each iteration is the whole stream of n_points G1s; the counter s_per_G1
// (seconds, "25n" = 25 ns) is the figure to set beside the rows above (the time column is per stream). Unchecked,
// as the one-call rows (GtrFamily::G1_up); the checked call (G1_gtr_family on spans) adds one pass over the inputs.
// The label names the instruction set the row ran: family-stream/* take the route chosen for this CPU,
// family-stream-avx2 and -avx512 the named route (skipped where this CPU does not run it).
using smithlab::GtrFamilyRoute;
using smithlab::GtrFamilyStream;
template <class F>
void run_stream(benchmark::State& state, GtrFamilyRoute route, const Stream& s, const F& G1_stream) {
    if (!GtrFamilyStream::get().runs(route)) {
        state.SkipWithError((std::string("this CPU or build has no ") + smithlab::name(route) + " route").c_str());
        return;
    }
    state.SetLabel(smithlab::name(route));
    std::vector<double> out(s.mu.size());
    for (auto _ : state) {
        G1_stream(route, s, out);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(out.size()));
    state.counters["s_per_G1"] = benchmark::Counter(
        static_cast<double>(out.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
void unchecked(GtrFamilyRoute route, const Stream& s, std::vector<double>& out) {
    GtrFamilyStream::get().G1_up(route, s.alpha.data(), s.gamma.data(), s.mu.data(), out.data(), out.size());
}
void checked(GtrFamilyRoute, const Stream& s, std::vector<double>& out) {
    smithlab::G1_gtr_family(s.alpha, s.gamma, s.mu, out);
}
GtrFamilyRoute chosen() { return GtrFamilyStream::get().route(); }
void BM_family_stream(benchmark::State& state) { run_stream(state, chosen(), stream(), unchecked); }
void BM_family_stream_scattered(benchmark::State& state) { run_stream(state, chosen(), scattered_stream(), unchecked); }
void BM_family_stream_checked(benchmark::State& state) { run_stream(state, chosen(), stream(), checked); }
void BM_family_stream_avx2(benchmark::State& state) { run_stream(state, GtrFamilyRoute::avx2, stream(), unchecked); }
void BM_family_stream_avx2_scattered(benchmark::State& state) {
    run_stream(state, GtrFamilyRoute::avx2, scattered_stream(), unchecked);
}
void BM_family_stream_avx512(benchmark::State& state) {
    run_stream(state, GtrFamilyRoute::avx512, stream(), unchecked);
}
void BM_table(benchmark::State& state) {
    const Stream& s = stream();
    static const std::vector<smithlab::LambdaTable> tables = [&] {
        std::vector<smithlab::LambdaTable> t;
        std::vector<bool> seen(n_materials, false);
        std::vector<int> order;
        for (int i = 0; i < n_points; ++i)
            if (!seen[s.material[i]]) seen[s.material[i]] = true, order.push_back(i);
        std::vector<int> where(n_materials, -1);
        for (int i : order) {
            where[s.material[i]] = static_cast<int>(t.size());
            t.push_back(smithlab::tabulate_Lambda(smithlab::gtr(s.alpha[i], s.gamma[i])));
        }
        std::vector<smithlab::LambdaTable> by_material;
        for (int m = 0; m < n_materials; ++m) by_material.push_back(where[m] >= 0 ? t[where[m]] : t[0]);
        return by_material;
    }();
    run(state, s, [&](std::size_t i) { return tables[s.material[i]].G1(s.mu[i]); });
}
void BM_dimov_spline(benchmark::State& state) {
    const Stream& s = stream();
    run(state, s, [&](std::size_t i) { return smithlab::G1_gtr_dimov_spline(s.alpha[i], s.gamma[i], s.mu[i]); });
}
void BM_exact_fixed(benchmark::State& state) {
    const Stream& s = stream();
    run(state, s, [&](std::size_t i) {
        return 1.0 /
            (1.0 +
             smithlab::Lambda_fixed(smithlab::gtr(s.alpha[i], s.gamma[i]), s.mu[i], {smithlab::Backend::gsl, 1e-12}));
    });
}
void BM_exact_gsl(benchmark::State& state) {
    const Stream& s = stream();
    run(state, s, [&](std::size_t i) {
        return 1.0 /
            (1.0 +
             smithlab::Lambda_1d(smithlab::gtr(s.alpha[i], s.gamma[i]), s.mu[i], {smithlab::Backend::gsl, 1e-12}));
    });
}

}  // namespace

BENCHMARK(BM_family)->Name("family/random");
BENCHMARK(BM_family_scattered)->Name("family/scattered");
BENCHMARK(BM_family_stream)->Name("family-stream/random");
BENCHMARK(BM_family_stream_scattered)->Name("family-stream/scattered");
BENCHMARK(BM_family_stream_checked)->Name("family-stream-checked/random");
BENCHMARK(BM_family_stream_avx2)->Name("family-stream-avx2/random");
BENCHMARK(BM_family_stream_avx2_scattered)->Name("family-stream-avx2/scattered");
BENCHMARK(BM_family_stream_avx512)->Name("family-stream-avx512/random");
BENCHMARK(BM_table)->Name("table/per-material");
BENCHMARK(BM_dimov_spline)->Name("dimov-spline/random");
BENCHMARK(BM_exact_fixed)->Name("exact-fixed-1e-12/random");
BENCHMARK(BM_exact_gsl)->Name("exact-gsl-1e-12/random");
BENCHMARK_MAIN();
