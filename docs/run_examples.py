#!/usr/bin/env python3
"""Run the shell blocks of README.md and docs/*.md that are marked as checked (ctest docs_examples).

    docs/run_examples.py BUILD_DIR WORK_DIR

A block is checked when the line before its opening ```sh fence is

    <!-- checked by docs/run_examples.py -->

Each such block runs as one bash script (bash -e: the first failing line fails the block) in WORK_DIR, made afresh,
where `build` links to BUILD_DIR and `experiments` and `tests` to the repository's, so that the commands run as
written from a checkout's root and what they write stays in WORK_DIR. A line whose comment starts with `exit N`
(`$S eval --ndf 'ggx(alpha=-1)' --mu 1   # exit 2: ...`) must end with exit code N. `python3` in a block is the
interpreter running this script (the one the build found, with NumPy and the module's ABI); a block that imports the
module from `build/python` is skipped where the build has none (the sanitized build).
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parent.parent
MARK = "<!-- checked by docs/run_examples.py -->"
EXPECTED_EXIT = re.compile(r"^(.*?)\s+#\s*exit (\d+)\b")


def with_exit_checks(script):
    """Each line that says `# exit N` runs so that any other exit code fails the block."""
    out = []
    for line in script.split("\n"):
        m = EXPECTED_EXIT.match(line)
        if m:
            command, code = m.groups()
            line = (f"if {command}; then rc=0; else rc=$?; fi; "
                    f"[ $rc = {code} ] || {{ echo \"expected exit {code}, got $rc\" >&2; false; }}")
        out.append(line)
    return "\n".join(out)


def blocks(path):
    lines = path.read_text().split("\n")
    for i, line in enumerate(lines):
        if line == MARK and i + 1 < len(lines) and lines[i + 1] == "```sh":
            end = next(j for j in range(i + 2, len(lines)) if lines[j] == "```")
            yield i + 2, "\n".join(lines[i + 2:end])


def main(argv):
    if len(argv) != 2:
        raise SystemExit(__doc__)
    build_dir, work = pathlib.Path(argv[0]).resolve(), pathlib.Path(argv[1])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    (work / "build").symlink_to(build_dir)
    for name in ("experiments", "tests"):
        (work / name).symlink_to(ROOT / name)
    env = dict(os.environ, PATH=str(pathlib.Path(sys.executable).parent) + os.pathsep + os.environ.get("PATH", ""))
    count, failed = 0, []
    for path in [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md")):
        for line, script in blocks(path):
            where = f"{path.relative_to(ROOT)}:{line}"
            if "build/python" in script and not (build_dir / "python" / "smithlab").is_dir():
                print(f"== {where}: skipped, the build has no Python module")
                continue
            count += 1
            print(f"== {where}", end="", flush=True)
            start = time.monotonic()
            run = subprocess.run(["bash", "-e", "-x", "-c", with_exit_checks(script)], cwd=work, env=env,
                                 capture_output=True, text=True)
            print(f" ({time.monotonic() - start:.1f} s)", flush=True)
            if run.returncode != 0:
                failed.append(where)
                print(run.stdout[-4000:] + run.stderr[-4000:])
                print(f"FAILED: the block at {where} exited {run.returncode}")
    if count == 0:
        print("no checked block found")
        return 1
    print(f"{count - len(failed)} of {count} checked blocks ran")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
