"""One-call runs: `adhesim.run`, `load`, `sweep` against the command line and themselves."""

import _thread
import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import adhesim

REPO = Path(__file__).resolve().parents[3]
JKR_TOML = REPO / "scenarios" / "jkr.toml"

# scenarios/jkr.toml as a dict (the same keys and values; comments left out).
JKR_DICT = {
    "grid": {"n": 128, "size": 0.25, "boundary": "free"},
    "material": {"contact_modulus": 1.0},
    "adhesion": {"work_of_adhesion": 3.5367765131532306e-5},
    "indenter": {"shape": "sphere", "radius": 1.0},
    "protocol": {"kind": "indent_pulloff", "max_depth": 5.0, "depth_unit": "jkr", "steps": 150},
    "output": {"jump_force_threshold": 0.01},
}

# A small, quick adhesive case (n = 32, 20 approach steps) for the behaviour tests.
SMALL = {"grid.n": 32, "protocol.steps": 20}


def cli_binary():
    """The `adhesim` binary named by ADHESIM_BIN (`.ci/run` sets it), or None."""
    path = os.environ.get("ADHESIM_BIN")
    if path and Path(path).is_file():
        return Path(path)
    return None


def same_bits(a, b):
    """Equal arrays, float64 compared by their bit patterns (NaN == NaN, -0 != +0)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "f":
        return a.shape == b.shape and np.array_equal(a.view(np.int64), b.view(np.int64))
    return a.shape == b.shape and np.array_equal(a, b)


def snapshot_steps(curve, chosen, approach_steps):
    """The snapshot steps of docs/output.md ("fields.npz") worked out from a curve: the
    chosen steps, the deepest (last approach) step, the last step in contact and the first
    step of the largest contact, each once, by step."""
    n_contact = np.asarray(curve["n_contact"])
    steps = set(chosen) | {approach_steps - 1}
    if n_contact.max() > 0:
        steps |= {int(np.flatnonzero(n_contact > 0)[-1]), int(np.argmax(n_contact))}
    return sorted(steps)


def without_performance(summary):
    """summary.json minus its timings and counters block (wall times differ run to run)."""
    return {k: v for k, v in summary.items() if k != "performance"}


@pytest.mark.skipif(cli_binary() is None, reason="ADHESIM_BIN is not set to a built `adhesim` binary")
@pytest.mark.parametrize(
    "name, overrides",
    [
        ("jkr.toml", {}),
        # a rolling run (reduced as in scripts/compare_outputs.sh): the translation path
        ("fig6.toml", {"grid.n": 32, "protocol.approach_steps": 20, "protocol.steps": 40}),
    ],
)
def test_run_is_bit_identical_to_the_command_line(tmp_path, name, overrides):
    """A scenario through `adhesim run` and through `adhesim.run` (scenarios/jkr.toml as
    it is: n = 128, 150 approach steps): the same curve.csv bytes, every column's values
    bit for bit, and the same summary.json apart from `performance` (timings)."""
    cli_out = tmp_path / "cli"
    sets = [arg for key, value in overrides.items() for arg in ("--set", f"{key}={value}")]
    subprocess.run(
        [str(cli_binary()), "run", str(REPO / "scenarios" / name), "--out", str(cli_out), "--quiet", *sets],
        check=True,
    )
    result = adhesim.run(REPO / "scenarios" / name, out=tmp_path / "py", overrides=overrides)
    cli_csv = (cli_out / "curve.csv").read_bytes()
    assert (tmp_path / "py" / "curve.csv").read_bytes() == cli_csv
    cli_curve = adhesim.load(cli_out).curve_arrays
    assert list(result.curve_arrays) == list(cli_curve)
    for column, values in cli_curve.items():
        assert same_bits(result.curve_arrays[column], values), column
    assert len(cli_curve["step"]) > 50
    cli_summary = json.loads((cli_out / "summary.json").read_text())
    assert without_performance(result.summary) == without_performance(cli_summary)
    assert result.summary["performance"].keys() == cli_summary["performance"].keys()
    assert result.summary == json.loads((tmp_path / "py" / "summary.json").read_text())


def test_dict_scenario_equals_its_toml_file():
    """The same scenario as a dict and as the TOML file gives identical curves and
    summaries (n = 32 overridden in both to keep it quick)."""
    from_file = adhesim.run(JKR_TOML, **SMALL)
    from_dict = adhesim.run(JKR_DICT, overrides=SMALL)
    assert list(from_dict.curve_arrays) == list(from_file.curve_arrays)
    for name, values in from_file.curve_arrays.items():
        assert same_bits(from_dict.curve_arrays[name], values), name
    assert without_performance(from_dict.summary) == without_performance(from_file.summary)
    # and as TOML text
    from_text = adhesim.run(JKR_TOML.read_text(), overrides=SMALL)
    assert same_bits(from_text.curve_arrays["force_normal"], from_file.curve_arrays["force_normal"])


def test_overrides_take_dotted_keys_like_set():
    result = adhesim.run(JKR_TOML, overrides={"grid.n": 32}, **{"protocol.steps": 20})
    assert result.summary["inputs"]["grid"]["n"] == 32
    assert result.summary["inputs"]["protocol"]["steps"] == 20
    assert result.curve_arrays["phase"][0] == "approach"
    assert result.curve_arrays["step"].dtype == np.int64
    assert result.curve_arrays["force_normal"].dtype == np.float64
    # the JKR run pulls off: some tensile force, and the normalised columns exist
    assert result.curve_arrays["force_norm"].min() < -0.5


@pytest.mark.parametrize(
    "scenario, overrides, names",
    [
        (JKR_TOML, {"indenter.radius": -1.0}, ["indenter.radius", "-1"]),
        (JKR_TOML, {"indenter.radiu": 1.0}, ["indenter.radiu"]),
        (JKR_TOML, {"grid.n": "many"}, ["grid.n", "many"]),
        ({**JKR_DICT, "indenter": {"shape": "sphere", "radius": -2.0}}, {}, ["indenter.radius", "-2"]),
        ({**JKR_DICT, "solver": {"tolerance": 1.0}}, {}, ["solver"]),
        ("[grid]\nn = 32\nsize = 0.25\n", {}, ["material"]),
    ],
)
def test_bad_input_raises_value_error_naming_the_key(scenario, overrides, names):
    with pytest.raises(ValueError) as error:
        adhesim.run(scenario, overrides=overrides)
    message = str(error.value)
    for name in names:
        assert name in message, message


def test_a_missing_scenario_file_is_file_not_found():
    """A missing file is a FileNotFoundError naming it (it was a ValueError)."""
    with pytest.raises(FileNotFoundError, match="no_such_file.toml"):
        adhesim.run("no_such_file.toml")


def test_bad_types_raise_type_error():
    with pytest.raises(TypeError, match="scenario must be"):
        adhesim.run(42)
    with pytest.raises(TypeError, match="grid.n"):
        adhesim.run(JKR_TOML, overrides={"grid.n": object()})
    with pytest.raises(TypeError, match="progress"):
        adhesim.run(JKR_TOML, progress="yes", **SMALL)


def test_progress_callback_sees_every_step_and_can_stop_the_run():
    calls = []
    result = adhesim.run(JKR_TOML, progress=lambda step, total: calls.append((step, total)), **SMALL)
    steps = len(result.curve_arrays["step"])
    assert [c[0] for c in calls] == list(range(1, steps + 1))
    assert all(total >= step for step, total in calls)

    def stop(step, total):
        if step == 5:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        adhesim.run(JKR_TOML, progress=stop, **SMALL)


def interrupt_with_sigint():
    """A real SIGINT to the main thread, as Ctrl-C in a terminal sends it."""
    signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)


@pytest.mark.parametrize("interrupt", [_thread.interrupt_main, interrupt_with_sigint])
def test_interrupt_stops_a_run(sigint_raises_keyboard_interrupt, interrupt):
    """_thread.interrupt_main() or a SIGINT from another thread (what Ctrl-C does) during
    a run of minutes (jkr.toml with 20 000 approach steps at n = 64) raises
    KeyboardInterrupt after the running step; the progress callback fails the test if
    that has not happened after 20 s."""
    start = time.monotonic()

    def give_up(step, total):
        if time.monotonic() - start > 20.0:
            raise RuntimeError(f"not interrupted after 20 s ({step} steps)")

    timer = threading.Timer(0.5, interrupt)
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            adhesim.run(JKR_TOML, progress=give_up, **{"grid.n": 64, "protocol.steps": 20000})
    finally:
        timer.cancel()
    assert time.monotonic() - start < 10.0


def test_snapshots_and_load_round_trip(tmp_path):
    """Snapshot steps of [output] come back as 2-D fields; a run written with out= reads
    back with load() as the same curve, summary and pressure/displacement fields."""
    result = adhesim.run(JKR_TOML, out=tmp_path, **SMALL, **{"output.snapshot_steps": [3, 15]})
    steps = snapshot_steps(result.curve_arrays, [3, 15], 20)
    assert [s.step for s in result.snapshots] == steps
    assert len(steps) >= 4  # the chosen two, the deepest, pull-off (the last in contact)
    snapshot = result.snapshots[1]
    assert snapshot.step == 15
    n = 32
    assert snapshot.pressure.shape == (n, n) and snapshot.contact.dtype == bool
    assert snapshot.depth == result.curve_arrays["d"][15]
    # the fields are those of the step: Δ²Σp is the step's force, the gap closes in contact
    dx = 0.25 / n
    assert dx * dx * snapshot.pressure.sum() == pytest.approx(result.curve_arrays["force_normal"][15], rel=1e-12)
    assert np.abs(snapshot.gap[snapshot.contact]).max() < 1e-6 * abs(snapshot.depth)
    assert snapshot.contact.sum() == result.curve_arrays["n_contact"][15]

    loaded = adhesim.load(tmp_path)
    for name, values in result.curve_arrays.items():
        assert same_bits(loaded.curve_arrays[name], values), name
    assert loaded.summary == result.summary
    # load() gives the same snapshots, every field bit for bit (read from fields.npz)
    assert [s.step for s in loaded.snapshots] == steps
    for mine, theirs in zip(result.snapshots, loaded.snapshots):
        assert (mine.depth, mine.offset) == (theirs.depth, theirs.offset)
        for name in ("pressure", "displacement", "gap", "contact"):
            assert same_bits(getattr(theirs, name), getattr(mine, name)), (mine.step, name)
    # and the .npy files of the chosen steps, as the command line writes them
    assert sorted(p.name for p in (tmp_path / "snapshots").iterdir()) == [
        f"step_{step:06d}_{name}.npy" for step in (3, 15) for name in ("displacement", "pressure")
    ]
    with pytest.raises(ValueError, match="curve.csv"):
        adhesim.load(tmp_path / "nothing")


def test_sweep_runs_every_case():
    cases = adhesim.sweep(JKR_TOML, vary={"adhesion.work_of_adhesion": [2e-5, 4e-5]}, **SMALL)
    assert [c.case for c in cases] == [{"adhesion.work_of_adhesion": 2e-5}, {"adhesion.work_of_adhesion": 4e-5}]
    single = adhesim.run(JKR_TOML, **SMALL, **{"adhesion.work_of_adhesion": 4e-5})
    assert same_bits(cases[1].curve_arrays["force_normal"], single.curve_arrays["force_normal"])
    table = adhesim.sweep_table(cases, "results.max_adhesive_force")
    # the pull-off force grows with γ (JKR: F ∝ γ)
    assert table["results.max_adhesive_force"][1] > 1.5 * table["results.max_adhesive_force"][0]
    with pytest.raises(ValueError, match=r"case 0 \(grid.n = -4\)"):
        adhesim.sweep(JKR_TOML, vary={"grid.n": [-4]})


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc/self/status")
def test_no_memory_growth_over_repeated_runs(resident_growth_kib):
    """100 small runs (n = 32, 5 approach steps, one snapshot each). After 10 warm-up
    runs the resident size may grow by at most 8 MiB. Each run allocates its operator
    (zero-padded 64 x 64 FFT buffers of 32-64 KiB each, plans, kernel spectrum), solver
    vectors, fields and result arrays, several hundred KiB in all, so leaking one run's
    allocations would add tens of MiB over 100 runs; 8 MiB leaves room for the
    allocator's and numpy's caches."""

    def once():
        result = adhesim.run(JKR_TOML, **{"grid.n": 32, "protocol.steps": 5, "output.snapshot_steps": [3]})
        return result.curve_arrays["force_normal"].sum()

    growth = resident_growth_kib(once, warm_up=10, repeats=100)
    assert growth < 8192, f"RSS grew by {growth} KiB over 100 runs"


def test_progress_true_draws_a_tqdm_bar_when_tqdm_is_there(capsys, monkeypatch):
    """progress=True: a tqdm bar on stderr where tqdm is importable, a warning that names
    tqdm otherwise; the results are the same either way."""
    plain = adhesim.run(JKR_TOML, **SMALL)
    try:
        import tqdm  # noqa: F401
    except ImportError:
        tqdm = None
    if tqdm is not None:
        with_bar = adhesim.run(JKR_TOML, progress=True, **SMALL)
        assert same_bits(with_bar.curve_arrays["force_normal"], plain.curve_arrays["force_normal"])
        assert "step" in capsys.readouterr().err
    # without tqdm (hidden from the import system here): a warning, the same results
    monkeypatch.setitem(sys.modules, "tqdm", None)
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    with pytest.warns(UserWarning, match="tqdm is not installed"):
        without = adhesim.run(JKR_TOML, progress=True, **SMALL)
    assert same_bits(without.curve_arrays["force_normal"], plain.curve_arrays["force_normal"])


def test_memory_guard_refuses_before_allocating(monkeypatch):
    """As on the command line, a scenario whose memory estimate exceeds the memory
    available (here stated as 1 MB through ADHESIM_MEMORY_AVAILABLE) is refused with a
    ValueError naming grid.n, not attempted (an allocation failure would abort the
    interpreter); allow_large=True runs it anyway."""
    monkeypatch.setenv("ADHESIM_MEMORY_AVAILABLE", str(1_000_000))
    with pytest.raises(ValueError, match=r"grid\.n = 128 .*allow_large=True"):
        adhesim.run(JKR_TOML)
    result = adhesim.run(JKR_TOML, allow_large=True, **SMALL)
    assert len(result.curve_arrays["step"]) > 20
    monkeypatch.setenv("ADHESIM_MEMORY_AVAILABLE", "lots")
    with pytest.raises(ValueError, match="ADHESIM_MEMORY_AVAILABLE"):
        adhesim.run(JKR_TOML, **SMALL)


def test_runs_in_threads_give_the_results_of_sequential_runs():
    """The GIL is released during a run: two runs in two threads proceed together and
    give the same bits as one after the other (each run owns its operator and state)."""
    cases = [{**SMALL, "adhesion.work_of_adhesion": gamma} for gamma in (2e-5, 4e-5)]
    sequential = [adhesim.run(JKR_TOML, overrides=case) for case in cases]
    threaded = [None, None]

    def work(k):
        threaded[k] = adhesim.run(JKR_TOML, overrides=cases[k])

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for one, other in zip(sequential, threaded):
        assert same_bits(one.curve_arrays["force_normal"], other.curve_arrays["force_normal"])


def test_out_folder_is_kept_as_the_command_line_keeps_it(tmp_path):
    """out= refuses a non-empty folder that is not a run folder (before running), unless
    force=True; rerunning into a run folder removes the previous run's snapshots, so
    load() never mixes two runs; the CLI accepts the folder as a run folder."""
    foreign = tmp_path / "notes"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("keep me")
    with pytest.raises(ValueError, match="not an adhesim run folder"):
        adhesim.run(JKR_TOML, out=foreign, **SMALL)
    assert not (foreign / "curve.csv").exists()
    adhesim.run(JKR_TOML, out=foreign, force=True, **SMALL)
    assert (foreign / "thesis.tex").read_text() == "keep me"

    folder = tmp_path / "run"
    first = adhesim.run(JKR_TOML, out=folder, **SMALL, **{"output.snapshot_steps": [3]})
    assert [s.step for s in adhesim.load(folder).snapshots] == snapshot_steps(first.curve_arrays, [3], 20)
    second = adhesim.run(JKR_TOML, out=folder, **SMALL)
    assert [s.step for s in adhesim.load(folder).snapshots] == snapshot_steps(second.curve_arrays, [], 20)
    assert 3 not in [s.step for s in adhesim.load(folder).snapshots]
    # The previous run's step-3 fields are gone (the folder is the Rust pipeline's, as the
    # command line's: snapshots/ holds this run's chosen steps only, here none).
    assert not list((folder / "snapshots").glob("*.npy"))
    assert (folder / ".adhesim-run").read_text().startswith("adhesim run folder\nresults_revision = ")
    if cli_binary() is not None:
        subprocess.run(
            [str(cli_binary()), "run", str(JKR_TOML), "--out", str(folder), "--quiet", "--set", "grid.n=32"],
            check=True,
        )


def test_sweep_on_a_thread_pool_gives_the_sequential_results():
    """An executor runs the cases (here two threads: the GIL is released during a case);
    the results come back in case order with the bits of the sequential sweep, and
    progress sees every case end."""
    from concurrent.futures import ThreadPoolExecutor

    vary = {"adhesion.work_of_adhesion": [2e-5, 3e-5, 4e-5]}
    sequential = adhesim.sweep(JKR_TOML, vary=vary, **SMALL)
    done = []
    with ThreadPoolExecutor(2) as pool:
        parallel = adhesim.sweep(JKR_TOML, vary=vary, executor=pool, progress=lambda d, t, c: done.append(d), **SMALL)
    assert [r.case for r in parallel] == [r.case for r in sequential]
    assert sorted(done) == [1, 2, 3]
    for one, other in zip(sequential, parallel):
        assert same_bits(one.curve_arrays["force_normal"], other.curve_arrays["force_normal"])


def test_relative_paths_resolve_against_the_scenario_folder(tmp_path, monkeypatch):
    """A height map named by a relative path in a scenario file is found next to the file
    whatever the working directory (as `adhesim run` does); the same text given as a
    string resolves against the working directory, and a missing map is a ValueError
    naming indenter.file. A dict may hold the path as a pathlib.Path."""
    folder = tmp_path / "study"
    folder.mkdir()
    n, size = 32, 0.25
    x = (np.arange(n) - n // 2) * (size / n)
    np.save(folder / "sphere.npy", (x[:, None] ** 2 + x[None, :] ** 2) / 2.0)  # R = 1
    text = f"""
