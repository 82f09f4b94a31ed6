// The diffuse fitter's costs: a training point's eval walk (split by diffuse events) and its tally, the equal-error
// time of a point by each eval estimator, one evaluation of each diffuse model, a whole fit, one alpha of an
// energy-compensation table, and a lookup of one; one node of the conductor compensation's scattering orders, and a
// lookup of them.
// Run: build/bench/bench_fit --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <smithlab/compensation/compensation.hpp>
#include <smithlab/compensation/scattering_orders.hpp>
#include <smithlab/fit/dataset.hpp>
#include <smithlab/fit/fit_model.hpp>
#include <smithlab/gtr.hpp>
#include <smithlab/walk/trace.hpp>
#include <string>
#include <utility>
#include <vector>

namespace {

using smithlab::Vec3;
namespace compensation = smithlab::compensation;
namespace fit = smithlab::fit;
namespace walk = smithlab::walk;

// items_per_second: eval walks per second, toward wo = (60, 135) from wi = (45, 0), Hammon's facets at albedo 1.
void eval_point(benchmark::State& state) {
    const walk::Microsurface ms(smithlab::ggx(0.5));
    const walk::FresnelDiffuse material{0.04, 1.0};
    const Vec3 wi = smithlab::direction_from_deg(45.0, 0.0), wo = smithlab::direction_from_deg(60.0, 135.0);
    fit::SplitMoments m;
    std::uint64_t k = 0;
    for (auto _ : state) {
        smithlab::WalkRng g(1, 0, k++);
        m.add(walk::eval_walk(ms, material, wi, wo, g).by_diffuse);
    }
    benchmark::DoNotOptimize(m.sum);
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(eval_point);

// The equal-error time of a fit point: what the fitter fits, the diffuse part at albedo 1 (sum of f_k, k >= 1, of
// f(wi, wo) |cos theta_o|), walk after walk by one estimator (walk.hpp, EvalEstimator). Counters: rel_var, the
// variance of one walk's value over its mean squared; s_to_1e-3, seconds (CPU) to a relative standard error of 1e-3,
// = time a walk x rel_var / 1e-6 (the work-normalized variance); items_per_second, walks.
template <class N, class M>
void equal_error(benchmark::State& state, const N& ndf, const M& material, fit::Directions d,
                 walk::EvalEstimator estimator) {
    const walk::Microsurface ms(ndf);
    const Vec3 wi = d.wi(), wo = d.wo();
    double sum = 0.0, sum2 = 0.0;
    std::uint64_t k = 0;
    for (auto _ : state) {
        smithlab::WalkRng g(1, 0, k++);
        const walk::EvalSample e = walk::eval_walk(ms, material, wi, wo, g, {}, estimator);
        double y = 0.0;
        for (int j = 1; j < walk::diffuse_bins; ++j) y += e.by_diffuse[j];
        sum += y;
        sum2 += y * y;
    }
    const double n = static_cast<double>(k), mean = sum / n, rel_var = (sum2 / n - mean * mean) / (mean * mean);
    state.counters["rel_var"] = rel_var;
    // (1e-6 / rel_var) x iterations / time, inverted: time / iterations x rel_var / 1e-6.
    state.counters["s_to_1e-3"] =
        benchmark::Counter(1e-6 / rel_var, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    state.SetItemsProcessed(state.iterations());
}

template <class N, class M>
void add_equal_error(const std::string& name, const N& ndf, const M& material) {
    // Fit points of the default training set's kind, grazing ones included: (theta_i, theta_o, phi), degrees.
    for (const fit::Directions d : {fit::Directions{45, 60, 135}, {0, 40, 0}, {60, 60, 180}, {80, 85, 0}, {15, 85, 90}})
        for (const auto& [label, e] : {std::pair{"next_event", walk::EvalEstimator::next_event},
                                       {"expected_first", walk::EvalEstimator::expected_first},
                                       {"reciprocal", walk::EvalEstimator::reciprocal},
                                       {"position_free", walk::EvalEstimator::position_free}}) {
            char where[64];
            std::snprintf(where, sizeof where, "(%g,%g,%g)/", d.theta_i, d.theta_o, d.phi);
            benchmark::RegisterBenchmark(("equal_error/" + name + where + label).c_str(), equal_error<N, M>, ndf,
                                         material, d, e);
        }
}

// The equal-error time of position_free against reciprocal (the fitter's) over a grid of fit points, the two run
// point by point in the same iteration (interleaved: the machine's drift falls on both alike): 30 pairs where
// neither direction is grazing -- theta_i in {25, 45, 65} x theta_o in {15, 40, 60} x phi in {0, 90, 180}, and
// theta_i = 0 toward theta_o in {15, 40, 60} -- and equal_error's five points, on Hammon's facets at albedo 1 (the
// fit's target: the diffuse part). Each point's s_to_1e-3 is its CPU time a walk x rel_var / 1e-6 (equal_error's);
// the counters are the ratios reciprocal / position_free over the 30 pairs and the five points (min, median, max;
// > 1: position_free is faster to a given error) and the median s_to_1e-3 of each over the 30.
struct GridPoint {
    fit::Directions d;
    double sum[2] = {}, sum2[2] = {}, seconds[2] = {};
    std::int64_t walks = 0;
    double s_to_1e3(int e) const {
        const double n = static_cast<double>(walks), mean = sum[e] / n;
        return seconds[e] / n * ((sum2[e] / n - mean * mean) / (mean * mean)) / 1e-6;
    }
};

std::vector<GridPoint> grid_points() {
    std::vector<GridPoint> out;
    for (double to : {15.0, 40.0, 60.0}) out.push_back({{0.0, to, 0.0}});
    for (double ti : {25.0, 45.0, 65.0})
        for (double to : {15.0, 40.0, 60.0})
            for (double phi : {0.0, 90.0, 180.0}) out.push_back({{ti, to, phi}});
    for (const fit::Directions d : {fit::Directions{45, 60, 135}, {0, 40, 0}, {60, 60, 180}, {80, 85, 0}, {15, 85, 90}})
        out.push_back({d});
    return out;
}

double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

template <class N>
void equal_error_grid(benchmark::State& state, const N& ndf) {
    const walk::Microsurface ms(ndf);
    const walk::FresnelDiffuse material{0.04, 1.0};
    constexpr walk::EvalEstimator estimators[2] = {walk::EvalEstimator::reciprocal, walk::EvalEstimator::position_free};
    constexpr std::int64_t walks = 512;  // per point, estimator and iteration
    std::vector<GridPoint> points = grid_points();
    std::uint64_t k0 = 0;
    for (auto _ : state) {
        for (std::size_t p = 0; p < points.size(); ++p) {
            GridPoint& g = points[p];
            const Vec3 wi = g.d.wi(), wo = g.d.wo();
            for (int e = 0; e < 2; ++e) {
                const auto start = std::chrono::steady_clock::now();
                for (std::int64_t k = 0; k < walks; ++k) {
                    smithlab::WalkRng rng(1 + e, p, k0 + static_cast<std::uint64_t>(k));
                    const walk::EvalSample s = walk::eval_walk(ms, material, wi, wo, rng, {}, estimators[e]);
                    double y = 0.0;
                    for (int j = 1; j < walk::diffuse_bins; ++j) y += s.by_diffuse[j];
                    g.sum[e] += y;
                    g.sum2[e] += y * y;
                }
                g.seconds[e] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            }
            g.walks += walks;
        }
        k0 += walks;
    }
    std::vector<double> grid, five, recip, free;
    for (std::size_t p = 0; p < points.size(); ++p) {
        const double r = points[p].s_to_1e3(0), f = points[p].s_to_1e3(1);
        (p < 30 ? grid : five).push_back(r / f);
        if (p < 30) recip.push_back(r), free.push_back(f);
    }
    state.counters["grid_min"] = *std::min_element(grid.begin(), grid.end());
    state.counters["grid_median"] = median_of(grid);
    state.counters["grid_max"] = *std::max_element(grid.begin(), grid.end());
    state.counters["five_min"] = *std::min_element(five.begin(), five.end());
    state.counters["five_max"] = *std::max_element(five.begin(), five.end());
    state.counters["s_to_1e-3_reciprocal"] = median_of(recip);
    state.counters["s_to_1e-3_position_free"] = median_of(free);
}

// GGX's D at alpha as a measured table, a row a degree to 89 (tabulated.hpp).
smithlab::TabulatedNdf tabulated_ggx(double alpha) {
    const smithlab::Ggx g = smithlab::ggx(alpha);
    std::string csv = "theta_deg,D\n";
    for (int t = 0; t <= 89; ++t)
        csv += std::to_string(t) + "," + smithlab::format_g17(g.D(std::cos(t * std::numbers::pi / 180.0))) + "\n";
    return smithlab::tabulated_ndf_from_csv(csv, "ggx.csv", {true});
}

// items_per_second: model evaluations per second over 64 direction pairs at alpha 0.5, published constants.
void model(benchmark::State& state, const fit::DiffuseModel* m) {
    std::vector<std::pair<Vec3, Vec3>> pairs;
    for (int i = 0; i < 64; ++i)
        pairs.emplace_back(smithlab::direction_from_deg(1.3 * i, 0.0),
                           smithlab::direction_from_deg(85.0 - 1.2 * i, 2.8 * i));
    double sum = 0.0;
    for (auto _ : state)
        for (const auto& [wi, wo] : pairs) sum += m->f(wi, wo, 0.5, 0.7, m->published.data());
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pairs.size()));
}

// One fit of Hammon's five constants to 144 synthetic points x 4 albedos (its own values at perturbed constants).
void hammon_fit(benchmark::State& state) {
    const fit::DiffuseModel& m = fit::find_diffuse_model("hammon-2017");
    const std::vector<double> truth{0.85, 0.45, 0.55, 1.0, 0.15};
    fit::FitData data{{}, {0.25, 0.5, 0.75, 1.0}, 0.02, {}};
    for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double ti : {0.0, 30.0, 60.0, 80.0})
            for (double to : {10.0, 40.0, 70.0})
                for (double phi : {0.0, 90.0, 180.0}) {
                    fit::DataPoint p{alpha, {ti, to, phi}, {}};
                    const Vec3 a = p.dir.wi(), b = p.dir.wo();
                    // f(a) = c1 a + c2 a^2 from f(1) and f(1/2); walks spread by +-2% about it.
                    const double f1 = m.f(a, b, alpha, 1.0, truth.data()) * b.z(),
                                 fh = m.f(a, b, alpha, 0.5, truth.data()) * b.z();
                    const double c2 = 2.0 * f1 - 4.0 * fh, c1 = f1 - c2;
                    for (int w = 0; w < 20; ++w) {
                        fit::Split x{};
                        x[1] = c1 * (1.0 + 0.01 * ((w % 5) - 2));
                        x[2] = c2 * (1.0 + 0.01 * ((w % 3) - 1));
                        p.moments.add(x);
                    }
                    data.points.push_back(p);
                }
    for (auto _ : state) benchmark::DoNotOptimize(fit::fit_model(m, data, "bench").chi2);
}
BENCHMARK(hammon_fit)->Unit(benchmark::kMillisecond);

