"""Adhesive indentation and pull-off through the step API against JKR (Johnson, Kendall &
Roberts 1971).

Set-up and tolerance of the Rust test `validation_jkr.rs`
(`pull_off_force_converges_at_first_order`): R = E* = 1, gamma such that a_JKR = 0.05,
a_JKR/dx = 8, approach to 2|d_JKR| in steps of |d_JKR|/40, then retraction until contact
is lost. The lattice detachment criterion converges to JKR at first order in dx/a_JKR,
from above: |F_min|/|F_JKR| - 1 = 1.4 dx/a_JKR within +-50 %.
"""

import math

import numpy as np
import pytest

import adhesim

A_JKR = 0.05
GAMMA = A_JKR**3 * 8.0 / (9.0 * math.pi)


def jkr_case(resolution, max_depth_jkr):
    """The grid of the Rust JkrCase: domain >= 2.3 x the contact radius at max depth."""
    scales = adhesim.reference.jkr_scales(1.0, 1.0, GAMMA)
    delta = A_JKR / resolution
    reach = adhesim.reference.jkr_at_depth(1.0, 1.0, GAMMA, max_depth_jkr * abs(scales["depth"]))
    n = max(math.ceil(2.3 * float(reach["contact_radius"]) / delta), 16)
    n += n % 2
    return adhesim.Grid(n, n * delta, "free"), scales


def cycle_depths(d_jkr, max_depth_jkr, steps_per_unit):
    """Approach depths as the library's IndentPulloff protocol computes them."""
    step = d_jkr / steps_per_unit
    max_depth = max_depth_jkr * d_jkr
    approach = [min(i * step, max_depth) for i in range(1, math.ceil(max_depth / step) + 1)]
    return approach, max_depth, step


def test_pull_off_force_through_step_api():
    resolution = 8.0
    grid, scales = jkr_case(resolution, 2.0)
    d_jkr = abs(scales["depth"])
    operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
    solver = adhesim.AdhesiveSolver(operator, GAMMA)
    heights = adhesim.geometry.sphere(grid, 1.0)
    state = adhesim.ContactState(grid)
    approach, depth, step = cycle_depths(d_jkr, 2.0, 40.0)
    forces = []
    for d in approach:
        report = solver.step(heights, d, state)
        forces.append(report.force)
    for _ in range(100_000):
        depth -= step
        report = solver.step(heights, depth, state)
        forces.append(report.force)
        if report.contact_elements == 0:
            break
    else:
        pytest.fail("contact not lost")
    error = max(-f for f in forces) / abs(scales["force"]) - 1.0
    expected = 1.4 / resolution
    assert 0.5 * expected < error < 1.5 * expected, f"|F_min|/|F_JKR| - 1 = {error:.4f}, expected ~{expected:.4f}"


def test_branches_follow_jkr_at_moderate_resolution():
    """Rust `branches_follow_jkr_at_moderate_resolution`, through `steps`: at a_JKR/dx = 16
    the retraction branch stays within 0.08|F_JKR| of JKR for d >= 0.5|d_JKR|, the
    approach branch within 0.08|F_JKR| for d >= 2|d_JKR|, and contact is lost within
    0.3|d_JKR| of the jump depth -9^(1/3)|d_JKR|."""
    grid, scales = jkr_case(16.0, 3.0)
    d_jkr, f_jkr = abs(scales["depth"]), abs(scales["force"])
    solver = adhesim.AdhesiveSolver(adhesim.HalfSpace(grid, adhesim.Material(1.0)), GAMMA)
    heights = adhesim.geometry.sphere(grid, 1.0)
    state = adhesim.ContactState(grid)
    approach, depth, step = cycle_depths(d_jkr, 3.0, 50.0)
    table = solver.steps(heights, np.array(approach), state)
    retract = []
    while state.contact_elements > 0:
        depth -= step
        retract.append((depth, solver.step(heights, depth, state).force))
        assert len(retract) < 100_000, "contact not lost"
    for depths, forces, minimum in (
        (table["depth"], table["force"], 2.0),
        (np.array([r[0] for r in retract[:-1]]), np.array([r[1] for r in retract[:-1]]), 0.5),
    ):
        reference = adhesim.reference.jkr_at_depth(1.0, 1.0, GAMMA, depths)
        checked = (depths >= minimum * d_jkr) & reference["in_contact"]
        error = np.abs(forces - reference["force"])[checked].max() / f_jkr
        assert error < 0.08, f"branch from d >= {minimum}|d_JKR|: error {error:.4f}"
    pull_off_depth = retract[-2][0]
    assert abs(pull_off_depth / d_jkr + 9 ** (1 / 3)) < 0.3, pull_off_depth / d_jkr


def test_steps_equals_step_loop_bit_for_bit():
    """`steps` (one call, signal checks between steps) and a Python loop of `step` give
    the same numbers, bit for bit."""
    grid, scales = jkr_case(6.0, 1.5)
    d_jkr = abs(scales["depth"])
    heights = adhesim.geometry.sphere(grid, 1.0)
    depths = np.concatenate([np.linspace(0.1, 1.5, 15), np.linspace(1.4, -1.0, 25)]) * d_jkr
    results = []
    for use_sequence in (True, False):
        operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
        solver = adhesim.AdhesiveSolver(operator, GAMMA)
        state = adhesim.ContactState(grid)
        if use_sequence:
            seen = []
            table = solver.steps(heights, depths, state, progress=lambda i, r: seen.append(i))
            assert seen == list(range(len(depths)))
            forces = table["force"]
        else:
            forces = np.array([solver.step(heights, d, state).force for d in depths])
        results.append((forces, state.pressure))
    assert np.array_equal(results[0][0], results[1][0])
    assert np.array_equal(results[0][1], results[1][1])


def test_energy_and_critical_stress():
    """sigma_c = sqrt(E* gamma/(c_U dx)) with c_U = 0.4732 (Pohrt & Popov 2015), and the
    energy of the contact-free state is 0."""
    grid = adhesim.Grid(16, 1.0)
    solver = adhesim.AdhesiveSolver(adhesim.HalfSpace(grid, adhesim.Material(2.0)), 0.01)
    expected = math.sqrt(2.0 * 0.01 / (0.47320100440933854 * grid.element_size))
    assert np.allclose(solver.critical_stress, expected, rtol=1e-14)
    assert solver.energy(adhesim.ContactState(grid)) == 0.0
