// Lambda per method and backend (closed, spline, 1D Boost, 1D GSL, 2D) for GGX, GTR at a few gamma and the Student-t;
// the table (the fast evaluator) against the closed-form GGX G1; the grazing law; every registered variant.
// Each iteration evaluates one Lambda; mu cycles through 0.01 .. 100 so that no single easy point is timed.
// The variant/ rows are timed as `smithlab report` times its rows (experiments/report/timing_points.hpp: the same
// points of a grid, the same loop), so that bench/compare_report_timing.py can set the two side by side; the GTR
// family evaluator has two rows there, one call (variant/family/...) and the stream (variant/family-stream/...).
// Run: build/bench/bench_lambda --benchmark_min_time=0.2   (one core; the README has the current numbers)
#include <benchmark/benchmark.h>

#include <array>
#include <cstdio>
#include <smithlab/gtr.hpp>
#include <string>
#include <utility>

#include "report/timing_points.hpp"

namespace {

constexpr std::array<double, 5> mus = {0.01, 0.1, 1.0, 10.0, 100.0};

template <class N>
void run(benchmark::State& state, const N& ndf, smithlab::LambdaOptions opts) {
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(smithlab::Lambda(ndf, mus[i++ % mus.size()], opts));
    }
    state.SetItemsProcessed(state.iterations());
}

using smithlab::Backend;
using smithlab::Method;

void register_all() {
    struct Ndf {
        std::string name;
        smithlab::AnyNdf ndf;
    };
    const auto reg = smithlab::builtin_registry();
    const std::array<Ndf, 6> ndfs = {Ndf{"ggx(0.3)", reg.make("ggx(alpha=0.3)")},
                                     Ndf{"gtr(0.3,0.5)", reg.make("gtr(alpha=0.3, gamma=0.5)")},
                                     Ndf{"gtr(0.3,1)", reg.make("gtr(alpha=0.3, gamma=1)")},
                                     Ndf{"gtr(0.3,1.5)", reg.make("gtr(alpha=0.3, gamma=1.5)")},
                                     Ndf{"gtr(0.3,3)", reg.make("gtr(alpha=0.3, gamma=3)")},
                                     Ndf{"student(0.3,4)", reg.make("student(alpha=0.3, gamma=4)")}};
    // Closed forms on the concrete types (no virtual call): what a renderer would pay.
    benchmark::RegisterBenchmark("closed/ggx(0.3)", [](benchmark::State& s) { run(s, smithlab::ggx(0.3), {}); });
    for (int g : {0, 1, 2, 3, 4, 10, 20})
        benchmark::RegisterBenchmark(("closed/gtr(0.3," + std::to_string(g) + ")").c_str(),
                                     [g](benchmark::State& s) { run(s, smithlab::gtr(0.3, g), {}); });
    benchmark::RegisterBenchmark("closed/beckmann(0.3)",
                                 [](benchmark::State& s) { run(s, smithlab::beckmann(0.3), {}); });
    // The Student-t (Ribardiere et al. 2017): its closed form over mu = 0.01 .. 100 (z = mu / alpha = 0.03 .. 333), and
    // where it costs most, z in [0.7, 2] (its continued fraction just past the seam at z = 0.7, longer as gamma grows).
    for (double g : {1.65, 2.0, 4.0, 30.0, 1e4}) {
        char name[64];
        std::snprintf(name, sizeof name, "student(0.3,%g)", g);
        benchmark::RegisterBenchmark((std::string("closed/") + name).c_str(),
                                     [g](benchmark::State& s) { run(s, smithlab::student(0.3, g), {}); });
        benchmark::RegisterBenchmark((std::string("closed/z=0.7..2/") + name).c_str(), [g](benchmark::State& s) {
            const smithlab::StudentT ndf = smithlab::student(0.3, g);
            constexpr std::array<double, 5> zs = {0.71, 0.9, 1.2, 1.6, 2.0};
            std::size_t i = 0;
            for (auto _ : s) benchmark::DoNotOptimize(ndf.Lambda(0.3 * zs[i++ % zs.size()]));
            s.SetItemsProcessed(s.iterations());
        });
    }
    benchmark::RegisterBenchmark("spline/gtr(0.3,1.5)", [](benchmark::State& s) {
        run(s, smithlab::gtr(0.3, 1.5), {.method = Method::spline});
    });
    for (const Ndf& n : ndfs)
        for (Backend b : {Backend::boost, Backend::gsl}) {
            const std::string be(smithlab::to_string(b));
            for (double tol : {1e-8, 1e-12})
                benchmark::RegisterBenchmark(
                    ("quadrature1d/" + be + "/tol" + (tol == 1e-8 ? "1e-8/" : "1e-12/") + n.name).c_str(),
                    [n, b, tol](benchmark::State& s) {
                        run(s, n.ndf, {.method = Method::quadrature, .backend = b, .tolerance = tol});
                    });
            if (n.name == "ggx(0.3)" || n.name == "gtr(0.3,1.5)")
                benchmark::RegisterBenchmark(
                    ("quadrature2d/" + be + "/tol1e-10/" + n.name).c_str(),
                    [n, b](benchmark::State& s) {
                        run(s, n.ndf, {.method = Method::quadrature2d, .backend = b, .tolerance = 1e-10});
                    })
                    ->Unit(benchmark::kMicrosecond);
        }
}