// One alpha's row of the fit's compensation table (tolerance compensation::table_tolerance): E at its 48 warped
// cosines, and 1 - E_avg by its own quadrature. A table of n_alpha rows measured on its 10x finer check grid costs ~100
// n_alpha such rows of E.
void compensation_row(benchmark::State& state, double alpha) {
    compensation::AlbedoOptions opts;
    opts.tolerance = compensation::table_tolerance;
    for (auto _ : state) {
        const compensation::SingleScatteringAlbedo<smithlab::Ggx> E(smithlab::ggx(alpha), opts);
        const double c = E.warp_scale();
        double sum = E.missing();
        for (int j = 0; j < 48; ++j) sum += E(compensation::unwarp_cosine(c, j / 47.0));
        benchmark::DoNotOptimize(sum);
    }
}

// The dielectric albedos {E_R, E_T} at 21 cosines j / 20 (tolerance compensation::table_tolerance); items_per_second:
// values.
void compensation_dielectric(benchmark::State& state, double alpha, double eta) {
    compensation::AlbedoOptions opts;
    opts.tolerance = compensation::table_tolerance;
    const compensation::SingleScatteringAlbedo<smithlab::Ggx> E(smithlab::ggx(alpha), opts);
    for (auto _ : state)
        for (int j = 0; j <= 20; ++j) benchmark::DoNotOptimize(E.dielectric(j / 20.0, eta).T);
    state.SetItemsProcessed(state.iterations() * 21);
}

