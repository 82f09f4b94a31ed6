#include "report/timing.hpp"

#include <benchmark/benchmark.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "smithlab/csv.hpp"

namespace smithlab::report {

// Google Benchmark, one core, each item cycling through its sample; the JSON it writes is what we read.
void time_all(const std::vector<Timed>& items, double min_time, const std::filesystem::path& json_file) {
    for (const Timed& t : items) {
        if (t.n == 0) continue;  // applies to no NDF of the scene: nothing to time
        benchmark::RegisterBenchmark(t.name.c_str(), [t](benchmark::State& s) {
            std::size_t k = 0;
            for (auto _ : s) benchmark::DoNotOptimize(t.eval(k++ % t.n));
        });
    }
    std::string flag = "--benchmark_min_time=" + format_g17(min_time);
    char arg0[] = "smithlab-report";
    char* argv[] = {arg0, flag.data(), nullptr};
    int argc = 2;
    benchmark::Initialize(&argc, argv);
    std::ofstream out(json_file);
    benchmark::JSONReporter reporter;
    reporter.SetOutputStream(&out);
    reporter.SetErrorStream(&std::cerr);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();
    out.close();
    std::ifstream in(json_file);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& b : j.at("benchmarks")) {
        const std::string name = b.at("name");
        const double scale = b.at("time_unit") == "ns" ? 1.0 : b.at("time_unit") == "us" ? 1e3 : 1e6;
        for (const Timed& t : items)
            if (t.name == name) *t.ns = b.at("cpu_time").get<double>() * scale;
    }
}

}  // namespace smithlab::report
