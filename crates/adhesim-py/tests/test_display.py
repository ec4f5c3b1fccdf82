"""Reprs show the object's parameters; RunResult._repr_html_ is a summary table plus the
force curve when matplotlib is importable (docs/python.md, "Object reference")."""

import base64
import re
import sys
from pathlib import Path

import numpy as np
import pytest

import adhesim

JKR_TOML = Path(__file__).resolve().parents[3] / "scenarios" / "jkr.toml"
SMALL = {"grid.n": 32, "protocol.steps": 20}


@pytest.fixture
def operator():
    return adhesim.HalfSpace(adhesim.Grid(16, 0.5, "periodic"), adhesim.Material(2.5))


def test_object_reprs_show_their_parameters(operator):
    grid = adhesim.Grid(16, 0.5, "periodic")
    assert repr(grid) == 'Grid(n=16, size=0.5, boundary="periodic")'
    assert repr(adhesim.Material(2.5)) == "Material(contact_modulus=2.5)"
    half = 'HalfSpace(grid=Grid(n=16, size=0.5, boundary="periodic"), contact_modulus=2.5)'
    assert repr(operator) == half
    assert repr(adhesim.Ccg(operator, tolerance=1e-8, max_iterations=300)) == (
        f"Ccg({half}, tolerance=1e-8, max_iterations=300)"
    )
    free = adhesim.HalfSpace(adhesim.Grid(16, 0.5), adhesim.Material(2.5))
    nested = repr(adhesim.NestedActiveSet(free, max_rounds=7, coarsest=8))
    assert nested.startswith("NestedActiveSet(HalfSpace(grid=Grid(n=16, size=0.5, boundary=\"free\")")
    assert "relative_tolerance=1e-10, max_cg_iterations=2000, max_rounds=7, coarsest=8)" in nested


def test_adhesive_solver_repr_shows_gamma_and_every_parameter(operator):
    uniform = repr(adhesim.AdhesiveSolver(operator, 0.125, attachment="penetration_only"))
    assert "work_of_adhesion=0.125," in uniform
    assert "attachment='penetration_only', worst_first_fraction=None" in uniform
    for text in ("relative_tolerance=1e-6", "front_tolerance=0.0001", "max_cg_iterations=5000",
                 "max_rounds=100000", "preconditioned=True", "carry_bans_when_retracting=True",
                 "retry_after_growth=True"):
        assert text in uniform
    gamma = np.linspace(0.1, 0.3, 256).reshape(16, 16)
    mapped = repr(adhesim.AdhesiveSolver(operator, gamma, worst_first_fraction=0.05, preconditioned=False))
    assert "work_of_adhesion=<map (16, 16), 0.1 to 0.3>" in mapped
    assert "worst_first_fraction=0.05" in mapped and "preconditioned=False" in mapped


def test_state_and_reports_reprs(operator):
    state = adhesim.ContactState(operator.grid)
    assert repr(state) == (
        'ContactState(grid=Grid(n=16, size=0.5, boundary="periodic"), depth=None, force=0e0, '
        "contact_elements=0)"
    )
    heights = adhesim.geometry.sphere(operator.grid, 1.0)
    report = adhesim.Ccg(operator).solve(heights, depth=0.002, state=state)
    assert "depth=0.002," in repr(state)
    assert f"contact_elements={state.contact_elements})" in repr(state) and state.contact_elements > 0
    shown = repr(report)
    assert shown.startswith("SolveReport(force=")
    assert float(re.search(r"force=([^,]+),", shown).group(1)) == state.force
    assert float(re.search(r"depth=([^,]+),", shown).group(1)) == 0.002
    assert f"contact_elements={state.contact_elements}," in shown


@pytest.fixture(scope="module")
def result(tmp_path_factory):
    return adhesim.run(JKR_TOML, out=tmp_path_factory.mktemp("display") / "run", **SMALL)


def test_run_result_and_snapshot_reprs(result):
    text = repr(result)
    assert text.startswith("RunResult(grid='32×32, size 0.25, free', steps=")
    steps = len(result.curve_arrays["step"])
    assert f"steps={steps}, snapshots={len(result.snapshots)}, out={str(result.out)!r}" in text
    force = result.results["max_adhesive_force"]
    assert f"max_adhesive_force={force:.6g}" in text
    snapshot = result.snapshots[0]
    assert repr(snapshot) == (
        f"Snapshot(step={snapshot.step}, depth={snapshot.depth:.6g}, offset=0, fields=32x32)"
    )


def _table(html):
    rows = re.findall(r"<tr><th[^>]*>(.*?)</th><td[^>]*>(.*?)</td></tr>", html)
    return dict(rows)


def test_repr_html_table_without_matplotlib(result, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # import matplotlib... fails
    monkeypatch.setitem(sys.modules, "matplotlib.figure", None)
    html = result._repr_html_()
    assert "<img" not in html
    table = _table(html)
    assert table["grid"] == "32×32, size 0.25, free"
    assert table["steps"] == str(len(result.curve_arrays["step"]))
    assert table["snapshots"] == str(len(result.snapshots))
    for key in ("max_adhesive_force", "gamma_approach", "gamma_pulloff"):
        assert float(table[key]) == pytest.approx(result.results[key], rel=1e-5)
    assert "mean_tangential_force" not in table  # None for an indentation: left out


def test_repr_html_has_the_force_curve_with_matplotlib(result):
    pytest.importorskip("matplotlib")
    html = result._repr_html_()
    assert float(_table(html)["max_adhesive_force"]) == pytest.approx(
        result.results["max_adhesive_force"], rel=1e-5
    )
    match = re.search(r"<img alt='force curve' src='data:image/png;base64,([A-Za-z0-9+/=]+)'", html)
    assert match, html[:300]
    png = base64.b64decode(match.group(1))
    assert png.startswith(b"\x89PNG\r\n\x1a\n") and len(png) > 2000


def test_sweep_result_repr(tmp_path):
    cases = adhesim.sweep(JKR_TOML, vary={"adhesion.work_of_adhesion": [3e-5, 4e-5]},
                          out=tmp_path / "sweep", **SMALL)
    assert repr(cases) == (
        f"SweepResult(cases=2, keys=['adhesion.work_of_adhesion'], ran=2, "
        f"out={str(tmp_path / 'sweep')!r})"
    )