// A lookup of a table as the fit writes it (64 alphas cube-root spaced from 1e-4 to 1, GGX's warp scales): E of
// mirror facets (48 cosines, the warp), or ln(E_R + E_T) from inside eta 1.5 (96 cosines, the warp and the critical
// angle's cluster, then exp); 1024 points spread over alpha and mu a pass; items_per_second: lookups.
void compensation_lookup(benchmark::State& state, bool dielectric) {
    compensation::AlbedoGrid grid{{}, {}, 48, {}};
    for (int i = 0; i < 64; ++i) {
        const double s = std::cbrt(1e-4) + (1.0 - std::cbrt(1e-4)) * i / 63.0;
        grid.alphas.push_back(std::min(s * s * s, 1.0));
        grid.scales.push_back(
            compensation::SingleScatteringAlbedo<smithlab::Ggx>(smithlab::ggx(grid.alphas.back())).warp_scale());
    }
    compensation::AlbedoTable t{
        dielectric ? compensation::dielectric_grid(grid, 96, 1.0 / 1.5) : grid, {}, compensation::Stored::value};
    if (dielectric) t.stored = compensation::Stored::log;
    t.values.assign(t.grid.alphas.size() * static_cast<std::size_t>(t.grid.n_x), -0.1);
    std::vector<std::pair<double, double>> points;
    for (int k = 0; k < 1024; ++k) points.emplace_back(std::pow(10.0, -4.0 * ((k * 37) % 1024) / 1024.0), k / 1023.0);
    for (auto _ : state)
        for (const auto& [alpha, mu] : points) benchmark::DoNotOptimize(t.lookup(alpha, mu));
    state.SetItemsProcessed(state.iterations() * 1024);
}