[grid]
n = {n}
size = {size}
[material]
contact_modulus = 1.0
[adhesion]
work_of_adhesion = 0.0
[indenter]
shape = "topography"
file = "sphere.npy"
spacing = {size / n}
[protocol]
kind = "indent_pulloff"
max_depth = 0.002
steps = 5
"""
    (folder / "scenario.toml").write_text(text)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    result = adhesim.run(folder / "scenario.toml")
    assert result.curve_arrays["force_normal"].max() > 0
    with pytest.raises(ValueError, match="indenter.file"):
        adhesim.run(text)
    from_dict = adhesim.run(
        {
            "grid": {"n": n, "size": size},
            "material": {"contact_modulus": 1.0},
            "adhesion": {"work_of_adhesion": 0.0},
            "indenter": {"shape": "topography", "file": folder / "sphere.npy", "spacing": size / n},
            "protocol": {"kind": "indent_pulloff", "max_depth": 0.002, "steps": 5},
        }
    )
    assert same_bits(from_dict.curve_arrays["force_normal"], result.curve_arrays["force_normal"])


@pytest.mark.skipif(cli_binary() is None, reason="ADHESIM_BIN is not set to a built `adhesim` binary")
@pytest.mark.parametrize(
    "name, overrides",
    [
        ("jkr.toml", {"grid.n": 32, "protocol.steps": 20, "output.snapshot_steps": [3, 15]}),
        # a translation: the gap follows the moving profile, offsets are not 0
        ("fig6.toml", {"grid.n": 32, "protocol.approach_steps": 20, "protocol.steps": 40}),
    ],
)
def test_fields_npz_of_run_is_the_command_line_s(tmp_path, name, overrides):
    """adhesim.run(out=...) writes fields.npz with the same bytes as `adhesim run` (both
    through the scenario crate's SnapshotFields and adhesim_topography::write_npz), and
    load() of either folder gives run()'s snapshots, bit for bit."""
    cli_out = tmp_path / "cli"
    sets = [arg for key, value in overrides.items() for arg in ("--set", f"{key}={_toml(value)}")]
    subprocess.run(
        [str(cli_binary()), "run", str(REPO / "scenarios" / name), "--out", str(cli_out), "--quiet", *sets],
        check=True,
    )
    result = adhesim.run(REPO / "scenarios" / name, out=tmp_path / "py", overrides=overrides)
    assert (tmp_path / "py" / "fields.npz").read_bytes() == (cli_out / "fields.npz").read_bytes()
    loaded = adhesim.load(cli_out)
    assert [s.step for s in loaded.snapshots] == [s.step for s in result.snapshots]
    assert len(result.snapshots) >= 2
    for mine, theirs in zip(result.snapshots, loaded.snapshots):
        assert (mine.depth, mine.offset) == (theirs.depth, theirs.offset)
        for field in ("pressure", "displacement", "gap", "contact"):
            assert same_bits(getattr(theirs, field), getattr(mine, field)), (mine.step, field)


def _toml(value):
    """A --set value as TOML text."""
    return "[" + ", ".join(map(str, value)) + "]" if isinstance(value, list) else str(value)


@pytest.mark.skipif(cli_binary() is None, reason="ADHESIM_BIN is not set to a built `adhesim` binary")
def test_cli_fields_npz_follows_the_documented_contract(tmp_path):
    """The built-in default scenario (`adhesim` without a subcommand, the
    paper's Fig. 1 case) at n = 32 through the binary; its fields.npz read with plain
    numpy.load has the names, shapes and dtypes of docs/output.md, and each snapshot's
    Δ²·Σ pressure is the step's force_normal in curve.csv. Tolerance: relative 1e-12 of
    the largest |force_normal| (the CSV holds the force to 17 significant digits; the
    sums differ only by the order of float additions)."""
    out = tmp_path / "default"
    default = REPO / "scenarios" / "fig1.toml"
    subprocess.run(
        [str(cli_binary()), "run", str(default), "--out", str(out), "--quiet", "--set", "grid.n=32"], check=True
    )
    curve = adhesim.load(out).curve_arrays
    size = adhesim.load(out).summary["inputs"]["grid"]["size"]
    n = 32
    with np.load(out / "fields.npz") as npz:
        names = set(npz.files)
        for axis in ("x", "y"):
            assert npz[axis].shape == (n,) and npz[axis].dtype == np.float64
        assert npz["heights"].shape == (n, n) and npz["heights"].dtype == np.float64
        assert npz["surface"].shape == (n, n) and npz["surface"].dtype == np.bool_
        steps = npz["steps"]
        assert steps.dtype == np.float64 and steps.ndim == 1 and len(steps) >= 3
        assert np.all(np.diff(steps) > 0) and np.all(steps == np.round(steps))
        for name in ("depths", "offsets"):
            assert npz[name].shape == steps.shape and npz[name].dtype == np.float64
        per_step = {f"{f}_{int(s):06d}" for s in steps for f in ("pressure", "displacement", "gap", "contact")}
        stacked = {"step", "pressure", "displacement", "gap", "contact"}  # fields contract 2
        assert names == {"x", "y", "heights", "surface", "steps", "depths", "offsets"} | per_step | stacked
        assert npz["step"].dtype == np.int64 and np.array_equal(npz["step"], steps)
        for field in ("pressure", "displacement", "gap", "contact"):
            assert npz[field].shape == (len(steps), n, n)
            for k, step in enumerate(steps.astype(int)):
                assert np.array_equal(npz[field][k], npz[f"{field}_{step:06d}"])
        dx = size / n
        # element centres (j - N/2)·Δ, the same along y
        assert np.allclose(npz["x"], (np.arange(n) - n // 2) * dx, rtol=0, atol=1e-12 * size)
        assert np.array_equal(npz["y"], npz["x"])
        scale = np.abs(curve["force_normal"]).max()
        for k, step in enumerate(steps.astype(int)):
            for field in ("pressure", "displacement", "gap"):
                assert npz[f"{field}_{step:06d}"].shape == (n, n)
                assert npz[f"{field}_{step:06d}"].dtype == np.float64
            contact = npz[f"contact_{step:06d}"]
            assert contact.dtype == np.bool_ and contact.shape == (n, n)
            assert npz["depths"][k] == curve["d"][step]
            force = dx * dx * npz[f"pressure_{step:06d}"].sum()
            assert abs(force - curve["force_normal"][step]) <= 1e-12 * scale, (step, force)
            assert contact.sum() == curve["n_contact"][step]


def test_a_hold_with_aging_adhesion_reads_back_its_time_and_raises_the_pull_off():
    # scenarios/aging.toml on 64²: bonds aging as γ0(1 + t/t_ref)^0.0883 during a hold of
    # 10 min in 20 steps. The hold's rows carry phase "hold" and their time; the pull-off
    # force exceeds the unaged one by the aged factor (1 + 10/0.01)^0.0883 = 1.84 within 3 %
    # (the mesh's excess changes by 1.4Δ/a_JKR(1 − 1.84^(-1/3)) ≈ 1.7 % at a_JKR ≈ 16Δ, and
    # the lattice scatters the pull-off by ~1 %).
    toml = REPO / "scenarios" / "aging.toml"
    aged = adhesim.run(toml, overrides={"grid.n": 64})
    hold = aged.curve[aged.curve["phase"] == "hold"]
    assert len(hold) == 20
    assert abs(float(hold["time"].iloc[-1]) - 10.0) < 1e-12
    fresh = adhesim.run(toml, overrides={"grid.n": 64, "protocol.hold_time": 1e-9, "protocol.time_step": 1e-9})
    ratio = aged.summary["results"]["max_adhesive_force"] / fresh.summary["results"]["max_adhesive_force"]
    assert abs(ratio / (1 + 10 / 0.01) ** 0.0883 - 1) < 0.03, ratio
