// The Python module's cost per call and per point: G1 through `import smithlab` (an interpreter embedded here, the
// package from the build tree) for 1 and 1e6 points, beside the same computation as a C++ loop over the module's own
// route (evaluation::lambda_g1, what Ndf.G1 runs per element) and, for the GTR family, the stream. items_per_second
// counts points: at 1e6 points the Python row approaches the C++ loop's rate, at 1 point it is the call's overhead.
#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <pybind11/embed.h>
#include <pybind11/numpy.h>

#include "evaluation/route.hpp"
#include "smithlab/gtr/family_stream.hpp"
#include "smithlab/gtr/registry.hpp"

namespace {

namespace py = pybind11;

// mu spread over [0.05, 20] (log), the same points for every row.
std::vector<double> mus(std::size_t n) {
    std::vector<double> mu(n);
    for (std::size_t i = 0; i < n; ++i) mu[i] = 0.05 * std::pow(400.0, static_cast<double>(i % 4096) / 4095.0);
    return mu;
}

void python_G1(benchmark::State& state, const std::string& spec, const std::string& method) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const py::module_ smithlab = py::module_::import("smithlab");
    const py::object G1 = smithlab.attr("ndf")(spec).attr("G1");
    const std::vector<double> mu = mus(n);
    const py::object points = n == 1 ? py::object(py::float_(mu[0])) : py::object(py::array_t<double>(n, mu.data()));
    const py::str m(method);
    for (auto _ : state) benchmark::DoNotOptimize(G1(points, m).ptr());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void cpp_G1(benchmark::State& state, const std::string& spec, const std::string& method) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const smithlab::NdfRegistry registry = smithlab::builtin_registry();
    namespace evaluation = smithlab::evaluation;
    const evaluation::Prepared p =
        evaluation::prepare(registry.make(spec), evaluation::route({.method = method}, smithlab::builtin_variants()));
    const std::vector<double> mu = mus(n);
    std::vector<double> out(n);
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i) out[i] = evaluation::lambda_g1(p, mu[i], smithlab::Downward::smith).g1;
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void python_family(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const py::object family_G1 = py::module_::import("smithlab").attr("family_G1");
    const std::vector<double> mu = mus(n);
    const py::object points = n == 1 ? py::object(py::float_(mu[0])) : py::object(py::array_t<double>(n, mu.data()));
    for (auto _ : state) benchmark::DoNotOptimize(family_G1(0.3, 1.5, points).ptr());
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

void cpp_family(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const std::vector<double> mu = mus(n), alpha(n, 0.3), gamma(n, 1.5);
    std::vector<double> out(n);
    for (auto _ : state) {
        smithlab::G1_gtr_family(alpha, gamma, mu, out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}

}  // namespace

int main(int argc, char** argv) {
    py::scoped_interpreter python;
    py::module_::import("sys").attr("path").attr("insert")(0, SMITHLAB_PYTHON_DIR);
    for (const auto& [spec, method] : {std::pair<std::string, std::string>{"ggx(alpha=0.3)", "auto"},
                                       {"gtr(alpha=0.3, gamma=1.5)", "family"},
                                       {"gtr(alpha=0.3, gamma=1.5)", "auto"}}) {
        const std::string row = "G1/" + spec + "/" + method;
        for (const std::int64_t n : {std::int64_t{1}, std::int64_t{1'000'000}}) {
            benchmark::RegisterBenchmark(("python/" + row).c_str(), python_G1, spec, method)->Arg(n);
            benchmark::RegisterBenchmark(("c++/" + row).c_str(), cpp_G1, spec, method)->Arg(n);
        }
    }
    for (const std::int64_t n : {std::int64_t{1}, std::int64_t{1'000'000}}) {
        benchmark::RegisterBenchmark("python/family_G1/stream", python_family)->Arg(n);
        benchmark::RegisterBenchmark("c++/family_G1/stream", cpp_family)->Arg(n);
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
}