// G1 = 1/(1 + Lambda_of(mu)), mu cycling over mus.
template <class F>
void time_G1(benchmark::State& state, const F& Lambda_of) {
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(1.0 / (1.0 + Lambda_of(mus[i++ % mus.size()])));
    state.SetItemsProcessed(state.iterations());
}

// G1 = 1/(1 + L.at_tan2(tan^2)), tan^2 = 1 / mu^2 cycling over mus.
template <class L>
void time_G1_tan2(benchmark::State& state, const L& fast) {
    std::size_t i = 0;
    constexpr std::array<double, 5> t2 = {1e4, 1e2, 1.0, 1e-2, 1e-4};  // tan^2 at mu = 0.01 .. 100
    for (auto _ : state) benchmark::DoNotOptimize(1.0 / (1.0 + fast.at_tan2(t2[i++ % t2.size()])));
    state.SetItemsProcessed(state.iterations());
}

// The yardstick and the Student-t's table; the walk's Lambda (FastLambda::at_tan2, tan^2 = 1 / mu^2 given): GGX's
// closed form, and the spline over the bits of tan^2 that every other NDF gets (detail/tan2_spline.hpp).
void register_table_yardsticks() {
    benchmark::RegisterBenchmark("G1/closed/ggx(0.3)", [](benchmark::State& s) {
        const smithlab::Ggx ggx = smithlab::ggx(0.3);
        time_G1(s, [&](double mu) { return ggx.Lambda(mu); });
    });
    benchmark::RegisterBenchmark("G1/closed/student(0.3,4)", [](benchmark::State& s) {
        const smithlab::StudentT ndf = smithlab::student(0.3, 4.0);
        time_G1(s, [&](double mu) { return ndf.Lambda(mu); });
    });
    benchmark::RegisterBenchmark("G1/table/student(0.3,4)", [](benchmark::State& s) {
        const smithlab::LambdaTable t = smithlab::tabulate_Lambda(smithlab::student(0.3, 4.0));
        time_G1(s, [&](double mu) { return t.Lambda(mu); });
    });
    benchmark::RegisterBenchmark("G1/walk-tan2/ggx(0.3)", [](benchmark::State& s) {
        time_G1_tan2(s, smithlab::FastLambda<smithlab::Ggx>(smithlab::ggx(0.3)));
    });
    benchmark::RegisterBenchmark("G1/walk-tan2/beckmann(0.3)", [](benchmark::State& s) {
        time_G1_tan2(s, smithlab::FastLambda<smithlab::Beckmann>(smithlab::beckmann(0.3)));
    });
    benchmark::RegisterBenchmark("G1/walk-tan2/gtr(0.3,1.5)", [](benchmark::State& s) {
        time_G1_tan2(s, smithlab::FastLambda<smithlab::Gtr>(smithlab::gtr(0.3, 1.5)));
    });
}

