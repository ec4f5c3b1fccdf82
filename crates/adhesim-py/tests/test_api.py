"""The package's surface: type stubs match the extension, everything public is documented."""

import ast
import inspect
import pathlib

import adhesim
from adhesim import _adhesim


def stub_names():
    stub = pathlib.Path(_adhesim.__file__).with_name("_adhesim.pyi")
    if not stub.exists():  # installed wheels carry the stub next to the extension
        stub = pathlib.Path(adhesim.__file__).with_name("_adhesim.pyi")
    tree = ast.parse(stub.read_text())
    names = {}
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            members = {n.name for n in node.body if isinstance(n, ast.FunctionDef)} if isinstance(node, ast.ClassDef) else set()
            members |= {n.target.id for n in getattr(node, "body", []) if isinstance(n, ast.AnnAssign)}
            names[node.name] = members
        elif isinstance(node, ast.AnnAssign):
            names[node.target.id] = set()
    return names


def test_stubs_match_the_extension():
    stubs = stub_names()
    public = {name for name in dir(_adhesim) if not name.startswith("__")} | {"__version__"}
    assert set(stubs) == public
    for name, members in stubs.items():
        obj = getattr(_adhesim, name)
        if inspect.isclass(obj) and members:
            # constructors (__new__) and other dunders: CI's mypy.stubtest checks those
            declared = {m for m in members if not m.startswith("__")}
            actual = {m for m in dir(obj) if not m.startswith("_")}
            assert declared == actual - set(dir(RuntimeError)), name


def test_everything_public_has_a_docstring():
    missing = []
    for module in (adhesim, adhesim.reference, adhesim.fit, adhesim.geometry, adhesim.surface):
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if callable(obj) and not (obj.__doc__ or "").strip():
                missing.append(f"{module.__name__}.{name}")
            if inspect.isclass(obj):
                for member, value in vars(obj).items():
                    if not member.startswith("_") and not (getattr(value, "__doc__", "") or "").strip():
                        missing.append(f"{name}.{member}")
    assert not missing, missing
