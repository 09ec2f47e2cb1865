"""The type stubs (fresnel/__init__.pyi) name every public function, class, method and parameter
of the module as it is."""
import ast
import inspect
import pathlib
import re

import fresnel

STUB = pathlib.Path(fresnel.__file__).with_name("__init__.pyi")


def stub_signatures():
    tree = ast.parse(STUB.read_text())
    out = {}

    def params(fn):
        a = fn.args
        return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs if x.arg != "self"]

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = params(node)
        elif isinstance(node, ast.ClassDef):
            out[node.name] = None
            for item in node.body:
                if isinstance(item, ast.FunctionDef):
                    out[f"{node.name}.{item.name}"] = params(item)
    return out


def runtime_params(obj):
    """Parameter names: from the signature of Python functions, from pybind11's docstring line otherwise."""
    try:
        return [p for p in inspect.signature(obj).parameters if p not in ("self", "args", "kwargs", "settings")]
    except (TypeError, ValueError):
        first = (obj.__doc__ or "").splitlines()[0]
        m = re.match(r"\w+\((.*)\)", first)
        names = re.findall(r"(?:^|, )\*?(\w+)(?=:| ?=|,|$)", m.group(1)) if m else []
        return [n for n in names if n not in ("self", "kwargs", "args")]


def test_every_public_name_has_a_stub():
    stubs = stub_signatures()
    for name in fresnel.__all__:
        assert name in stubs, f"{name} is not in {STUB.name}"
    for cls in (fresnel.Job, fresnel.Scene, fresnel.Renderer):
        for attr, value in vars(cls).items():
            if attr.startswith("_") and attr not in ("__enter__", "__exit__", "__getitem__", "__setitem__"):
                continue
            assert f"{cls.__name__}.{attr}" in stubs, f"{cls.__name__}.{attr} is not in {STUB.name}"


def test_stub_parameters_match_the_module():
    stubs = stub_signatures()
    for name in fresnel.__all__:
        obj = getattr(fresnel, name)
        if inspect.isclass(obj) or stubs.get(name) is None:
            continue
        runtime = runtime_params(obj)
        stub = [p for p in stubs[name] if p != "settings"]
        assert runtime == stub, f"{name}: module {runtime}, stub {stub}"
    for cls in (fresnel.Renderer,):
        for attr in ("render", "channel"):
            runtime = runtime_params(getattr(cls, attr))
            stub = [p for p in stubs[f"{cls.__name__}.{attr}"] if p != "settings"]
            assert runtime == stub, f"{cls.__name__}.{attr}: module {runtime}, stub {stub}"
