"""`adhesim.sweep` on the command line's sweep engine: the same cases, folders and
table.csv as `adhesim sweep`, run on concurrent.futures and Dask executors, resumed
without computing a finished case again."""

import concurrent.futures
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import adhesim

# A wavy sphere on a 32 × 32 grid (sweeps/tiny.toml's scenario): seconds per case.
BASE = """
[grid]
n = 32
size = 0.8
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 6.16850275068085e-4
[indenter]
shape = "wavy_sphere"
radius = 1.0
amplitude = 0.0025
wavelength = 0.1
[protocol]
kind = "indent_pulloff"
max_depth = 6.0
depth_unit = "jkr"
steps = 12
[output]
jump_force_threshold = 0.01
"""

ALPHAS = {"alpha": [0.8, 1.2]}


def cli_binary():
    path = os.environ.get("ADHESIM_BIN")
    if path and Path(path).is_file():
        return Path(path)
    pytest.skip("ADHESIM_BIN does not name the adhesim binary")


@pytest.fixture(scope="module")
def command_line_sweep(tmp_path_factory):
    """`adhesim sweep` of base.toml with [vary] alpha = [0.8, 1.2] (series "s")."""
    folder = tmp_path_factory.mktemp("cli")
    (folder / "base.toml").write_text(BASE)
    (folder / "sweep.toml").write_text('base = "base.toml"\nseries = "s"\n[vary]\nalpha = [0.8, 1.2]\n')
    out = folder / "out"
    subprocess.run(
        [str(cli_binary()), "sweep", str(folder / "sweep.toml"), "--out", str(out), "--jobs", "1", "--quiet"],
        check=True,
    )
    return folder, out


def without_timings(summary_path):
    summary = json.loads(Path(summary_path).read_text())
    summary.pop("performance")
    return summary


def assert_same_sweep(python_out, cli_out):
    """table.csv byte-identical; per case curve.csv, fields.npz, scenario.toml, case.json
    byte-identical and summary.json equal apart from its timings."""
    assert (python_out / "table.csv").read_bytes() == (cli_out / "table.csv").read_bytes()
    cli_cases = sorted(p.name for p in (cli_out / "cases").iterdir())
    assert sorted(p.name for p in (python_out / "cases").iterdir()) == cli_cases
    for case in cli_cases:
        mine, theirs = python_out / "cases" / case, cli_out / "cases" / case
        assert sorted(p.name for p in mine.rglob("*")) == sorted(p.name for p in theirs.rglob("*"))
        for name in ("curve.csv", "fields.npz", "scenario.toml", "case.json", "done"):
            assert (mine / name).read_bytes() == (theirs / name).read_bytes(), f"{case}/{name}"
        assert without_timings(mine / "summary.json") == without_timings(theirs / "summary.json")


def done_markers(out):
    return {p.parent.name: p.stat().st_mtime_ns for p in (out / "cases").glob("*/done")}


def test_a_process_pool_sweep_equals_the_command_line_and_resumes(command_line_sweep):
    folder, cli_out = command_line_sweep
    out = folder / "python"
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        cases = adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s", executor=pool)
    assert len(cases) == 2 and cases.ran == 2
    assert [c.case for c in cases] == [{"alpha": 0.8}, {"alpha": 1.2}]
    assert_same_sweep(out, cli_out)
    # The JKR-type pull-off force of each case is the command line's table value.
    assert list(cases.table["case"]) == [c.case_id for c in cases]
    # Numbers, as sweep_table gives them (they were the cells' text).
    assert cases.table["max_adhesive_force"].dtype == np.float64
    assert list(cases.table["max_adhesive_force"]) == [
        c.results["max_adhesive_force"] for c in cases
    ]
    # A second call with the same folder computes no case again.
    markers = done_markers(out)
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        again = adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s", executor=pool)
    assert again.ran == 0
    assert done_markers(out) == markers
    assert [c.summary["results"] for c in again] == [c.summary["results"] for c in cases]


def test_a_lost_case_is_the_only_one_run_again(command_line_sweep, tmp_path):
    folder, cli_out = command_line_sweep
    out = tmp_path / "sweep"
    adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s")
    first, second = sorted((out / "cases").iterdir())
    # A worker killed mid-case leaves no case folder, only its temporary one.
    os.rename(second, out / "tmp" / f"{second.name}.99999")
    markers = done_markers(out)
    cases = adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s")
    assert cases.ran == 1
    assert done_markers(out)[first.name] == markers[first.name]
    assert not list((out / "tmp").iterdir())
    assert_same_sweep(out, cli_out)


