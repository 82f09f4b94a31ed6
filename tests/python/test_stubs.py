"""The type stubs (_ndf.pyi, _walk.pyi) name every public function and method of the extensions, with the same
parameters in the same order: what an editor completes and checks is what the module takes."""
import ast
import pathlib
import re

import pytest

import smithlab
from smithlab import _ndf, _walk


def stub_signatures(module):
    tree = ast.parse(pathlib.Path(module.__file__).with_name(module.__name__.split(".")[-1] + ".pyi").read_text())
    out = {}

    def params(f):
        a = f.args
        return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg != "self"]

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = params(node)
        elif isinstance(node, ast.ClassDef):
            for f in node.body:
                if isinstance(f, ast.FunctionDef) and not any(
                        isinstance(d, ast.Name) and d.id == "property" for d in f.decorator_list):
                    out[f"{node.name}.{f.name}"] = params(f)
    return out


def module_signatures(module):
    """From pybind11's docstrings, whose first line is NAME(ARG: TYPE, ...) -> TYPE."""
    out = {}

    def params(doc, name):
        m = re.match(rf"{re.escape(name)}\((.*)\) ->", doc.splitlines()[0] if doc else "")
        assert m, f"{name}: no signature line in its docstring"
        names = re.findall(r"(?:^|, )\*?(\w+):", m.group(1))
        return [n for n in names if n != "self"]

    for name in dir(module):
        if name.startswith("_"):
            continue
        obj = getattr(module, name)
        if isinstance(obj, type):
            for attr, f in vars(obj).items():
                if not attr.startswith("_") and callable(f):
                    out[f"{name}.{attr}"] = params(f.__doc__, attr)
        elif callable(obj):
            out[name] = params(obj.__doc__, name)
    return out


@pytest.mark.parametrize("module", [_ndf, _walk])
def test_stub_matches_module(module):
    stub, real = stub_signatures(module), module_signatures(module)
    assert sorted(stub) == sorted(real)
    for name, params in real.items():
        assert stub[name] == params, name


def test_package_exports_everything():
    for module in (_ndf, _walk):
        for name in dir(module):
            if not name.startswith("_"):
                assert name in smithlab.__all__ and getattr(smithlab, name) is getattr(module, name)