// One node of the scattering orders' tables (compensation/scattering_orders.hpp): 10 000 mirror-facet walks from 60
// degrees on GGX, counted; items_per_second: walks. The fit's default, 16 x 16 nodes of 100 000 walks, is 2.56e7 walks
// a family.
void order_node(benchmark::State& state, double alpha) {
    const walk::Microsurface ms(smithlab::ggx(alpha));
    walk::CellRequest r;
    r.wi = smithlab::direction_from_deg(60.0, 0.0);
    r.walks = 10'000;
    r.threads = 1;
    for (auto _ : state) {
        ++r.cell;
        benchmark::DoNotOptimize(
            compensation::scattering_orders(walk::trace_cell(ms, walk::Mirror{}, r).albedo).orders.q2);
    }
    state.SetItemsProcessed(state.iterations() * r.walks);
}

// A renderer's multiply scattered albedo of a conductor from the orders' tables: q_2, q_3 and p looked up (16 alphas
// cube-root spaced from 0.01 to 1 x 16 warped cosines, GGX's scales) and multiple_scattering_albedo; 1024 points a
// pass; items_per_second: albedos.
void order_lookup(benchmark::State& state) {
    compensation::AlbedoGrid grid{{}, {}, 16, {}};
    for (int i = 0; i < 16; ++i) {
        const double s = std::cbrt(0.01) + (1.0 - std::cbrt(0.01)) * i / 15.0;
        grid.alphas.push_back(std::min(s * s * s, 1.0));
        grid.scales.push_back(
            compensation::SingleScatteringAlbedo<smithlab::Ggx>(smithlab::ggx(grid.alphas.back())).warp_scale());
    }
    compensation::OrderTables t;
    for (auto [table, v] : {std::pair{&t.q2, 0.5}, std::pair{&t.q3, 0.2}, std::pair{&t.p, 0.7}})
        *table = compensation::AlbedoTable{grid, std::vector<double>(16 * 16, v), compensation::Stored::value};
    std::vector<std::pair<double, double>> points;
    for (int k = 0; k < 1024; ++k) points.emplace_back(std::pow(10.0, -2.0 * ((k * 37) % 1024) / 1024.0), k / 1023.0);
    for (auto _ : state)
        for (const auto& [alpha, mu] : points)
            benchmark::DoNotOptimize(compensation::multiple_scattering_albedo(0.8, t.lookup(alpha, mu), 0.9));
    state.SetItemsProcessed(state.iterations() * 1024);
}

}  // namespace

