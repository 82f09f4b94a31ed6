// Walks per second of the microsurface walk (sample estimator, one thread unless the name says threads:2), each
// benchmark named by its NDF and facet material, at theta_i = 45 degrees; items_per_second = walks/s, and the
// counters bounces = hits per walk and bounces_per_second = hits/s. "[hit_normal=hammon]": Hammon's D cos hit
// normals (walk::HitNormal) instead of visible normals. The yardstick: Heitz et al. 2016's public code,
// ~2.4-2.7 M walks/s per core here on GGX mirror alpha = 0.5 (float, global mt19937, virtual calls per bounce).
// The block/ rows time what a command runs, a block of 4096 walks: the D-only GGX on its own type (walk::trace_block),
// the same D registered as a plug-in and run through the surface its registration records (smithlab/surface.hpp: one
// virtual call a block), and through AnyNdf itself (a virtual D and Lambda a call: what an unregistered NDF gets);
// and GGX's D as a measured table (tabulated.hpp: 100 rows to 89 degrees), registered as `tabulated` is; GGX with
// mirror facets built in, as a registered material walked as its own type (material_kernels.hpp: one virtual call
// a block), and as one registered without GGX's type listed (the NDF erased).
// The ndf/ rows: every built-in family at roughness alpha = 0.1, 0.5, 1 (GTR at gamma 1, 1.5, 3; Student at gamma 4;
// ABC at c = 2; Blinn by its roughness mapping) and GGX's D as a 100-row table, with mirror and lambert facets, as a
// command runs them (blocks of 4096 through the registered surface); items_per_second = walks/s, so ns a walk is its
// inverse. Compare a row with ggx at the same alpha and material, in the same run.
// Run: build/bench/bench_walk --benchmark_repetitions=7 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <smithlab/gtr.hpp>
#include <smithlab/surface.hpp>
#include <smithlab/walk/trace.hpp>
#include <string>
#include <variant>
#include <vector>

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
    state.counters["bounces_per_second"] =
        benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
}

