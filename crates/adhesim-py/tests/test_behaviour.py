"""What a Python user expects beyond the numbers: Ctrl-C between steps, the GIL released
during solves, no memory growth over repeated solves."""

import _thread
import signal
import sys
import threading
import time

import numpy as np
import pytest

import adhesim

GAMMA = 0.05**3 * 8.0 / (9.0 * np.pi)  # a_JKR = 0.05 for R = E* = 1


def long_sequence():
    """A small adhesive contact and 200 000 depths cycling in and out of contact: minutes
    of work, so only an interrupt ends it within the test's time."""
    grid = adhesim.Grid(48, 48 * 0.05 / 6.0)
    solver = adhesim.AdhesiveSolver(adhesim.HalfSpace(grid, adhesim.Material(1.0)), GAMMA)
    heights = adhesim.geometry.sphere(grid, 1.0)
    d_jkr = abs(adhesim.reference.jkr_scales(1.0, 1.0, GAMMA)["depth"])
    cycle = np.concatenate([np.linspace(0.1, 2.0, 20), np.linspace(1.9, -2.2, 40)]) * d_jkr
    return grid, solver, heights, np.tile(cycle, 200_000 // cycle.size)


def give_up_after(seconds):
    """A progress callback that ends a sequence the interrupt failed to stop."""
    start = time.monotonic()

    def check(index, report):
        if time.monotonic() - start > seconds:
            raise RuntimeError(f"not interrupted after {seconds} s ({index} steps)")

    return check


def test_interrupt_main_stops_steps(sigint_raises_keyboard_interrupt):
    """_thread.interrupt_main() from another thread (what Ctrl-C does) raises
    KeyboardInterrupt from `steps` after the running step, leaving a consistent state."""
    grid, solver, heights, depths = long_sequence()
    state = adhesim.ContactState(grid)
    timer = threading.Timer(0.5, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            solver.steps(heights, depths, state, progress=give_up_after(20.0))
    finally:
        timer.cancel()
    assert time.monotonic() - start < 10.0
    # the state is that of the last completed step: its force is dx^2 sum(p)
    assert state.force == pytest.approx(grid.element_area * state.pressure.sum(), rel=1e-12)


@pytest.mark.skipif(not hasattr(signal, "pthread_kill"), reason="needs signal.pthread_kill")
def test_sigint_stops_a_python_loop_of_steps(sigint_raises_keyboard_interrupt):
    """A real SIGINT sent to the main thread while it loops over `step` calls (the GIL is
    released inside each step, so the sending thread runs) raises KeyboardInterrupt."""
    grid, solver, heights, depths = long_sequence()
    state = adhesim.ContactState(grid)
    main = threading.get_ident()
    timer = threading.Timer(0.5, signal.pthread_kill, args=(main, signal.SIGINT))
    done = 0
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            for depth in depths:
                solver.step(heights, depth, state)
                done += 1
                assert time.monotonic() - start < 20.0, f"not interrupted after 20 s ({done} steps)"
    finally:
        timer.cancel()
    assert 0 < done < depths.size
    assert time.monotonic() - start < 10.0


def test_gil_is_released_during_a_solve():
    """While one thread runs a long sequence of steps, the main thread keeps running
    Python code (it could not if the GIL were held throughout the steps)."""
    grid, solver, heights, depths = long_sequence()
    state = adhesim.ContactState(grid)
    worker = threading.Thread(target=solver.steps, args=(heights, depths[:240], state))
    ticks = 0
    worker.start()
    while worker.is_alive():
        ticks += 1
        time.sleep(0.001)
    worker.join()
    assert ticks > 10


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")
def test_no_memory_growth_over_repeated_solves(resident_growth_kib):
    """100 small solves, each with new objects (grid, operator, solver, state: ~2 MB of
    buffers and FFT plans at n = 64) and numpy results. After 20 warm-up solves the
    resident size may grow by at most 4 MiB: leaking one operator per solve would add
    > 20 MiB, leaking one state and its arrays ~7 MiB."""

    def solve():
        grid = adhesim.Grid(64, 1.0)
        operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
        heights = adhesim.geometry.sphere(grid, 1.0)
        report = adhesim.NestedActiveSet(operator).solve(heights, 0.01)
        state = report.state
        solver = adhesim.AdhesiveSolver(operator, 0.001)
        solver.step(heights, 0.01, state)
        return state.pressure.sum() + state.gap.sum() + operator.apply(state.pressure).sum()

    growth = resident_growth_kib(solve, warm_up=20, repeats=100)
    assert growth < 4096, f"RSS grew by {growth} KiB over 100 solves"