int main(int argc, char** argv) {
    const walk::FresnelDiffuse hammon{0.04, 1.0};
    add_equal_error("ggx(alpha=0.5)/fresnel-diffuse", smithlab::ggx(0.5), hammon);
    add_equal_error("ggx(alpha=0.5)/lambert", smithlab::ggx(0.5), walk::Lambert{1.0});
    add_equal_error("gtr(alpha=0.5, gamma=1)/fresnel-diffuse", smithlab::gtr(0.5, 1.0), hammon);
    add_equal_error("gtr(alpha=0.5, gamma=3)/fresnel-diffuse", smithlab::gtr(0.5, 3.0), hammon);
    for (const double a : {0.1, 0.5, 1.0}) {
        const std::string at = "(alpha=" + smithlab::format_shortest(a) + ")";
        const auto add = [&](const std::string& name, const auto& ndf) {
            benchmark::RegisterBenchmark(("equal_error_grid/" + name).c_str(),
                                         equal_error_grid<std::decay_t<decltype(ndf)>>, ndf)
                ->Unit(benchmark::kMillisecond)
                ->Iterations(8);
        };
        add("ggx" + at, smithlab::ggx(a));
        add("gtr" + at.substr(0, at.size() - 1) + ", gamma=1)", smithlab::gtr(a, 1.0));
        add("gtr" + at.substr(0, at.size() - 1) + ", gamma=3)", smithlab::gtr(a, 3.0));
        add("beckmann" + at, smithlab::beckmann(a));
        add("tabulated ggx" + at, tabulated_ggx(a));
    }
    for (const fit::DiffuseModel& m : fit::diffuse_models())
        benchmark::RegisterBenchmark(("model/" + std::string(m.name)).c_str(), model, &m);
    for (double a : {0.1, 0.5, 1.0})
        benchmark::RegisterBenchmark(("compensation/ggx(" + std::to_string(a).substr(0, 3) + ")").c_str(),
                                     compensation_row, a)
            ->Unit(benchmark::kMillisecond);
    for (double a : {0.1, 0.5})
        for (const auto& [label, eta] : {std::pair{"1.5", 1.5}, {"1/1.5", 1.0 / 1.5}})
            benchmark::RegisterBenchmark(
                ("compensation_dielectric/ggx(" + std::to_string(a).substr(0, 3) + ")/eta=" + label).c_str(),
                compensation_dielectric, a, eta)
                ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("compensation_lookup/E", compensation_lookup, false);
    benchmark::RegisterBenchmark("compensation_lookup/ln(E_R+E_T) inside eta=1.5", compensation_lookup, true);
    for (double a : {0.1, 0.5, 1.0})
        benchmark::RegisterBenchmark(("order_node/ggx(" + std::to_string(a).substr(0, 3) + ")").c_str(), order_node, a)
            ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("order_lookup", order_lookup);
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
