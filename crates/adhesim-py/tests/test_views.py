"""Fields are read-only arrays, not fresh copies (docs/python.md, "Units, signs, arrays"):
the same array at each access until the owner changes, and writing into one raises
ValueError."""

from pathlib import Path

import numpy as np
import pytest

import adhesim

JKR_TOML = Path(__file__).resolve().parents[3] / "scenarios" / "jkr.toml"


@pytest.fixture
def solved():
    grid = adhesim.Grid(32, 1.0)
    operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
    heights = adhesim.geometry.sphere(grid, 1.0)
    state = adhesim.ContactState(grid)
    solver = adhesim.Ccg(operator)
    solver.solve(heights, depth=0.01, state=state)
    return solver, heights, state


@pytest.mark.parametrize("name", ["pressure", "displacement", "contact", "gap"])
def test_state_fields_are_one_read_only_array(solved, name):
    _, _, state = solved
    first, second = getattr(state, name), getattr(state, name)
    assert first is second
    assert not first.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        first[0, 0] = 1
    # a writeable copy is the caller's to take
    copy = np.array(first)
    copy[0, 0] = copy[0, 0]
    assert not np.shares_memory(copy, first)


def test_a_solve_gives_new_arrays_and_old_ones_keep_their_values(solved):
    solver, heights, state = solved
    before, gap_before = state.pressure, state.gap
    kept = before.copy()
    force_before = state.force
    solver.solve(heights, depth=0.02, state=state)
    after = state.pressure
    assert after is not before
    np.testing.assert_array_equal(before, kept)  # the old array is a snapshot
    assert state.force > force_before
    assert after.sum() * state.grid.element_area == pytest.approx(state.force, rel=1e-12)
    # the gap of the new depth: 0.01 less wherever no contact or displacement changed
    assert state.gap is state.gap and state.gap is not gap_before
    assert state.gap[0, 0] < gap_before[0, 0]
    assert state.gap[state.contact] == pytest.approx(0, abs=1e-9)


def test_adhesive_step_renews_the_fields_and_critical_stress_is_cached():
    grid = adhesim.Grid(32, 0.2)
    solver = adhesim.AdhesiveSolver(adhesim.HalfSpace(grid, adhesim.Material(1.0)), 1e-4)
    heights = adhesim.geometry.sphere(grid, 1.0)
    state = adhesim.ContactState(grid)
    empty = state.contact
    assert not empty.any()
    solver.step(heights, 1e-3, state)
    assert state.contact is not empty and state.contact.sum() == state.contact_elements > 0
    assert solver.critical_stress is solver.critical_stress
    assert not solver.critical_stress.flags.writeable


def test_copy_has_its_own_arrays(solved):
    _, _, state = solved
    copy = state.copy()
    assert copy.pressure is not state.pressure
    np.testing.assert_array_equal(copy.pressure, state.pressure)
    assert not copy.pressure.flags.writeable


def test_run_result_arrays_are_read_only(tmp_path):
    result = adhesim.run(JKR_TOML, out=tmp_path / "run", **{"grid.n": 32, "protocol.steps": 20})
    for loaded in (result, adhesim.load(tmp_path / "run")):
        column = loaded.curve_arrays["d"]
        assert loaded.curve_arrays["d"] is column and not column.flags.writeable
        snapshot = loaded.snapshots[0]
        for name in ("pressure", "displacement", "gap", "contact"):
            array = getattr(snapshot, name)
            assert getattr(snapshot, name) is array
            with pytest.raises(ValueError, match="read-only"):
                array[0, 0] = 0

