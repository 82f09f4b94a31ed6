#!/usr/bin/env python3
"""Rewrite the generated and quoted blocks of README.md and docs/*.md; with --check, only say whether any differs.

    docs/update_docs.py BUILD_DIR            rewrite the blocks in place
    docs/update_docs.py --check BUILD_DIR    exit 1, with a diff, when a block differs from its source (ctest
                                             docs_up_to_date)

Two kinds of block, each between a start and an end marker on lines of their own:

    <!-- generated: smithlab ARGS -->        the output of BUILD_DIR/experiments/smithlab ARGS, in a text fence
    <!-- end generated -->

    <!-- quoted: PATH NAME -->               the lines of PATH (relative to the repository root) between the
    <!-- end quoted -->                      comment lines "[docs: NAME]" and "[end docs]", dedented, in a fence
                                             named after PATH's extension; without NAME, the whole file

Everything outside the markers is left as it is. CITATION.cff's `version:` is kept equal to the version in
CMakeLists.txt's project().
"""
import difflib
import pathlib
import re
import shlex
import subprocess
import sys
import textwrap

ROOT = pathlib.Path(__file__).resolve().parent.parent
START = re.compile(r"^<!-- (generated|quoted): (.+?) -->$")
END = {"generated": "<!-- end generated -->", "quoted": "<!-- end quoted -->"}
FENCES = {".cpp": "cpp", ".hpp": "cpp", ".toml": "toml", ".csv": "csv", ".py": "python", ".cmake": "cmake",
          ".txt": "cmake", ".sh": "sh"}


def fenced(language, text):
    return ["```" + language] + text.rstrip("\n").split("\n") + ["```"]


def generated(args, build_dir):
    words = shlex.split(args)
    if not words or words[0] != "smithlab":
        raise SystemExit(f"generated block: '{args}' does not start with 'smithlab'")
    exe = pathlib.Path(build_dir) / "experiments" / "smithlab"
    run = subprocess.run([str(exe)] + words[1:], capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"'{args}' exited {run.returncode}:\n{run.stderr}")
    return fenced("text", run.stdout.replace(str(exe), "smithlab"))


def quoted(args):
    words = args.split()
    path = ROOT / words[0]
    lines = path.read_text().split("\n")
    if len(words) == 1:
        return fenced(FENCES.get(path.suffix, ""), "\n".join(lines))
    name = words[1]
    starts = [i for i, line in enumerate(lines) if line.strip().endswith(f"[docs: {name}]")]
    if len(starts) != 1:
        raise SystemExit(f"{words[0]}: {len(starts)} lines end with '[docs: {name}]', expected 1")
    ends = [i for i in range(starts[0] + 1, len(lines)) if lines[i].strip().endswith("[end docs]")]
    if not ends:
        raise SystemExit(f"{words[0]}: no '[end docs]' after '[docs: {name}]'")
    return fenced(FENCES.get(path.suffix, ""), textwrap.dedent("\n".join(lines[starts[0] + 1:ends[0]])))


def rewrite(path, build_dir):
    lines = path.read_text().split("\n")
    out, i = [], 0
    while i < len(lines):
        out.append(lines[i])
        m = START.match(lines[i])
        i += 1
        if not m:
            continue
        kind, args = m.groups()
        end = next((j for j in range(i, len(lines)) if lines[j] == END[kind]), None)
        if end is None:
            raise SystemExit(f"{path.relative_to(ROOT)}:{i}: no '{END[kind]}' after this block's start")
        out += generated(args, build_dir) if kind == "generated" else quoted(args)
        i = end
    return "\n".join(out)


def citation(old):
    project = re.search(r"project\(smithlab VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not project:
        raise SystemExit("CMakeLists.txt: no 'project(smithlab VERSION X.Y.Z' found")
    return re.sub(r"(?m)^version: .*$", "version: " + project.group(1), old)


def main(argv):
    check = "--check" in argv
    rest = [a for a in argv if a != "--check"]
    if len(rest) != 1:
        raise SystemExit(__doc__)
    build_dir = rest[0]
    stale = []
    for path in [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md")) + [ROOT / "CITATION.cff"]:
        old = path.read_text()
        new = citation(old) if path.suffix == ".cff" else rewrite(path, build_dir)
        if new == old:
            continue
        stale.append(path)
        if check:
            name = str(path.relative_to(ROOT))
            sys.stdout.writelines(difflib.unified_diff(old.splitlines(True), new.splitlines(True), name, name + " (generated)"))
        else:
            path.write_text(new)
    if check and stale:
        print("\nout of date: " + ", ".join(str(p.relative_to(ROOT)) for p in stale) +
              f"\nrun: python3 docs/update_docs.py {build_dir}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
