"""Non-adhesive solves through the Python objects against Hertz (1882).

Set-up of the Rust test `validation_hertz.rs`: free grid n = 128, side 1, R = E* = 1,
contact radius a = sqrt(R d) = 32 elements. Tolerances (as in Rust): force within 0.5 %
(the discretisation error at a = 32 dx is about 1e-4), contact radius within one element
(the contact boundary is a staircase of elements).
"""

import numpy as np
import pytest

import adhesim

N = 128
A_ELEMENTS = 32


@pytest.fixture(scope="module")
def setup():
    grid = adhesim.Grid(N, 1.0, "free")
    operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
    heights = adhesim.geometry.sphere(grid, 1.0)
    a = A_ELEMENTS * grid.element_size
    return grid, operator, heights, a * a  # depth d = a^2/R


@pytest.mark.parametrize("solver_name", ["Ccg", "NestedActiveSet"])
def test_force_and_radius_at_given_depth(setup, solver_name):
    grid, operator, heights, depth = setup
    solver = getattr(adhesim, solver_name)(operator)
    report = solver.solve(heights, depth)
    hertz = adhesim.reference.hertz(1.0, 1.0, depth)
    force_error = report.force / hertz["force"] - 1.0
    assert abs(force_error) < 5e-3, f"{solver_name}: force error {force_error:.2e}"
    radius = report.state.contact_radius()
    assert abs(radius - hertz["contact_radius"]) <= grid.element_size, (radius, hertz["contact_radius"])
    # the state is consistent: F = dx^2 sum(p), p >= 0, gap 0 in contact and >= 0 outside
    state = report.state
    assert state.force == pytest.approx(report.force, rel=1e-12)
    assert state.pressure.min() >= 0.0
    gap = state.gap
    assert np.all(gap[~state.contact] >= -1e-12 * depth)
    assert np.abs(gap[state.contact]).max() < 1e-6 * depth


def test_load_control_finds_hertz_depth(setup):
    """Load control reaches the load to 1e-8 relative and the depth it finds matches
    Hertz's within the same 0.5 % as the force (Rust: hertz_load_control_and_warm_start)."""
    grid, operator, heights, depth = setup
    load = adhesim.reference.hertz(1.0, 1.0, depth)["force"]
    report = adhesim.Ccg(operator).solve(heights, load=float(load))
    assert report.force == pytest.approx(load, rel=1e-8)
    assert report.depth == pytest.approx(depth, rel=5e-3)
    assert report.state.depth == report.depth


def test_warm_start_reuses_state(setup):
    """A second solve at the same depth from the solved state needs far fewer iterations
    and returns the same force (to the solver tolerance)."""
    grid, operator, heights, depth = setup
    solver = adhesim.Ccg(operator)
    state = adhesim.ContactState(grid)
    cold = solver.solve(heights, depth, state=state)
    warm = solver.solve(heights, depth, state=state)
    assert warm.state is state
    assert warm.iterations < cold.iterations
    assert warm.force == pytest.approx(cold.force, rel=1e-8)


def test_solves_are_deterministic(setup):
    """Fresh objects give bit-identical fields (no hidden state between solves)."""
    grid, _, heights, depth = setup
    results = []
    for _ in range(2):
        operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
        results.append(adhesim.NestedActiveSet(operator).solve(heights, depth).state.pressure)
    assert np.array_equal(results[0], results[1])


def test_operator_self_compliance_and_linearity():
    """u = K p: a unit pressure on the centre element gives K(0,0) there (free grid);
    the operator is linear; on a periodic grid a uniform pressure displaces nothing
    (K^(0) = 0)."""
    grid = adhesim.Grid(32, 1.0, "free")
    operator = adhesim.HalfSpace(grid, adhesim.Material(2.0))
    unit = np.zeros((32, 32))
    unit[16, 16] = 1.0
    u = operator.apply(unit)
    assert u[16, 16] == pytest.approx(operator.self_compliance, rel=1e-12)
    rng = np.random.default_rng(1)
    p, q = rng.random((32, 32)), rng.random((32, 32))
    combined = operator.apply(2.0 * p + q)
    assert np.allclose(combined, 2.0 * operator.apply(p) + operator.apply(q), rtol=1e-12, atol=1e-14)
    periodic = adhesim.HalfSpace(adhesim.Grid(32, 1.0, "periodic"), adhesim.Material(1.0))
    assert np.abs(periodic.apply(np.ones((32, 32)))).max() < 1e-12
    # Boussinesq far field of the free operator: u(r) -> F/(pi E* r) for a point load
    u_far = u[16, 31]
    r = 15 * grid.element_size
    assert u_far == pytest.approx(grid.element_area / (np.pi * 2.0 * r), rel=1e-3)


def test_periodic_grid_under_load_control():
    """On a periodic grid (one sphere per period L) the contact under the Hertz load of
    a = L/8 has Hertz's radius within one element: the periodic images, at distance L
    >= 8a, change the pressure near the contact only slightly. The depth is not compared:
    on a periodic half-space the mean displacement is undefined (K^(0) = 0), so the depth
    is a mean-gap measure there."""
    grid = adhesim.Grid(128, 1.0, "periodic")
    operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
    a = 16 * grid.element_size
    load = float(adhesim.reference.hertz(1.0, 1.0, a * a)["force"])
    report = adhesim.Ccg(operator).solve(adhesim.geometry.sphere(grid, 1.0), load=load)
    assert report.force == pytest.approx(load, rel=1e-8)
    assert abs(report.state.contact_radius() - a) <= grid.element_size