// GTR(0.3, gamma) by its table, and what building the table costs by the default route (auto: the closed form at
// integer gamma, else the fixed rule) beside the adaptive one that `auto` does not take.
void register_table_gtr() {
    for (double gamma : {0.5, 1.5, 2.0, 7.3, 15.0}) {
        const std::string name = "gtr(0.3," + std::to_string(gamma).substr(0, gamma < 10 ? 3 : 4) + ")";
        benchmark::RegisterBenchmark(("G1/table/" + name).c_str(), [gamma](benchmark::State& s) {
            const smithlab::LambdaTable t = smithlab::tabulate_Lambda(smithlab::gtr(0.3, gamma));
            time_G1(s, [&](double mu) { return t.Lambda(mu); });
        });
        for (const auto& [route, method] :
             {std::pair{"", smithlab::Method::automatic}, std::pair{"/adaptive", smithlab::Method::quadrature}})
            if (method == smithlab::Method::automatic || !smithlab::gtr_has_closed_form(gamma))
                benchmark::RegisterBenchmark(
                    ("table-build/" + name + route).c_str(),
                    [gamma, method](benchmark::State& s) {
                        for (auto _ : s)
                            benchmark::DoNotOptimize(
                                smithlab::tabulate_Lambda(smithlab::gtr(0.3, gamma), {.exact = {.method = method}})
                                    .knots());
                    })
                    ->Unit(benchmark::kMillisecond);
    }
}

// Far outside [1e-5, 1e5]: the table's small-mu asymptote (mu = 1e-7) and its continued tail (1e7) for a D-only
// GGX (nothing closed-form), against the exact route at 1e-7; and the table's build.
void register_table_donly() {
    using DOnlyGgx = smithlab::DOnly<smithlab::Ggx>;
    for (const auto& [at, mu] : {std::pair{"1e-7", 1e-7}, std::pair{"1e7", 1e7}}) {
        benchmark::RegisterBenchmark(
            (std::string("G1/table/outside-range/donly-ggx(0.3)/mu=") + at).c_str(), [mu](benchmark::State& s) {
                const smithlab::LambdaTable t = smithlab::tabulate_Lambda(DOnlyGgx{smithlab::ggx(0.3)});
                double m = mu;
                for (auto _ : s) {
                    benchmark::DoNotOptimize(m);  // not a constant to fold
                    benchmark::DoNotOptimize(t.G1(m));
                }
                s.SetItemsProcessed(s.iterations());
            });
    }
    benchmark::RegisterBenchmark("G1/quadrature1d/donly-ggx(0.3)/mu=1e-7", [](benchmark::State& s) {
        const DOnlyGgx ndf{smithlab::ggx(0.3)};
        double m = 1e-7;
        for (auto _ : s) {
            benchmark::DoNotOptimize(m);
            benchmark::DoNotOptimize(smithlab::G1(ndf, m));
        }
        s.SetItemsProcessed(s.iterations());
    })->Unit(benchmark::kMicrosecond);
    for (const auto& [route, method] :
         {std::pair{"", smithlab::Method::automatic}, std::pair{"/adaptive", smithlab::Method::quadrature}})
        benchmark::RegisterBenchmark(
            (std::string("table-build/donly-ggx(0.3)") + route).c_str(),
            [method](benchmark::State& s) {
                for (auto _ : s)
                    benchmark::DoNotOptimize(
                        smithlab::tabulate_Lambda(DOnlyGgx{smithlab::ggx(0.3)}, {.exact = {.method = method}}).knots());
            })
            ->Unit(benchmark::kMillisecond);
}

// The fast evaluator against the yardstick, the closed-form GGX G1: G1 = 1/(1 + Lambda) by each, on the
// concrete types; and what building a table costs (once per NDF).
void register_table() {
    register_table_yardsticks();
    register_table_gtr();
    register_table_donly();
}

