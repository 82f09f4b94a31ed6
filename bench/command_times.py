#!/usr/bin/env python3
"""Time the main job's commands on the default scenes and rewrite the timing block of docs/performance.md.

    bench/command_times.py BUILD_DIR [--threads N] [--with-build]

With --with-build, first the README's build (configure, then `cmake --build -j2`, Release) of this source tree from
nothing, into a scratch build directory, whose time heads the table. Then, in a scratch directory, one after another: `smithlab check --all`, `smithlab report`, `smithlab trace`,
`smithlab fit` (cold: nothing cached), `smithlab tables`, and `smithlab fit` again (warm: every traced point read from
fit/cache/).
Wall time of each, with the machine (CPU model, cores, load average before the run) and the date, between

    <!-- command times: bench/command_times.py -->
    <!-- end command times -->

in docs/performance.md, and the main job's total (the build, when timed, and the commands the README's first
command runs: the first fit, not the second). About 5 minutes on 2 cores (17 with the build); a machine busy with other work gives longer times, and the
block says what the load was.
"""
import datetime
import os
import pathlib
import platform
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "performance.md"
START, END = "<!-- command times: bench/command_times.py -->", "<!-- end command times -->"
# (what it runs, its arguments, whether the README's main job runs it)
RUNS = [("the per-distribution checks of every registered NDF", ["check", "--all"], True),
        ("the default report scene", ["report"], True),
        ("the default trace sweep", ["trace"], True),
        ("the default fit, nothing cached", ["fit"], True),
        ("the default compensation tables, without a fit", ["tables"], True),
        ("the same fit again, its traced points read from fit/cache/", ["fit"], False)]


def cpu_model():
    for line in pathlib.Path("/proc/cpuinfo").read_text().splitlines():
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return platform.processor() or "unknown CPU"


def main(argv):
    threads = None
    with_build = "--with-build" in argv
    argv = [a for a in argv if a != "--with-build"]
    if "--threads" in argv:
        i = argv.index("--threads")
        threads = argv[i + 1]
        argv = argv[:i] + argv[i + 2:]
    if len(argv) != 1:
        raise SystemExit(__doc__)
    exe = pathlib.Path(argv[0]).resolve() / "experiments" / "smithlab"
    load = os.getloadavg()[0]
    rows = []
    work = pathlib.Path(tempfile.mkdtemp(prefix="smithlab-times-"))
    try:
        if with_build:
            build = work / "build"
            t0 = time.monotonic()
            for cmd in (["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release"],
                        ["cmake", "--build", str(build), "-j2"]):
                run = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
                if run.returncode != 0:
                    raise SystemExit(f"{' '.join(cmd)} exited {run.returncode}:\n{run.stderr[-2000:]}")
            seconds = time.monotonic() - t0
            print(f"the build: {seconds:.1f} s", flush=True)
            rows.append(("the README's build from nothing, `-j2`", "cmake -S . -B build && cmake --build build -j2",
                         seconds, True))
        for label, args, in_job in RUNS:
            threaded = args[0] in ("trace", "fit", "tables")
            cmd = [str(exe)] + args + (["--threads", threads] if threads and threaded else [])
            t0 = time.monotonic()
            run = subprocess.run(cmd, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            seconds = time.monotonic() - t0
            if run.returncode != 0:
                raise SystemExit(f"{' '.join(cmd)} exited {run.returncode}:\n{run.stderr[-2000:]}")
            print(f"{label}: {seconds:.1f} s", flush=True)
            rows.append((label, "smithlab " + " ".join(args), seconds, in_job))
    finally:
        shutil.rmtree(work, ignore_errors=True)

    block = [START,
             f"Measured {datetime.date.today().isoformat()} on {cpu_model()}, {os.cpu_count()} cores, "
             f"load average {load:.1f} when the runs began (Release build; wall time, one run each).",
             "",
             "| command | what it runs | wall time |",
             "|---|---|---:|"]
    block += [f"| `{cmd}` | {label} | {seconds:.0f} s |" for label, cmd, seconds, _ in rows]
    total = sum(seconds for _, _, seconds, in_job in rows if in_job)  # the warm fit is not part of it
    commands = sum(1 for _, args, in_job in RUNS if in_job)
    what = f"the build and the {commands} commands" if with_build else f"the {commands} commands, the build not included"
    block.append(f"| the main job | {what}, as the README's first command runs them | {total / 60:.1f} min |")
    block.append(END)

    text = DOC.read_text()
    if START not in text or END not in text:
        raise SystemExit(f"{DOC}: no '{START}' ... '{END}' block")
    head, rest = text.split(START, 1)
    tail = rest.split(END, 1)[1]
    DOC.write_text(head + "\n".join(block) + tail)
    print(f"rewrote the block in {DOC.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
