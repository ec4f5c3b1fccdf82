"""Bad input raises ValueError/TypeError naming the argument and the value, never a panic;
a solver that does not converge raises adhesim.SolveError."""

import numpy as np
import pytest

import adhesim


@pytest.fixture(scope="module")
def grid():
    return adhesim.Grid(32, 1.0)


@pytest.fixture(scope="module")
def operator(grid):
    return adhesim.HalfSpace(grid, adhesim.Material(1.0))


@pytest.mark.parametrize(
    "call, words",
    [
        (lambda: adhesim.reference.hertz(-1.0, 1.0, 0.1), ["radius", "-1"]),
        (lambda: adhesim.reference.jkr_scales(1.0, 1.0, -0.5), ["work_of_adhesion", "-0.5"]),
        (lambda: adhesim.reference.flat_punch(-2.0, 1.0), ["radius", "-2"]),
        (lambda: adhesim.reference.hertz(1.0, 0.0, 0.1), ["contact_modulus", "0"]),
        (lambda: adhesim.Material(-3.0), ["contact_modulus", "-3"]),
        (lambda: adhesim.Material.from_youngs_modulus(1.0, 0.7), ["Poisson", "0.7"]),
        (lambda: adhesim.Grid(1, 1.0), ["n", "1"]),
        (lambda: adhesim.Grid(-4, 1.0), ["n", "-4"]),
        (lambda: adhesim.Grid(8, float("nan")), ["size", "NaN"]),
        (lambda: adhesim.Grid(8, 1.0, "round"), ["boundary", "round"]),
        (lambda: adhesim.geometry.sphere(adhesim.Grid(8, 1.0), -1.0), ["radius", "-1"]),
        (lambda: adhesim.reference.johnson_parameter(1.0, -0.1, 1.0, 1.0), ["amplitude", "-0.1"]),
    ],
)
def test_bad_scalars_name_the_argument(call, words):
    with pytest.raises(ValueError) as error:
        call()
    for word in words:
        assert word in str(error.value)


def test_wrong_shape_heights(grid, operator):
    solver = adhesim.Ccg(operator)
    with pytest.raises(ValueError, match=r"heights must have shape \(32, 32\).*got shape \[16, 16\]"):
        solver.solve(np.zeros((16, 16)), 0.01)
    with pytest.raises(ValueError, match=r"heights must have shape \(32, 32\)"):
        adhesim.AdhesiveSolver(operator, 0.01).step(np.zeros(32 * 32), 0.01, adhesim.ContactState(grid))
    with pytest.raises(ValueError, match=r"pressure must have shape \(32, 32\)"):
        operator.apply(np.zeros((32, 31)))


def test_wrong_dtype_and_type(grid, operator):
    solver = adhesim.NestedActiveSet(operator)
    with pytest.raises(TypeError, match=r"heights must have dtype float64 and shape \(32, 32\).*int64"):
        solver.solve(np.zeros((32, 32), dtype=np.int64), 0.01)
    with pytest.raises(TypeError, match=r"float32"):
        solver.solve(np.zeros((32, 32), dtype=np.float32), 0.01)
    with pytest.raises(TypeError, match=r"heights must be a numpy.ndarray .*got list"):
        solver.solve([[0.0] * 32] * 32, 0.01)


def test_non_finite_values(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    heights[3, 4] = np.nan
    with pytest.raises(ValueError, match=r"heights\[3, 4\] must be finite or \+inf.*NaN"):
        adhesim.Ccg(operator).solve(heights, 0.01)
    with pytest.raises(ValueError, match=r"depth must be finite, got inf"):
        adhesim.Ccg(operator).solve(adhesim.geometry.sphere(grid, 1.0), float("inf"))
    with pytest.raises(ValueError, match=r"work_of_adhesion must be finite and >= 0, got -1"):
        adhesim.AdhesiveSolver(operator, -1.0)
    with pytest.raises(ValueError, match=r"work_of_adhesion must have shape \(32, 32\)"):
        adhesim.AdhesiveSolver(operator, np.ones((4, 4)))


def test_control_and_grid_mismatch(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    with pytest.raises(ValueError, match=r"exactly one of depth and load"):
        adhesim.Ccg(operator).solve(heights, 0.01, load=1.0)
    with pytest.raises(ValueError, match=r"load must be finite and > 0, got -1"):
        adhesim.Ccg(operator).solve(heights, load=-1.0)
    other = adhesim.ContactState(adhesim.Grid(16, 1.0))
    with pytest.raises(ValueError, match=r"state is for a grid of n=16"):
        adhesim.Ccg(operator).solve(heights, 0.01, state=other)
    periodic = adhesim.HalfSpace(adhesim.Grid(32, 1.0, "periodic"), adhesim.Material(1.0))
    with pytest.raises(ValueError, match=r"free grids only"):
        adhesim.NestedActiveSet(periodic)
    with pytest.raises(ValueError, match=r"max_iterations must be an integer >= 1, got 0"):
        adhesim.Ccg(operator, max_iterations=0)
    with pytest.raises(ValueError, match=r"attachment must be"):
        adhesim.AdhesiveSolver(operator, 0.01, attachment="glue")


def test_non_convergence_is_reported(grid, operator):
    heights = adhesim.geometry.sphere(grid, 1.0)
    with pytest.raises(adhesim.SolveError, match=r"did not converge in 2 iterations"):
        adhesim.Ccg(operator, max_iterations=2).solve(heights, 0.01)
    assert issubclass(adhesim.SolveError, RuntimeError)


def test_gap_needs_a_solve(grid):
    with pytest.raises(ValueError, match=r"not been solved"):
        adhesim.ContactState(grid).gap
