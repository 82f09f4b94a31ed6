#!/usr/bin/env python3
"""The report's ns/eval beside bench_lambda's, variant by variant, on the same points, run alternately on the same machine.

bench_lambda times each variant on the first of gtr(alpha=0.3, gamma=1.5), ggx(alpha=0.3), beckmann(alpha=0.3) it
applies to, at mu = 0.01, 0.1, 1, 10, 100 (the variant/ rows; the GTR family evaluator also as a stream). For each of
those NDFs this script runs `smithlab report` on a scene whose grid is that NDF at those mu, so that the report times
the same calls on the same points (experiments/report/timing_points.hpp), and prints both medians of a few
repetitions (bench and reports interleaved) and their ratio. A measurement, not a test: the two are expected to agree within 20%, on a quiet machine.

Run: python3 bench/compare_report_timing.py BUILD_DIR [--repetitions 3] [--min-time 0.2] [--work DIR]
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

MUS = [0.01, 0.1, 1.0, 10.0, 100.0]
NDFS = {  # bench_lambda's spec (spaces removed) -> the report scene's [[ndf]] table
    "gtr(alpha=0.3,gamma=1.5)": 'family = "gtr"\ngamma = [1.5]\n',
    "ggx(alpha=0.3)": 'family = "ggx"\n',
    "beckmann(alpha=0.3)": 'family = "beckmann"\n',
}


def bench_once(build, min_time):
    """{(variant, spec): ns per evaluation} from one run of bench_lambda's variant/ rows."""
    out = subprocess.run([os.path.join(build, "bench", "bench_lambda"), "--benchmark_filter=^variant/",
                          f"--benchmark_min_time={min_time}", "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    times = {}
    for b in json.loads(out)["benchmarks"]:
        _, variant, spec = b["run_name"].split("/", 2)
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6}[b["time_unit"]]
        # a stream's time is per stream; its counter ns_per_eval per point (timing_points.hpp: time_stream)
        times[(variant, spec)] = b["ns_per_eval"] if "ns_per_eval" in b else b["cpu_time"] * scale
    return times


def report_command(exe, scene, out):
    """`smithlab report` with the scene and output options this build takes."""
    usage = subprocess.run([exe, "report", "--help"], capture_output=True, text=True).stdout
    if "--scene" in usage:
        return [exe, "report", "--scene", scene, "--out", out]
    return [exe, "report", scene, "--output", out]


def report_once(build, specs, min_time, work, r):
    """{(variant, spec): ns per evaluation} from variants.csv, one report per NDF."""
    exe = os.path.join(build, "experiments", "smithlab")
    times = {}
    for spec in specs:
        scene = os.path.join(work, spec + ".toml")
        with open(scene, "w") as f:
            f.write(f"[grid]\nalpha = [0.3]\nmu = {MUS}\n[[ndf]]\n{NDFS[spec]}[variants]\ninclude = [\"*\"]\n"
                    f"[timing]\nmin_time = {min_time}\n")
        out = os.path.join(work, f"{spec}.{r}")
        subprocess.run(report_command(exe, scene, out), check=True, capture_output=True)
        with open(os.path.join(out, "variants.csv")) as f:
            for row in csv.DictReader(f):
                if row["ns_per_eval"]:
                    times[(row["variant"], spec)] = float(row["ns_per_eval"])
    return times


def medians(runs):
    """{key: median} of a list of {key: value}."""
    keys = set().union(*runs)
    return {k: statistics.median(r[k] for r in runs if k in r) for k in keys}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("build")
    p.add_argument("--repetitions", type=int, default=3)
    p.add_argument("--min-time", type=float, default=0.2)
    p.add_argument("--work", default=None, help="where the report scenes and outputs go (default: a temporary dir)")
    a = p.parse_args()
    work = a.work or tempfile.mkdtemp(prefix="compare_report_timing.")
    os.makedirs(work, exist_ok=True)
    # Interleaved, repetition by repetition, so that a change in the load of a shared machine meets both alike.
    bench_runs, report_runs = [], []
    for r in range(a.repetitions):
        bench_runs.append(bench_once(a.build, a.min_time))
        report_runs.append(report_once(a.build, sorted({spec for _, spec in bench_runs[0]}), a.min_time, work, r))
    bench, report = medians(bench_runs), medians(report_runs)
    print("| variant | ndf | report ns/eval | bench_lambda ns/eval | report / bench |")
    print("|---|---|---:|---:|---:|")
    outside = 0
    for (variant, spec), b in sorted(bench.items(), key=lambda kv: kv[1]):
        r = report.get((variant, spec))
        if r is None:
            print(f"| {variant} | {spec} | (not timed) | {b:.1f} | |")
            continue
        ratio = r / b
        outside += not (1 / 1.2 <= ratio <= 1.2)
        print(f"| {variant} | {spec} | {r:.1f} | {b:.1f} | {ratio:.2f} |")
    print(f"\n{len(bench)} variants, {outside} outside 20%", file=sys.stderr)


if __name__ == "__main__":
    main()
