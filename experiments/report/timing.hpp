// Timing for the report: Google Benchmark, run in-process on one core, read back from the JSON it writes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace smithlab::report {

// Something to time: evaluation k of n (cycled), and where its ns/eval goes.
struct Timed {
    std::string name;
    std::size_t n;
    std::function<double(std::size_t)> eval;
    double* ns;
};

// Runs every item with at least min_time seconds of measurement, writes json_file, and sets each *ns from it.
void time_all(const std::vector<Timed>& items, double min_time, const std::filesystem::path& json_file);

// At most 64 evenly spread elements of v.
template <class T>
std::vector<T> sample_of(const std::vector<T>& v) {
    std::vector<T> out;
    const std::size_t step = std::max<std::size_t>(1, v.size() / 64);
    for (std::size_t k = 0; k < v.size(); k += step) out.push_back(v[k]);
    return out;
}

}  // namespace smithlab::report
