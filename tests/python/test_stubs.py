"""The type stubs (python/prtkit/_prtkit.pyi) list every public name with the binding's own
parameters, in order, so editors complete what the module really takes."""

import ast
import os
import re

import prtkit

STUB = os.path.join(os.path.dirname(prtkit.__file__), "_prtkit.pyi")


def stub_functions():
    tree = ast.parse(open(STUB).read())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = node
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    out[f"{node.name}.{item.name}"] = item
            out[node.name] = node
    return out


def params(fn):
    a = fn.args
    names = [x.arg for x in a.posonlyargs + a.args if x.arg != "self"]
    return names + ["*"] * bool(a.kwonlyargs) + [x.arg for x in a.kwonlyargs]


def binding_params(obj):
    """Parameter names from pybind11's signature line: name(a: T, b: T = d, *, c: T) -> R."""
    line = obj.__doc__.splitlines()[0]
    inside = line[line.index("(") + 1:line.rindex(") ->")]
    depth, cur, parts = 0, "", []
    for ch in inside:
        depth += ch in "([{"
        depth -= ch in ")]}"
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
        else:
            cur += ch
    parts.append(cur)
    names = [re.split(r"[:=]", p.strip())[0].strip() for p in parts if p.strip()]
    return [n for n in names if n != "self"]


def test_every_public_name_is_in_the_stubs():
    stubs = stub_functions()
    missing = [n for n in prtkit.__all__ if n not in stubs]
    assert not missing, f"not in _prtkit.pyi: {missing}"


def test_stub_parameters_match_the_binding():
    stubs = stub_functions()
    for name in prtkit.__all__:
        obj = getattr(prtkit, name)
        if isinstance(obj, type):
            if issubclass(obj, BaseException) or name in ("Environment", "BakeFile", "HaarLight"):
                continue
            assert binding_params(obj.__init__) == params(stubs[f"{name}.__init__"]), name
            for attr, value in vars(obj).items():
                if callable(value) and not attr.startswith("_") and f"{name}.{attr}" in stubs:
                    assert binding_params(value) == params(stubs[f"{name}.{attr}"]), attr
        else:
            assert binding_params(obj) == params(stubs[name]), name


def test_the_package_is_typed():
    assert os.path.exists(os.path.join(os.path.dirname(prtkit.__file__), "py.typed"))
