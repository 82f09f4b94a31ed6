#include "report/timing.hpp"

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "output/checked_file.hpp"
#include "output/progress.hpp"
#include "output/write_error.hpp"
#include "smithlab/csv.hpp"

namespace smithlab::report {

namespace {

// The JSON reporter, and a progress line on stderr as the runs come in.
class ProgressReporter : public benchmark::JSONReporter {
public:
    explicit ProgressReporter(std::size_t items) : items_(items) {}
    void ReportRuns(const std::vector<Run>& runs) override {
        benchmark::JSONReporter::ReportRuns(runs);
        done_ += runs.size();
        progress_(static_cast<double>(done_) / static_cast<double>(items_), [&] {
            return "report: timing " + std::to_string(done_) + "/" + std::to_string(items_) +
                " variants and estimators";
        });
    }

private:
    std::size_t items_, done_ = 0;
    output::ProgressLine progress_;
};

// Google Benchmark over what is registered, with min_time seconds each, its JSON written to json_file.
void run_registered(std::size_t items, double min_time, const std::filesystem::path& json_file) {
    std::string flag = "--benchmark_min_time=" + format_g17(min_time);
    char arg0[] = "smithlab-report";
    char* argv[] = {arg0, flag.data(), nullptr};
    int argc = 2;
    benchmark::Initialize(&argc, argv);
    output::CheckedFile out(json_file.string(), output::published_name(json_file.string()));
    out.stream().exceptions(std::ios::goodbit);  // a failed write is kept for close(): none thrown through the library
    ProgressReporter reporter(items);
    reporter.SetOutputStream(&out.stream());
    reporter.SetErrorStream(&std::cerr);
    benchmark::RunSpecifiedBenchmarks(&reporter);
    benchmark::ClearRegisteredBenchmarks();
    out.close();  // a failed write is reported here, naming the file, before anything reads it back
}

}  // namespace

void Timing::run(double min_time, const std::filesystem::path& json_file) const {
    for (const Item& t : items_) benchmark::RegisterBenchmark(t.name.c_str(), t.body);
    run_registered(items_.size(), min_time, json_file);
    std::ifstream in(json_file);
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& b : j.at("benchmarks")) {
        const std::string name = b.at("name");
        const double scale = b.at("time_unit") == "ns" ? 1.0 : b.at("time_unit") == "us" ? 1e3 : 1e6;
        for (const Item& t : items_)
            if (t.name == name) *t.ns = b.at("cpu_time").get<double>() * scale / static_cast<double>(t.per_run);
    }
}

}  // namespace smithlab::report