// Below the quadrature domain (mu < 1e-12): the grazing law (grazing.hpp) for GTR(0.3, 1.5) and a D-only GGX. Its
// constants once per NDF (two quadratures: grazing-law-build), a Lambda from them (grazing-law/Lambda), and
// smithlab::Lambda by `auto`, which integrates the constants again on every call (no per-NDF state to keep them).
void register_grazing() {
    using DOnlyGgx = smithlab::DOnly<smithlab::Ggx>;
    constexpr std::array<double, 5> tiny = {1e-13, 1e-20, 1e-100, 1e-300, 4.9e-324};
    auto rows = [&](const std::string& name, const auto& ndf) {
        benchmark::RegisterBenchmark(("grazing-law-build/" + name).c_str(), [ndf](benchmark::State& s) {
            for (auto _ : s) benchmark::DoNotOptimize(smithlab::grazing_law(ndf).c);
        })->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("grazing-law/Lambda/" + name).c_str(), [ndf, tiny](benchmark::State& s) {
            const smithlab::GrazingLaw law = smithlab::grazing_law(ndf);
            std::size_t i = 0;
            for (auto _ : s) benchmark::DoNotOptimize(smithlab::Lambda_grazing(law, tiny[i++ % tiny.size()]));
            s.SetItemsProcessed(s.iterations());
        });
        benchmark::RegisterBenchmark(("grazing-law/auto-per-call/" + name).c_str(), [ndf, tiny](benchmark::State& s) {
            std::size_t i = 0;
            for (auto _ : s) benchmark::DoNotOptimize(smithlab::Lambda(ndf, tiny[i++ % tiny.size()]));
            s.SetItemsProcessed(s.iterations());
        })->Unit(benchmark::kMicrosecond);
    };
    rows("gtr(0.3,1.5)", smithlab::gtr(0.3, 1.5));
    rows("donly-ggx(0.3)", DOnlyGgx{smithlab::ggx(0.3)});
}

// Every registered variant, on the first of GTR(0.3, 1.5), GGX(0.3), Beckmann(0.3) it applies to, at the report's
// timing points of the grid {that NDF} x mus; the family evaluator also as a stream over the same points.
void register_variant(const smithlab::LambdaVariant& v, const smithlab::AnyNdf& ndf) {
    std::string spec = ndf.spec();
    std::erase(spec, ' ');
    benchmark::RegisterBenchmark(("variant/" + v.name + "/" + spec).c_str(), [v, ndf](benchmark::State& s) {
        const std::vector<smithlab::LambdaOfMu> prepared = {smithlab::prepare(v, ndf)};  // not timed
        const std::vector<smithlab::report::LambdaPoint> points = smithlab::report::lambda_timing_points(prepared, mus);
        smithlab::report::time_cycling(s, std::span<const smithlab::report::LambdaPoint>(points),
                                       smithlab::report::lambda_point_value);
    });
    if (v.name != "family") return;
    benchmark::RegisterBenchmark(("variant/family-stream/" + spec).c_str(), [ndf](benchmark::State& s) {
        const smithlab::report::GtrStreamPoints points =
            smithlab::report::gtr_stream_timing_points(std::span(&ndf, 1), mus);
        smithlab::report::time_stream(s, points.size(), [&](double* out) { points.G1(out); });
    });
}

void register_variants() {
    const auto reg = smithlab::builtin_registry();
    const std::array<smithlab::AnyNdf, 3> candidates = {reg.make("gtr(alpha=0.3, gamma=1.5)"),
                                                        reg.make("ggx(alpha=0.3)"), reg.make("beckmann(alpha=0.3)")};
    const smithlab::VariantRegistry variants = smithlab::builtin_variants();
    for (const smithlab::LambdaVariant& v : variants.list())
        for (const smithlab::AnyNdf& ndf : candidates)
            if (v.applies(ndf)) {
                register_variant(v, ndf);
                break;
            }
}

}  // namespace

int main(int argc, char** argv) {
    register_all();
    register_table();
    register_grazing();
    register_variants();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