# The wavy sphere of BASE on 64 × 64 in 60 steps per branch: long enough (seconds) for a
# checkpoint before the case ends.
LONG = BASE.replace("n = 32", "n = 64").replace("steps = 12", "steps = 60")


def test_a_killed_case_goes_on_from_its_checkpoint(tmp_path, capfd):
    """A worker killed (SIGKILL) mid-case after a checkpoint: the next call goes on from
    it ("resumed case ... at step k" on stderr) and the case folder is the uninterrupted
    run's (curve.csv, fields.npz byte-identical; summary.json but its timings)."""
    base = tmp_path / "base.toml"
    base.write_text(LONG)
    vary = {"alpha": [0.8]}
    reference = tmp_path / "reference"
    adhesim.sweep(base, vary=vary, out=reference, series="s", checkpoint_every=0.05)
    killed = tmp_path / "killed"
    script = (f"import adhesim; adhesim.sweep({str(base)!r}, vary={vary!r}, out={str(killed)!r}, "
              f"series='s', checkpoint_every=0.05)")
    child = subprocess.Popen([sys.executable, "-c", script], stderr=subprocess.DEVNULL)
    start = time.monotonic()
    while not list(killed.glob("tmp/*/checkpoint.json")):
        assert time.monotonic() - start < 120, "no checkpoint written"
        assert child.poll() is None, "the case ended before a checkpoint"
        time.sleep(0.002)
    time.sleep(0.05)
    child.kill()
    child.wait()
    if list(killed.glob("cases/*/done")):
        return  # the case finished before the kill (a very fast machine): nothing to resume
    capfd.readouterr()
    cases = adhesim.sweep(base, vary=vary, out=killed, series="s", checkpoint_every=0.05)
    assert cases.ran == 1
    assert "resumed case " in capfd.readouterr().err
    (case,) = [p.name for p in (reference / "cases").iterdir()]
    for name in ("curve.csv", "fields.npz"):
        assert (killed / "cases" / case / name).read_bytes() == (reference / "cases" / case / name).read_bytes()
    assert without_timings(killed / "cases" / case / "summary.json") == without_timings(
        reference / "cases" / case / "summary.json")
    assert (killed / "table.csv").read_bytes() == (reference / "table.csv").read_bytes()


def test_a_dask_cluster_runs_the_sweep(command_line_sweep):
    distributed = pytest.importorskip("dask.distributed")
    folder, cli_out = command_line_sweep
    out = folder / "dask"
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            cases = adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s",
                                  executor=client.get_executor())
    assert cases.ran == 2
    assert_same_sweep(out, cli_out)


def test_sweep_errors_name_the_argument(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(BASE)
    with pytest.raises(TypeError, match=r"vary must be a mapping.*\[0.8\]"):
        adhesim.sweep(base, vary=[0.8], out=tmp_path / "a")
    with pytest.raises(ValueError, match=r"unknown sweep key `alpah`"):
        adhesim.sweep(base, vary={"alpah": [0.8]}, out=tmp_path / "a")
    with pytest.raises(ValueError, match=r"case 0 \(grid.n = -4\).*grid.n"):
        adhesim.sweep(base, vary={"grid.n": [-4]}, out=tmp_path / "a")
    adhesim.sweep(base, vary={"alpha": [0.8]}, out=tmp_path / "b")
    with pytest.raises(ValueError, match="holds a different sweep"):
        adhesim.sweep(base, vary={"alpha": [1.2]}, out=tmp_path / "b")
    # An alpha sweep of a scenario without amplitude-bearing indenter names the problem.
    with pytest.raises(ValueError, match="alpha"):
        adhesim.sweep(base, vary={"alpha": [0.8]}, derived={"alpha": "indenter.radius"}, out=tmp_path / "c")


def test_one_thread_cases_on_a_process_pool_equal_the_command_line(command_line_sweep, tmp_path):
    """`threads=1`: each case in a one-thread pool of its own, two cases side by side (the
    faster split on few cores); the same bits as the command line's sweep."""
    folder, cli_out = command_line_sweep
    out = tmp_path / "one_thread"
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        cases = adhesim.sweep(folder / "base.toml", vary=ALPHAS, out=out, series="s", executor=pool, threads=1)
    assert cases.ran == 2
    assert [c.summary["performance"]["threads"] for c in cases] == [1, 1]
    assert_same_sweep(out, cli_out)


@pytest.mark.parametrize("threads", [0, -2, 2.0, False])
def test_a_bad_thread_count_of_a_sweep_is_refused_by_name(threads, tmp_path):
    with pytest.raises(ValueError, match="threads must be an integer >= 1, got"):
        adhesim.sweep(BASE, vary=ALPHAS, out=tmp_path / "s", threads=threads)
    assert not (tmp_path / "s").exists()
