"""The Python functions and classes of the package have numpy-style docstrings
(docs/python.md): numpydoc section headers, never Google-style ``Args:``, and a
``Parameters`` section that names every parameter of the signature."""

import inspect
import re

import pytest

import adhesim
from adhesim import _run, _sweep, fit, geometry, reference, surface, topography

MODULES = [_run, _sweep, fit, geometry, reference, surface, topography]
GOOGLE = re.compile(r"^\s*(Args|Arguments|Returns|Raises|Attributes|Yields|Examples?):\s*$", re.M)


def documented():
    for module in MODULES:
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if inspect.isfunction(obj) or inspect.isclass(obj):
                yield f"{module.__name__}.{name}", obj


@pytest.mark.parametrize("name, obj", list(documented()), ids=lambda v: v if isinstance(v, str) else "")
def test_numpy_style(name, obj):
    doc = inspect.getdoc(obj) or ""
    assert doc.strip(), f"{name} has no docstring"
    assert not GOOGLE.search(doc), f"{name}: Google-style section {GOOGLE.search(doc).group(0)!r}"
    if "\nParameters\n----------\n" in doc and inspect.isfunction(obj):
        section = doc.split("\nParameters\n----------\n", 1)[1].split("\n\n")[0]
        listed = section + "\n" + doc  # groups such as "zip, random, derived : dict"
        for parameter in inspect.signature(obj).parameters:
            pattern = rf"^[\w, *]*\b{parameter}\b[\w, *]*( :.*)?$"
            assert re.search(pattern, listed, re.M), f"{name}: parameter {parameter} not documented"


def test_the_converted_functions_have_their_sections():
    for function in (adhesim.run, adhesim.load, adhesim.sweep, fit.jkr_work_of_adhesion, reference.hertz):
        doc = inspect.getdoc(function)
        assert "Parameters\n----------" in doc and "Returns\n-------" in doc, function.__name__


COMPILED = [
    adhesim.Grid,
    adhesim.Material,
    adhesim.HalfSpace,
    adhesim.ContactState,
    adhesim.Ccg,
    adhesim.NestedActiveSet,
    adhesim.AdhesiveSolver,
    adhesim.SolveReport,
    adhesim.StepReport,
    adhesim.reference.jkr_scales,
]


def test_compiled_objects_are_numpy_style():
    """The docstrings written in Rust (src/objects.rs, src/state.rs, src/solvers.rs,
    src/adhesive.rs) and jkr_scales': no Google section on a class or any of its members,
    and the constructors' parameters in a numpydoc section."""
    for obj in COMPILED:
        members = [getattr(obj, m) for m in dir(obj) if not m.startswith("_")] if inspect.isclass(obj) else []
        for item in [obj, *members]:
            doc = inspect.getdoc(item) or ""
            assert not GOOGLE.search(doc), f"{getattr(item, '__qualname__', item)}: {GOOGLE.search(doc).group(0)!r}"
    assert "Parameters\n----------\noperator\n" in inspect.getdoc(adhesim.AdhesiveSolver)
    assert "Parameters\n----------\nn, size : int, float\n" in inspect.getdoc(adhesim.Grid)
    assert "Raises\n------\nValueError\n" in inspect.getdoc(adhesim.Material)
    assert "Parameters\n----------\ngrid : Grid\n" in inspect.getdoc(adhesim.ContactState)
    apply = inspect.getdoc(adhesim.HalfSpace.apply)
    assert "Parameters\n----------\npressure : array_like" in apply and "Returns\n-------\ndisplacement" in apply
