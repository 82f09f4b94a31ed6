#!/usr/bin/env python3
"""Every source file's namespaces match its folder, in lib/, gtr/ and experiments/; the umbrellas hold the public headers.

    namespaces.py [--root DIR]     the check (exit 1 naming each file whose namespace is not its folder's)
    namespaces.py --self-test      the rule on small inline samples

A file's folder names its namespace: lib/include/smithlab/ROOM/... and lib/src/ROOM/... are in smithlab::ROOM, the
files directly in lib/include/smithlab/ and lib/src/ in smithlab; experiments/ROOM/... is in smithlab::ROOM (a room's
sub-folders, such as fit/diffuse/ or report/sections/, are parts of the room and share its namespace), and
experiments/include/smithlab/ is in smithlab. gtr/ extends smithlab itself: its folder is named after the NDF it
holds, whose maker is the function smithlab::gtr. A namespace opened inside the folder's (detail, an anonymous one,
any other) is the folder's business; a file that opens none (a main, a user's program: experiments/plugin_example/)
is not checked. What a file may open besides its folder's namespace: an enclosing one holding forward declarations
only (`namespace smithlab { class MaterialKernels; }`).

A header in a detail/ folder is a helper (in the detail namespace, by the rule above), no part of the API: the umbrella
<smithlab/smithlab.hpp> includes every other header of lib/include/smithlab/ and none of detail/, and
<smithlab/gtr.hpp> includes the umbrella and every header of gtr/include/smithlab/gtr/.

The scanner is function_lengths.py's (comments, literals and preprocessor lines taken out).
"""

import argparse
import os
import sys

from function_lengths import ScanError, source_files, tokenize

UNCHECKED = ("experiments/plugin_example/",)  # a user's program: its own names


def expected_namespace(name):
    """The namespace the file at `name` (relative to the root, with '/') belongs in, or None where none is asked."""
    if name.startswith(UNCHECKED):
        return None
    parts = name.split("/")
    for prefix in (["lib", "include", "smithlab"], ["lib", "src"], ["experiments", "include", "smithlab"],
                   ["gtr", "include", "smithlab"], ["gtr", "src"], ["gtr", "tools"]):
        if parts[:len(prefix)] == prefix:
            rest = parts[len(prefix):]
            if prefix[0] == "gtr" or len(rest) == 1:
                return "smithlab"
            return "smithlab::" + rest[0]
    if parts[0] == "experiments" and len(parts) > 2:
        return "smithlab::" + parts[1]
    return None


def opened_namespaces(src):
    """The outermost named namespaces `src` opens: (name, line, forward_declarations_only) each."""
    tokens = tokenize(src)
    out, depth, i = [], 0, 0
    while i < len(tokens):
        t = tokens[i]
        if t.text == "namespace" and t.kind == "id":
            j, name = i + 1, ""
            while j < len(tokens) and (tokens[j].kind == "id" or tokens[j].text == "::"):
                name += tokens[j].text
                j += 1
            if j < len(tokens) and tokens[j].text == "{":
                if depth == 0 and name:
                    close = matching_brace(tokens, j)
                    out.append((name, t.line, only_forward_declarations(tokens[j + 1:close])))
                    i = close + 1
                    continue
                depth += 1
                i = j + 1
                continue
            i = j  # an alias (namespace fs = ...;) or a using-directive
            continue
        if t.text == "{":
            depth += 1
        elif t.text == "}":
            depth -= 1
        i += 1
    return out


def matching_brace(tokens, j):
    depth = 0
    for k in range(j, len(tokens)):
        if tokens[k].text == "{":
            depth += 1
        elif tokens[k].text == "}":
            depth -= 1
            if depth == 0:
                return k
    raise ScanError(f"line {tokens[j].line}: unbalanced braces")


def only_forward_declarations(body):
    """Whether the tokens are `class X;` / `struct X;` declarations and nothing else."""
    texts = [t.text for t in body]
    groups = [texts[k:k + 3] for k in range(0, len(texts), 3)]
    return all(len(g) == 3 and g[0] in ("class", "struct") and g[2] == ";" for g in groups)


def problems(files):
    """Each file whose outermost namespaces are not its folder's: 'FILE:LINE: ...' lines."""
    out = []
    for name, src in files:
        want = expected_namespace(name)
        if want is None:
            continue
        for ns, line, forward_only in opened_namespaces(src):
            if ns == want or ns.startswith(want + "::"):
                continue
            if forward_only and want.startswith(ns + "::"):
                continue
            out.append(f"{name}:{line}: namespace {ns}, but the folder's is {want}")
    return out


