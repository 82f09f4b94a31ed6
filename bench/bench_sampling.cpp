// Samples per second for each sampler (the concrete classes, as a renderer would call them), on GGX(0.3),
// Beckmann(0.3), GTR(0.3, 1.5) and a D-only NDF at theta_i = 45 degrees; and what preparing a sampler costs.
// Visible normals by the template on the concrete NDF (VisibleNormals<N>, as the walk calls it), closed form, GGX
// mixture and rejection, at 45, 135 and 170 degrees (wi below the horizon: a ray going up).
// Run: build/bench/bench_sampling --benchmark_min_time=0.2   (one core; docs/performance.md has the current numbers)
#include <benchmark/benchmark.h>

#include <smithlab/gtr.hpp>
#include <string>

namespace {

using smithlab::Vec3;

template <class F>
void run(benchmark::State& state, F&& draw) {
    smithlab::Rng g = smithlab::make_rng(1);
    for (auto _ : state) benchmark::DoNotOptimize(draw(g));
    state.SetItemsProcessed(state.iterations());
}

template <class N>
void register_for(const std::string& name, const N& ndf) {
    const Vec3 wi = smithlab::direction_from_theta_deg(45.0);
    benchmark::RegisterBenchmark(("dcos/" + name).c_str(), [ndf](benchmark::State& s) {
        const smithlab::DcosSampler d(ndf);
        run(s, [&](smithlab::Rng& g) { return d.sample(g).pdf; });
    });
    benchmark::RegisterBenchmark(("dcos-table/" + name).c_str(), [ndf](benchmark::State& s) {
        const smithlab::DcosSampler d(ndf, true);
        run(s, [&](smithlab::Rng& g) { return d.sample(g).pdf; });
    });
    benchmark::RegisterBenchmark(("vndf/" + name).c_str(), [ndf, wi](benchmark::State& s) {
        const smithlab::VisibleNormalSampler v(ndf);
        run(s, [&](smithlab::Rng& g) { return v.sample(wi, g).pdf; });
    });
    benchmark::RegisterBenchmark(("hammon/" + name).c_str(), [ndf, wi](benchmark::State& s) {
        const smithlab::HammonSampler h(ndf);
        run(s, [&](smithlab::Rng& g) { return h.sample_normal(wi, g).z(); });
    });
    benchmark::RegisterBenchmark(("hammon-upward/" + name).c_str(), [ndf](benchmark::State& s) {
        const smithlab::HammonSampler h(ndf);
        const Vec3 below = smithlab::direction_from_theta_deg(120.0);  // the ray travels up at 30 degrees
        run(s, [&](smithlab::Rng& g) { return h.sample_normal(below, g).z(); });
    });
    for (double theta : {45.0, 135.0, 170.0}) {
        const Vec3 v = smithlab::direction_from_theta_deg(theta);
        const std::string at = theta == 45.0 ? "/45" : theta == 135.0 ? "/135" : "/170";
        for (auto route :
             {smithlab::VisibleRoute::closed, smithlab::VisibleRoute::mixture, smithlab::VisibleRoute::rejection}) {
            const smithlab::VisibleNormals<N> vn(ndf, route);
            if (route == smithlab::VisibleRoute::closed && !vn.closed_form()) continue;
            if (route == smithlab::VisibleRoute::mixture && !vn.mixture()) continue;
            std::string label = vn.closed_form() ? "visible-closed/"
                : vn.mixture()                   ? "visible-mixture/"
                                                 : "visible-rejection/";
            label.append(name).append(at);
            benchmark::RegisterBenchmark(label.c_str(), [vn, v](benchmark::State& s) {
                run(s, [&](smithlab::Rng& g) { return vn.sample(v, g).z(); });
            });
        }
    }
    benchmark::RegisterBenchmark(("prepare-vndf/" + name).c_str(), [ndf](benchmark::State& s) {
        for (auto _ : s) benchmark::DoNotOptimize(smithlab::VisibleNormalSampler(ndf).table_error());
    })->Unit(benchmark::kMillisecond);
    // What a walk's microsurface builds once per cell: the automatic route (the mixture's fit, the Lambda spline).
    benchmark::RegisterBenchmark(("prepare-walk-normals/" + name).c_str(), [ndf](benchmark::State& s) {
        for (auto _ : s) benchmark::DoNotOptimize(smithlab::VisibleNormals<N>(ndf).table_error());
    })->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
    const Vec3 wi = smithlab::direction_from_theta_deg(45.0);
    benchmark::RegisterBenchmark("vndf-ggx/ggx(0.3)", [wi](benchmark::State& s) {
        run(s, [&](smithlab::Rng& g) { return smithlab::sample_ggx_visible(0.3, wi, g).pdf; });
    });
    register_for("ggx(0.3)", smithlab::ggx(0.3));
    register_for("beckmann(0.3)", smithlab::beckmann(0.3));
    register_for("gtr(0.3,1.5)", smithlab::gtr(0.3, 1.5));
    register_for("donly-ggx(0.3)", smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.3)});
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