template <class N, class M>
void add(const std::string& name, const N& ndf, const M& material, const walk::MicrosurfaceOptions& opts = {}) {
    // The microsurface (its tables) is built once, outside the timed runs.
    auto ms = std::make_shared<const walk::Microsurface<N>>(ndf, opts);
    benchmark::RegisterBenchmark(("walk/" + name).c_str(),
                                 [ms, material](benchmark::State& s) { walks(s, *ms, material); });
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

// A plug-in's D, written as a user would: GGX's D and nothing else.
struct PlugInGgx {
    smithlab::Ggx ggx;
    double D(double c) const { return ggx.D(c); }
};

walk::CellRequest block_request() {
    walk::CellRequest r;
    r.wi = smithlab::direction_from_theta_deg(45.0);
    r.walks = std::int64_t{1} << 40;  // blocks of 4096 from an unbounded cell: block b is walks [4096 b, 4096 (b + 1))
    return r;
}

template <class Run>
void add_block(const std::string& name, Run run) {
    benchmark::RegisterBenchmark(("block/" + name).c_str(), [run](benchmark::State& s) {
        const walk::CellRequest r = block_request();
        std::uint64_t b = 0;
        std::int64_t bounces = 0;
        for (auto _ : s) bounces += run(r, b++).albedo.events;
        s.SetItemsProcessed(s.iterations() * r.block);
        s.counters["bounces_per_second"] =
            benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
    })->Unit(benchmark::kMicrosecond);
}

template <class N>
void add_block_of(const std::string& name, const N& ndf) {
    auto ms = std::make_shared<const walk::Microsurface<N>>(ndf);
    add_block(name, [ms](const walk::CellRequest& r, std::uint64_t b) {
        return walk::trace_block(*ms, walk::Mirror{}, r, b);
    });
}

void add_block_of(const std::string& name, const smithlab::AnyNdf& ndf,
                  const walk::Material& material = walk::Mirror{}) {
    const std::shared_ptr<const smithlab::AnySurface> surface = smithlab::make_surface(ndf);
    add_block(name, [surface, material](const walk::CellRequest& r, std::uint64_t b) {
        return surface->trace_block(material, r, b);
    });
}

// Mirror facets as a plug-in material: walk::Mirror's members, registered under its own name.
struct PlugInMirror : walk::Mirror {
    static walk::MaterialInfo info() { return {"plugin-mirror", {}, "walk::Mirror, registered"}; }
    static PlugInMirror make(const walk::MaterialParams&) { return {}; }
    smithlab::NdfSpec spec() const { return {"plugin-mirror", {}}; }
};

// The same walk through the surface of a registered GGX with the material built in, registered with the NDF types
// listed (its own compiled walk), and registered with none listed (the NDF erased).
void add_registered_materials() {
    const smithlab::NdfRegistry builtin = smithlab::builtin_registry();
    const smithlab::AnyNdf ggx = builtin.make("ggx(alpha=0.5)");
    smithlab::MaterialRegistry listed, erased;
    listed.add<PlugInMirror>(smithlab::builtin_ndf_types{});
    erased.add<PlugInMirror>(smithlab::NdfTypes<>{});
    add_block_of("ggx(alpha=0.5)/mirror, built in", ggx);
    add_block_of("ggx(alpha=0.5)/plug-in mirror, registered", ggx, listed.make("plugin-mirror"));
    add_block_of("ggx(alpha=0.5)/plug-in mirror, NDF erased", ggx, erased.make("plugin-mirror"));
}

// GGX's D at roughness alpha as a table of 100 rows to 89 degrees (CSV text).
std::string ggx_table(double alpha) {
    std::string table = "theta_deg,D\n";
    for (int i = 0; i < 100; ++i) {
        const double deg = 89.0 * i / 99.0;
        char row[64];
        std::snprintf(row, sizeof row, "%.17g,%.17g\n", deg,
                      smithlab::ggx(alpha).D(std::cos(deg * std::numbers::pi / 180.0)));
        table += row;
    }
    return table;
}

void add_family_matrix() {
    smithlab::NdfRegistry registry = smithlab::builtin_registry();
    const std::vector<std::pair<std::string, std::vector<std::pair<std::string, double>>>> families = {
        {"ggx", {}},
        {"beckmann", {}},
        {"blinn", {}},
        {"gtr", {{"gamma", 1.0}}},
        {"gtr", {{"gamma", 1.5}}},
        {"gtr", {{"gamma", 3.0}}},
        {"student", {{"gamma", 4.0}}},
        {"abc", {{"c", 2.0}}}};
    for (double alpha : {0.1, 0.5, 1.0}) {
        std::vector<smithlab::AnyNdf> ndfs;
        for (const auto& [family, others] : families) ndfs.push_back(registry.make_at_alpha(family, alpha, others));
        const std::string a = alpha == 1.0 ? "1" : alpha == 0.5 ? "0.5" : "0.1";
        const std::string table = "ggx_table_" + std::to_string(static_cast<int>(alpha * 100));
        registry.add({table, {}, "GGX's D as a table of 100 rows", {}},
                     [rows = ggx_table(alpha)](const smithlab::NdfParams&) {
                         return smithlab::tabulated_ndf_from_csv(rows, "ggx.csv");
                     });
        ndfs.push_back(registry.make(table));
        for (const smithlab::AnyNdf& ndf : ndfs)
            for (const walk::Material& m : {walk::Material{walk::Mirror{}}, walk::Material{walk::Lambert{1.0}}}) {
                const std::shared_ptr<const smithlab::AnySurface> surface = smithlab::make_surface(ndf);
                const std::string material = (m.get_if<walk::Mirror>() != nullptr) ? "mirror" : "lambert";
                benchmark::RegisterBenchmark(("ndf/alpha=" + a + "/" + ndf.spec() + "/" + material).c_str(),
                                             [surface, m](benchmark::State& s) {
                                                 const walk::CellRequest r = block_request();
                                                 std::uint64_t b = 0;
                                                 std::int64_t bounces = 0;
                                                 for (auto _ : s)
                                                     bounces += surface->trace_block(m, r, b++).albedo.events;
                                                 s.SetItemsProcessed(s.iterations() * r.block);
                                                 s.counters["bounces"] = static_cast<double>(bounces) /
                                                     static_cast<double>(s.iterations() * r.block);
                                             })
                    ->Unit(benchmark::kMicrosecond);
            }
    }
}

const bool registered = [] {
    add("ggx(alpha=0.5)/mirror", smithlab::ggx(0.5), walk::Mirror{});
    add("ggx(alpha=0.5)/lambert(albedo=1)", smithlab::ggx(0.5), walk::Lambert{1.0});
    add("ggx(alpha=0.5)/fresnel-diffuse(f0=0.02, albedo=1)", smithlab::ggx(0.5), walk::FresnelDiffuse{0.02, 1.0});
    add("ggx(alpha=0.5)/conductor(eta=0.2, k=3)", smithlab::ggx(0.5), walk::Conductor{0.2, 3.0});
    add("ggx(alpha=0.5)/dielectric(eta=1.5)", smithlab::ggx(0.5), walk::Dielectric{1.5});
    add("ggx(alpha=0.5)/mirror[hit_normal=hammon]", smithlab::ggx(0.5), walk::Mirror{},
        {.hit_normal = walk::HitNormal::hammon_dcos});
    add("beckmann(alpha=0.5)/mirror", smithlab::beckmann(0.5), walk::Mirror{});
    add("gtr(alpha=0.5, gamma=1.5)/mirror", smithlab::gtr(0.5, 1.5), walk::Mirror{});
    add("gtr(alpha=0.5, gamma=1.5)/lambert(albedo=1)", smithlab::gtr(0.5, 1.5), walk::Lambert{1.0});
    add("D-only ggx(alpha=0.5)/mirror", smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.5)}, walk::Mirror{});
    for (unsigned t : {1u, 2u}) add_cell("ggx(alpha=0.5)/mirror", smithlab::ggx(0.5), walk::Mirror{}, t);

    smithlab::NdfRegistry registry;
    registry.add({"plugin_ggx", {"alpha"}, "GGX's D alone, registered", {}},
                 [](const smithlab::NdfParams& p) { return PlugInGgx{smithlab::ggx(p.at("alpha"))}; });
    const smithlab::AnyNdf plugin = registry.make("plugin_ggx(alpha=0.5)");
    add_block_of("D-only ggx(alpha=0.5)/mirror", smithlab::DOnly<smithlab::Ggx>{smithlab::ggx(0.5)});
    add_block_of("plug-in ggx(alpha=0.5), registered/mirror", plugin);
    add_block_of("plug-in ggx(alpha=0.5), through AnyNdf/mirror", smithlab::as_any(PlugInGgx{smithlab::ggx(0.5)}));
    smithlab::NdfRegistry tabulated;
    tabulated.add({"ggx_table", {}, "GGX's D as a table of 100 rows", {}}, [](const smithlab::NdfParams&) {
        return smithlab::tabulated_ndf_from_csv(ggx_table(0.5), "ggx.csv");
    });
    add_block_of("tabulated ggx(alpha=0.5), 100 rows, registered/mirror", tabulated.make("ggx_table"));
    add_registered_materials();
    add_family_matrix();
    return true;
}();

}  // namespace

BENCHMARK_MAIN();
