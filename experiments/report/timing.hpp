// Timing for the report: Google Benchmark, run in-process on one core, read back from the JSON it writes. Each item
// is timed in a loop compiled for it (timing_points.hpp: the loops bench/bench_lambda.cpp runs too); its ns/eval is
// the benchmark's CPU time per call, or per point of a stream.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "report/timing_points.hpp"

namespace smithlab::report {

class Timing {
public:
    // eval(p) for p cycling through points; *ns gets the time per call. No points: not timed (*ns left as it is).
    template <class Point, class Eval>
    void add(std::string name, std::vector<Point> points, Eval eval, double* ns) {
        if (points.empty()) return;
        items_.push_back({std::move(name), 1, ns, [points = std::move(points), eval](benchmark::State& s) {
                              time_cycling(s, std::span<const Point>(points), eval);
                          }});
    }
    // stream(out) evaluates n points into out; *ns gets the time per point.
    template <class Stream>
    void add_stream(std::string name, std::size_t n, Stream stream, double* ns) {
        if (n == 0) return;
        items_.push_back({std::move(name), n, ns, [n, stream](benchmark::State& s) { time_stream(s, n, stream); }});
    }
    std::size_t size() const { return items_.size(); }

    // Runs every item with at least min_time seconds of measurement (a progress line on stderr past a few seconds),
    // writes json_file, and sets each item's ns from it.
    void run(double min_time, const std::filesystem::path& json_file) const;

private:
    struct Item {
        std::string name;
        std::size_t per_run;  // evaluations an iteration
        double* ns;
        std::function<void(benchmark::State&)>
            body;  // registered with Google Benchmark: called once per run, not per evaluation
    };
    std::vector<Item> items_;
};

}  // namespace smithlab::report
