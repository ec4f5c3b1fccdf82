"""`adhesim.run(threads=...)`: each run has its own thread pool, never rayon's global one."""

import concurrent.futures
import multiprocessing
import sys
import warnings
from pathlib import Path

import pytest

import adhesim

REPO = Path(__file__).resolve().parents[3]
JKR_TOML = REPO / "scenarios" / "jkr.toml"
SMALL = {"grid.n": 32, "protocol.steps": 20}


def _run_steps():
    return len(adhesim.run(JKR_TOML, overrides=SMALL).curve_arrays["step"])


def _nested_solve_force():
    grid = adhesim.Grid(64, 1.0, "free")
    solver = adhesim.NestedActiveSet(adhesim.HalfSpace(grid, adhesim.Material(1.0)))
    return solver.solve(adhesim.geometry.sphere(grid, 1.0), 0.01).force


@pytest.mark.skipif(sys.platform != "linux", reason="the fork start method is Linux's default")
@pytest.mark.parametrize("call", [_run_steps, _nested_solve_force])
def test_a_call_in_a_forked_worker_after_one_in_its_parent_finishes(call):
    # On rayon's global pool the parent's call started its threads and a forked child
    # inherited the pool without them: its call waited forever (measured: no result in 60 s).
    expected = call()
    context = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=context) as pool:
        future = pool.submit(call)
        try:
            # The call takes well under a second; 120 s only guards against a hang.
            assert future.result(timeout=120) == expected
        except concurrent.futures.TimeoutError:
            for process in pool._processes.values():
                process.kill()
            pytest.fail(f"{call.__name__} in the forked worker did not finish in 120 s")


def test_every_thread_count_gives_the_same_bits():
    one = adhesim.run(JKR_TOML, overrides=SMALL, threads=1)
    two = adhesim.run(JKR_TOML, overrides=SMALL, threads=2)
    assert one.curve_arrays.keys() == two.curve_arrays.keys()
    for name, column in one.curve_arrays.items():
        assert column.tobytes() == two.curve_arrays[name].tobytes(), name


@pytest.mark.parametrize("threads", [0, -1, 1.5, True, "2"])
def test_a_bad_thread_count_is_refused_by_name(threads):
    with pytest.raises(ValueError, match=r"threads must be an integer >= 1, got " + repr(threads).replace(".", r"\.")):
        adhesim.run(JKR_TOML, overrides=SMALL, threads=threads)


@pytest.mark.parametrize("threads", [100_000, 10**30])
def test_more_threads_than_cores_are_clamped_with_a_warning(threads):
    # 10**30 exceeds a machine word (it raised OverflowError before it was clamped).
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = adhesim.run(JKR_TOML, overrides=SMALL, threads=threads)
    clamped = [str(w.message) for w in caught if " exceeds the " in str(w.message) and "cores" in str(w.message)]
    # One warning, naming the count given (not the machine word it was cut to before).
    assert len(clamped) == 1 and clamped[0].startswith(f"threads = {threads} exceeds"), [
        str(w.message) for w in caught
    ]
    assert len(result.curve_arrays["step"]) > 0
