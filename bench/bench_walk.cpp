// Walks per second of the microsurface walk (sample estimator, one thread unless the name says threads:2), each
// benchmark named by its NDF and facet material, at theta_i = 45 degrees; items_per_second = walks/s, and the
// counters bounces = hits per walk and bounces_per_second = hits/s. "[hit_normal=hammon]": Hammon's D cos hit
// normals (walk::HitNormal) instead of visible normals. The yardstick: Heitz et al. 2016's public code,
// ~2.4-2.7 M walks/s per core here on GGX mirror alpha = 0.5 (float, global mt19937, virtual calls per bounce).
// Run: build/bench/bench_walk --benchmark_repetitions=7 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <smithlab/smithlab.hpp>
#include <smithlab/walk/trace.hpp>
#include <memory>
#include <string>

namespace {

using smithlab::Vec3;
namespace walk = smithlab::walk;

template <class MS, class M>
void walks(benchmark::State& state, const MS& ms, const M& material) {
    const Vec3 wi = smithlab::direction_from_theta_deg(45.0);
    std::uint64_t k = 0;
    std::int64_t bounces = 0;
    for (auto _ : state) {
        smithlab::WalkRng g(1, 0, k++);
        const walk::WalkSample s = walk::sample_walk(ms, material, wi, g);
        bounces += s.order;
        benchmark::DoNotOptimize(s.weight);
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["bounces"] = static_cast<double>(bounces) / static_cast<double>(state.iterations());
    state.counters["bounces_per_second"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
}

template <class N, class M>
void add(const std::string& name, const N& ndf, const M& material, const walk::MicrosurfaceOptions& opts = {}) {
    // The microsurface (its tables) is built once, outside the timed runs.
    auto ms = std::make_shared<const walk::Microsurface<N>>(ndf, opts);
    benchmark::RegisterBenchmark(("walk/" + name).c_str(), [ms, material](benchmark::State& s) { walks(s, *ms, material); });
}

template <class N, class M>
void add_cell(const std::string& name, const N& ndf, const M& material, unsigned threads) {
    benchmark::RegisterBenchmark(("cell/" + name + "/threads:" + std::to_string(threads)).c_str(),
                                 [ndf, material, threads](benchmark::State& s) {
                                     const walk::Microsurface ms(ndf);
                                     walk::CellRequest r;
                                     r.wi = smithlab::direction_from_theta_deg(45.0);
                                     r.walks = 400'000;
                                     r.threads = threads;
                                     std::int64_t bounces = 0;
                                     for (auto _ : s) bounces += walk::trace_cell(ms, material, r).albedo.events;
                                     s.SetItemsProcessed(s.iterations() * r.walks);
                                     s.counters["bounces_per_second"] =
                                         benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
}

const bool registered = [] {
    add("ggx(alpha=0.5)/mirror", smithlab::ggx(0.5), walk::Mirror{});
    add("ggx(alpha=0.5)/lambert(albedo=1)", smithlab::ggx(0.5), walk::Lambert{1.0});
    add("ggx(alpha=0.5)/fresnel-diffuse(f0=0.02, albedo=1)", smithlab::ggx(0.5), walk::FresnelDiffuse{0.02, 1.0});
    add("ggx(alpha=0.5)/conductor(eta=0.2, k=3)", smithlab::ggx(0.5), walk::Conductor{0.2, 3.0});
    add("ggx(alpha=0.5)/dielectric(eta=1.5)", smithlab::ggx(0.5), walk::Dielectric{1.5});
    add("ggx(alpha=0.5)/mirror[hit_normal=hammon]", smithlab::ggx(0.5), walk::Mirror{}, {.hit_normal = walk::HitNormal::hammon_dcos});
    add("beckmann(alpha=0.5)/mirror", smithlab::beckmann(0.5), walk::Mirror{});
    add("gtr(alpha=0.5, gamma=1.5)/mirror", smithlab::gtr(0.5, 1.5), walk::Mirror{});
    add("gtr(alpha=0.5, gamma=1.5)/lambert(albedo=1)", smithlab::gtr(0.5, 1.5), walk::Lambert{1.0});
    add("D-only ggx(alpha=0.5)/mirror", smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.5)}, walk::Mirror{});
    for (unsigned t : {1u, 2u}) add_cell("ggx(alpha=0.5)/mirror", smithlab::ggx(0.5), walk::Mirror{}, t);
    return true;
}();

}  // namespace

BENCHMARK_MAIN();
