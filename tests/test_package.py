"""The public package: its exports and the shipped type stubs agree with the compiled module."""

import ast
from pathlib import Path

import vtrack
from vtrack import _core


def stub_names():
    tree = ast.parse((Path(vtrack.__file__).parent / "_core.pyi").read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names - {"ArrayLike", "RngLike"}


def test_stubs_cover_exactly_the_compiled_module():
    compiled = {n for n in dir(_core) if not n.startswith("_")} | {"__version__"}
    assert stub_names() == compiled


def test_public_api_is_exported_and_documented():
    for name in vtrack.__all__:
        obj = getattr(vtrack, name)
        if callable(obj):
            assert obj.__doc__, f"vtrack.{name} has no docstring"
    assert (Path(vtrack.__file__).parent / "py.typed").exists()
