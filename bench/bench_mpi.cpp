// Strong scaling of `mpirun -np N smithlab trace` on a deliberately skewed scene, bench/mpi_skewed_scene.toml
// (GGX mirror cells at alpha = 0.01 beside D-only Blinn-Phong lambert cells, an order of magnitude apart in cost; the
// costliest last), and what rank 0 communicates.
//
// scaling/np1_vs_np2: each iteration runs the scene at np = 1 and then at np = 2 (--threads 1 per rank, on this
// 2-core machine), so the ratio comes from one run on one machine; its time is np = 2's wall time. Counters:
//   speedup (np1 / np2 wall time, mpirun's start and MPI_Init included: ~0.3 s each), efficiency (speedup / 2), np1_s,
//   np2_s, speedup_in_run (the ratio of the runs' own seconds, meta.json: the division of work alone),
//   bytes_per_cell, messages_per_cell (rank 0's, both ways, from meta.json), rank0_serving_us (rank 0's main thread,
//   per message: reading, merging, writing finished cells, answering), rank0_share (the blocks rank 0's own thread
//   traced, of all).
// cell_cost/cheapest and cell_cost/costliest: one cell of each kind alone (one process, one thread), ns per walk
// (the process's start subtracted).
// The wall times include the launcher's start (mpirun: ~0.1 s). Quote medians:
//   build/bench/bench_mpi --benchmark_repetitions=5 --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

const fs::path work = fs::temp_directory_path() / ("smithlab-bench-mpi-" + std::to_string(::getpid()));

std::string launcher() {
    std::string l = std::string(SMITHLAB_MPIEXEC) + " --oversubscribe";  // Open MPI's flags (Debian's MPI)
    if (::geteuid() == 0) l += " --allow-run-as-root";
    return l;
}

// Runs the command (its output to a log beside the outputs) and returns its wall time in seconds.
double timed(const std::string& command) {
    const auto t0 = std::chrono::steady_clock::now();
    if (std::system((command + " > " + (work / "log").string() + " 2>&1").c_str()) != 0)
        throw std::runtime_error("bench_mpi: failed: " + command + " (see " + (work / "log").string() + ")");
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double trace_scene(int np, const fs::path& out) {
    fs::remove_all(out);
    return timed(launcher() + " -np " + std::to_string(np) + " " + SMITHLAB_EXE + " trace " + SMITHLAB_SKEWED_SCENE +
                 " --threads 1 --output " + out.string());
}

void scaling(benchmark::State& state) {
    double np1 = 0.0, np2 = 0.0, traced1 = 0.0, traced2 = 0.0, bytes = 0.0, messages = 0.0, serving = 0.0, rank0 = 0.0,
           cells = 0.0;
    auto seconds_of = [](const fs::path& dir) {
        std::ifstream in(dir / "meta.json");
        return nlohmann::json::parse(in).at("seconds").get<double>();
    };
    for (auto _ : state) {
        const double t1 = trace_scene(1, work / "np1"), t2 = trace_scene(2, work / "np2");
        state.SetIterationTime(t2);
        np1 += t1;
        np2 += t2;
        traced1 += seconds_of(work / "np1");
        traced2 += seconds_of(work / "np2");
        std::ifstream in(work / "np2" / "meta.json");
        const nlohmann::json meta = nlohmann::json::parse(in);
        const nlohmann::json& mpi = meta.at("mpi");
        cells = static_cast<double>(meta.at("cells").size());
        bytes += mpi.at("bytes").get<double>();
        messages += mpi.at("messages").get<double>();
        serving += mpi.at("rank0_serving_seconds").get<double>() / mpi.at("messages").get<double>() * 2.0;
        rank0 += mpi.at("blocks_rank0").get<double>() /
            (mpi.at("blocks_rank0").get<double>() + mpi.at("blocks_other_ranks").get<double>());
    }
    const auto n = static_cast<double>(state.iterations());
    state.counters["speedup"] = np1 / np2;
    state.counters["efficiency"] = np1 / np2 / 2.0;
    state.counters["np1_s"] = np1 / n;
    state.counters["np2_s"] = np2 / n;
    state.counters["speedup_in_run"] = traced1 / traced2;
    state.counters["bytes_per_cell"] = bytes / n / cells;
    state.counters["messages_per_cell"] = messages / n / cells;
    state.counters["rank0_serving_us"] = serving / n * 1e6;
    state.counters["rank0_share"] = rank0 / n;
}

// ns per walk of one cell alone: the wall time of n walks less that of 1 walk (the process's start), over n - 1.
void cell_cost(benchmark::State& state, const std::string& ndf, const std::string& material, long walks) {
    auto run = [&](long n) {
        fs::remove_all(work / "cell");
        return timed(std::string(SMITHLAB_EXE) + " trace --ndf '" + ndf + "' --material '" + material +
                     "' --theta-i 0 --walks " + std::to_string(n) + " --threads 1 --output " +
                     (work / "cell").string());
    };
    double ns = 0.0;
    for (auto _ : state) {
        const double t = run(walks), t0 = run(1);
        state.SetIterationTime(t);
        ns += (t - t0) / static_cast<double>(walks - 1) * 1e9;
    }
    state.counters["ns_per_walk"] = ns / static_cast<double>(state.iterations());
}

}  // namespace

BENCHMARK(scaling)->Name("scaling/np1_vs_np2")->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(cell_cost, cheapest, "ggx(alpha=0.01)", "mirror", 10'000'000)
    ->Name("cell_cost/cheapest")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK_CAPTURE(cell_cost, costliest, "blinn(n=0.5)", "lambert(albedo=1)", 1'000'000)
    ->Name("cell_cost/costliest")
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

int main(int argc, char** argv) {
    fs::create_directories(work);
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    fs::remove_all(work);
}
