// The points a Lambda variant is timed at, and the timed loops: one definition for the report (timing.hpp) and
// bench/bench_lambda.cpp, so that the two time the same calls on the same points and their ns/eval can be set side
// by side (bench/compare_report_timing.py). Header-only, on smithlab's public API and Google Benchmark alone, so
// that a benchmark includes it without the command line's library.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "smithlab/any_ndf.hpp"
#include "smithlab/gtr/family_stream.hpp"
#include "smithlab/variants.hpp"

namespace smithlab::report {

// A point of a grid of NDFs x mu, by index.
struct GridIndex {
    std::size_t ndf, mu;
};

// The points of the grid n_ndfs x n_mus (NDF-major) a variant is timed at: every step-th, step = max(1, total / 64),
// from the first; so a grid of up to 127 points is timed whole, a larger one at 64 to 127 points spread over it.
inline std::vector<GridIndex> timing_points(std::size_t n_ndfs, std::size_t n_mus) {
    std::vector<GridIndex> out;
    const std::size_t total = n_ndfs * n_mus, step = std::max<std::size_t>(1, total / 64);
    for (std::size_t k = 0; k < total; k += step) out.push_back({k / n_mus, k % n_mus});
    return out;
}

// A Lambda variant prepared for one NDF of the grid (variants.hpp), at one mu; lambda_point_value evaluates it.
struct LambdaPoint {
    const LambdaOfMu* Lambda;
    double mu;
};
inline double lambda_point_value(const LambdaPoint& p) { return (*p.Lambda)(p.mu); }
// The timing points of a variant prepared for each NDF of a grid (prepared[n] for NDF n) over mus. prepared must
// outlive the points.
inline std::vector<LambdaPoint> lambda_timing_points(std::span<const LambdaOfMu> prepared,
                                                     std::span<const double> mus) {
    std::vector<LambdaPoint> out;
    for (const GridIndex& i : timing_points(prepared.size(), mus.size())) out.push_back({&prepared[i.ndf], mus[i.mu]});
    return out;
}

// The same points as parallel arrays, for the GTR family's stream evaluator (gtr/family_stream.hpp): ndfs are GTRs.
struct GtrStreamPoints {
    std::vector<double> alpha, gamma, mu;
    std::size_t size() const { return mu.size(); }
    // G1 at every point into out (GtrFamilyStream::G1_up: eight points at a time where the CPU has AVX-512, four with
    // AVX2).
    void G1(double* out) const { GtrFamilyStream::get().G1_up(alpha.data(), gamma.data(), mu.data(), out, mu.size()); }
};
inline GtrStreamPoints gtr_stream_timing_points(std::span<const AnyNdf> ndfs, std::span<const double> mus) {
    GtrStreamPoints out;
    for (const GridIndex& i : timing_points(ndfs.size(), mus.size())) {
        out.alpha.push_back(ndfs[i.ndf].param("alpha"));
        out.gamma.push_back(ndfs[i.ndf].param("gamma"));
        out.mu.push_back(mus[i.mu]);
    }
    return out;
}

// eval(p) for p cycling through points, one call an iteration (points not empty). The loop is compiled for the
// concrete eval (no type erasure of its own) and wraps by a comparison (no division).
template <class Point, class Eval>
void time_cycling(benchmark::State& state, std::span<const Point> points, const Eval& eval) {
    const Point* const first = points.data();
    const Point* const end = first + points.size();
    const Point* p = first;
    for (auto _ : state) {
        benchmark::DoNotOptimize(eval(*p));
        if (++p == end) p = first;
    }
    state.SetItemsProcessed(state.iterations());
}

// stream(out) evaluates n points into out, the whole stream an iteration; the time is per stream, the counter
// ns_per_eval (and items per second) per point.
template <class Stream>
void time_stream(benchmark::State& state, std::size_t n, const Stream& stream) {
    std::vector<double> out(n);
    for (auto _ : state) {
        stream(out.data());
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<benchmark::IterationCount>(n));
    state.counters["ns_per_eval"] = benchmark::Counter(
        static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

}  // namespace smithlab::report