UMBRELLAS = (("lib/include", "smithlab/smithlab.hpp", "smithlab", ()),
             ("gtr/include", "smithlab/gtr.hpp", "smithlab/gtr", ("smithlab/smithlab.hpp",)))


def umbrella_problems(root):
    """Where an umbrella misses a public header of its layer, or includes a helper: 'FILE: ...' lines."""
    out = []
    for include_root, umbrella, folder, extra in UMBRELLAS:
        base = os.path.join(root, include_root)
        public = set(extra)
        for dirpath, dirnames, filenames in os.walk(os.path.join(base, folder)):
            dirnames[:] = [d for d in dirnames if d != "detail"]
            public |= {os.path.relpath(os.path.join(dirpath, f), base).replace(os.sep, "/")
                       for f in filenames if f.endswith(".hpp")}
        public.discard(umbrella)
        with open(os.path.join(base, umbrella), encoding="utf-8") as fh:
            included = {line.split('"')[1] for line in fh if line.startswith('#include "')}
        name = f"{include_root}/{umbrella}"
        out += [f"{name}: does not include the public header {h}" for h in sorted(public - included)]
        out += [f"{name}: includes {h}, which is no public header of its layer" for h in sorted(included - public)]
    return out


def self_test():
    failures = []

    def expect(what, got, want):
        if got != want:
            failures.append(f"{what}: got {got!r}, want {want!r}")

    expect("lib header", expected_namespace("lib/include/smithlab/ndf.hpp"), "smithlab")
    expect("lib room", expected_namespace("lib/include/smithlab/walk/trace.hpp"), "smithlab::walk")
    expect("lib sub-folder", expected_namespace("lib/include/smithlab/fit/diffuse/eon.hpp"), "smithlab::fit")
    expect("lib source", expected_namespace("lib/src/compensation/furnace.cpp"), "smithlab::compensation")
    expect("experiments room", expected_namespace("experiments/scene/strict_table.hpp"), "smithlab::scene")
    expect("experiments public", expected_namespace("experiments/include/smithlab/cli.hpp"), "smithlab")
    expect("gtr", expected_namespace("gtr/include/smithlab/gtr/family.hpp"), "smithlab")
    expect("plug-in", expected_namespace("experiments/plugin_example/main.cpp"), None)

    good = ("namespace smithlab { class K; struct L; }\nnamespace smithlab::walk {\nnamespace detail { int x; }\n"
            "namespace { int y; }\nnamespace fs = std::filesystem;\nvoid f() {}\n}  // namespace smithlab::walk\n")
    expect("a good file", problems([("lib/include/smithlab/walk/a.hpp", good)]), [])
    bad = "namespace smithlab::report {\nint x;\n}\nnamespace smithlab {\nint y;\n}\n"
    expect("a bad file", problems([("experiments/scene/a.hpp", bad)]), [
        "experiments/scene/a.hpp:1: namespace smithlab::report, but the folder's is smithlab::scene",
        "experiments/scene/a.hpp:4: namespace smithlab, but the folder's is smithlab::scene",
    ])
    expect("nested alike", problems([("experiments/fit/a.cpp", "namespace smithlab {\nnamespace fitrun {\n}\n}\n")]),
           ["experiments/fit/a.cpp:1: namespace smithlab, but the folder's is smithlab::fit"])
    expect("no namespace", problems([("experiments/cli/main.cpp", "int main() { return 0; }\n")]), [])

    for f in failures:
        print("self-test:", f, file=sys.stderr)
    print(f"self-test: {'FAILED' if failures else 'passed'}")
    return 1 if failures else 0


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--root", default=os.path.dirname(here), help="the source tree (default: this file's ../)")
    p.add_argument("--self-test", action="store_true", help="check the rule on inline samples")
    a = p.parse_args()
    if a.self_test:
        return self_test()
    try:
        files = []
        for name, path in source_files(a.root, ("lib", "gtr", "experiments")):
            with open(path, encoding="utf-8") as fh:
                files.append((name, fh.read()))
        if not files:
            raise ScanError(f"no sources under {a.root}")
        found = problems(files) + umbrella_problems(a.root)
    except (ScanError, OSError) as e:
        print(f"namespaces: {e}", file=sys.stderr)
        return 2
    for line in found:
        print(line, file=sys.stderr)
    print(f"namespaces: {len(files)} files; {len(found)} problems")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
