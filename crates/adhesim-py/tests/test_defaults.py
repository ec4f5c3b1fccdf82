"""The solvers' default parameters come from the Rust library's Default impls: listed by
`defaults()`, used when an argument is left out, and written by hand nowhere in the
Python signatures, stubs or docstrings (docs/python.md, "Object reference")."""

import ast
import inspect
import pathlib
import re

import pytest

import adhesim

SOLVERS = [adhesim.Ccg, adhesim.NestedActiveSet, adhesim.AdhesiveSolver]


def make(cls, **kwargs):
    operator = adhesim.HalfSpace(adhesim.Grid(16, 1.0), adhesim.Material(1.0))
    if cls is adhesim.AdhesiveSolver:
        return cls(operator, 0.01, **kwargs)
    return cls(operator, **kwargs)


@pytest.mark.parametrize("cls", SOLVERS, ids=lambda c: c.__name__)
def test_defaults_are_the_parameters_left_out(cls):
    defaults = cls.defaults()
    required = {"operator", "work_of_adhesion"}
    optional = [name for name in inspect.signature(cls).parameters if name not in required]
    assert list(defaults) == optional
    # left out and given explicitly build the same solver (the repr shows every parameter)
    assert repr(make(cls)) == repr(make(cls, **defaults))
    for name, value in defaults.items():
        shown = "'trial'" if value == "trial" else repr(value).replace("e-06", "e-6")
        assert f"{name}={shown}" in repr(make(cls)), (name, repr(make(cls)))
    assert cls.defaults() is not defaults  # a fresh dict: changing it changes nothing


def test_adhesive_defaults_are_the_library_rules():
    defaults = adhesim.AdhesiveSolver.defaults()
    assert defaults["attachment"] == "trial" and defaults["worst_first_fraction"] is None
    assert defaults["preconditioned"] and defaults["retry_after_growth"]


@pytest.mark.parametrize("cls", SOLVERS, ids=lambda c: c.__name__)
def test_no_default_number_is_written_by_hand(cls):
    assert not re.search(r"default \d", cls.__doc__), cls.__doc__
    stub = pathlib.Path(adhesim.__file__).with_name("_adhesim.pyi")
    tree = ast.parse(stub.read_text())
    (node,) = [n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls.__name__]
    (new,) = [n for n in node.body if isinstance(n, ast.FunctionDef) and n.name == "__new__"]
    defaults = new.args.defaults
    assert len(defaults) == len(cls.defaults())
    assert all(isinstance(d, ast.Constant) and d.value is Ellipsis for d in defaults)
