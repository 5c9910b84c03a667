"""The public package: its layout, its exports, and type stubs that cannot drift from the
compiled module (names, signatures and every component's default parameters)."""

import ast
import math
import re
from pathlib import Path

import pytest

import vtrack
from vtrack import _core

STUB = ast.parse((Path(vtrack.__file__).parent / "_core.pyi").read_text())


def stub_names():
    names = set()
    for node in STUB.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names - {"ArrayLike", "RngLike"}


def test_stubs_cover_exactly_the_compiled_module():
    compiled = {n for n in dir(_core) if not n.startswith("_")} | {"__version__"}
    assert stub_names() == compiled


def runtime_parameters(func):
    """(positional names, keyword-only names, has **kwargs) from pybind11's signature line."""
    line = func.__doc__.strip().splitlines()[0]
    inside = line[line.index("(") + 1: line.rindex(")")]
    depth, part, parts = 0, "", []
    for ch in inside:
        depth += ch in "([{"
        depth -= ch in ")]}"
        if ch == "," and depth == 0:
            parts.append(part.strip())
            part = ""
        else:
            part += ch
    parts.append(part.strip())
    positional, keyword, var_kwargs, seen_star = [], [], False, False
    for p in filter(None, parts):
        if p == "*":
            seen_star = True
        elif p.startswith("**"):
            var_kwargs = True
        else:
            name = re.split(r"[:=]", p)[0].strip()
            (keyword if seen_star else positional).append(name)
    return [n for n in positional if n != "self"], keyword, var_kwargs


def stub_functions():
    """(owner, name, FunctionDef) of every stub function and method (first of overloads)."""
    for node in STUB.body:
        if isinstance(node, ast.FunctionDef):
            yield None, node.name, node
        elif isinstance(node, ast.ClassDef):
            seen = set()
            for item in node.body:
                if isinstance(item, ast.FunctionDef) and item.name not in seen:
                    seen.add(item.name)
                    if not any(isinstance(d, ast.Name) and d.id == "property"
                               for d in item.decorator_list) and not item.name.startswith("__") \
                            or item.name == "__init__":
                        yield node.name, item.name, item


def literal(node):
    if isinstance(node, ast.Constant) and node.value is Ellipsis:
        return Ellipsis
    return ast.literal_eval(node)


@pytest.mark.parametrize("owner, name, node", list(stub_functions()),
                         ids=lambda v: v if isinstance(v, str) else "")
def test_stub_signatures_match_the_compiled_ones(owner, name, node):
    obj = getattr(_core, owner) if owner else _core
    func = getattr(obj, name)
    positional, keyword, var_kwargs = runtime_parameters(func)
    args = node.args
    stub_positional = [a.arg for a in args.posonlyargs + args.args if a.arg != "self"]
    assert stub_positional == positional, (owner, name)
    stub_keyword = [a.arg for a in args.kwonlyargs]
    defaults = getattr(obj, "default_params", None) if name == "__init__" else None
    if defaults is None:
        assert stub_keyword == keyword and not var_kwargs, (owner, name)
        return
    # A parameterised component: its keyword-only parameters are the model arguments the binding
    # names, then exactly its default_params(), with the same defaults.
    params = defaults()
    assert var_kwargs, f"{owner} takes its parameters as **kwargs"
    assert stub_keyword[:len(keyword)] == keyword, owner
    assert stub_keyword[len(keyword):] == list(params), owner
    for arg, default in zip(args.kwonlyargs[len(keyword):], args.kw_defaults[len(keyword):]):
        value = literal(default)
        expected = params[arg.arg]
        if isinstance(expected, float) and not math.isfinite(expected):
            assert value is Ellipsis, (owner, arg.arg)
        else:
            assert value == expected and type(value) is type(expected), (owner, arg.arg, value)


COMPONENTS = [vtrack.KdeBackground, vtrack.MultiBernoulliTracker, vtrack.BoxTracker,
              vtrack.GlmbTracker, vtrack.HogPeopleDetector, vtrack.models.DepthLikelihood,
              vtrack.smc.ParticleFilter, vtrack.smc.MCMCParticleFilter,
              vtrack.ColorParticleTracker, vtrack.PartParticleTracker,
              vtrack.ReclusteringSirTracker, vtrack.vehicles.VehicleDimensionEstimator]


def test_every_component_has_the_same_parameter_surface():
    for cls in COMPONENTS:
        params = cls.default_params()
        assert params and all(isinstance(k, str) for k in params), cls
        assert cls.default_params() == params  # a fresh dict each time, equal


SUBMODULES = ("assign", "detectors", "image", "io", "metrics", "models", "pipelines", "smc",
              "trackers", "vehicles", "evaluate", "synthetic", "scenarios", "rgbd", "synthetic_road",
              "synthetic_occlusion", "detsim")


def test_public_api_is_exported_and_documented():
    for name in vtrack.__all__:
        obj = getattr(vtrack, name)
        if callable(obj):
            assert obj.__doc__, f"vtrack.{name} has no docstring"
    for module in SUBMODULES:
        mod = __import__(f"vtrack.{module}", fromlist=["_"])
        assert mod.__doc__ and len(mod.__doc__) > 80, f"vtrack.{module} needs a module docstring"
        for name in getattr(mod, "__all__", []):
            assert hasattr(mod, name), f"vtrack.{module}.{name}"
    # Every compiled name is reachable from a public module.
    public = {n for m in SUBMODULES for n in getattr(__import__(f"vtrack.{m}", fromlist=["_"]),
                                                      "__all__", [])} | set(vtrack.__all__)
    internal = {"track_video", "track_detections", "follow_video"}  # wrapped by vtrack.pipelines
    missing = {n for n in dir(_core) if not n.startswith("_")} - public - internal
    assert not missing, missing
    assert (Path(vtrack.__file__).parent / "py.typed").exists()
