"""One-call runs of a scenario: ``run``, ``load``, ``sweep``.

A scenario is the TOML file of the command line (docs/cli.md), given as a path, as TOML
text, or as a nested dict with the same keys. ``run`` goes through the same Rust code as
``adhesim run`` (reading, ``--set`` overrides, validation, the run pipeline, the
``curve.csv`` columns and the ``summary.json`` content), so its curve is bit-identical to
the command line's.
"""

from __future__ import annotations

import csv
import itertools
import json
import os
import re
import threading
import warnings
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Union

import numpy as np

from . import _adhesim

__all__ = ["RunResult", "Snapshot", "run", "load", "sweep"]

ScenarioLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]


class Snapshot:
    """The contact fields of one step, float64 (n, n) arrays indexed [row = y, column = x].

    The fields are those of ``fields.npz`` (docs/output.md): ``run`` and ``load`` give the
    same snapshots for the same run.

    Attributes:
        step: step number (0-based, as in curve.csv).
        depth: indentation depth d of the step (> 0 into the body).
        offset: lateral position X of the indenter axis (0 for indentation).
        pressure: p (> 0 compressive, < 0 tensile).
        displacement: u (> 0 into the body).
        gap: g = u + z - d (0 in contact, > 0 outside; 0 where the indenter has no
            surface); None only when read back from an old run folder without
            ``fields.npz``.
        contact: bool (n, n) contact mask; None as ``gap``.
    """

    def __init__(self, step, depth, pressure, displacement, gap=None, contact=None, offset=0.0):
        self.step = int(step)
        self.depth = float(depth)
        self.offset = float(offset)
        self.pressure = pressure
        self.displacement = displacement
        self.gap = gap
        self.contact = contact

    def __repr__(self) -> str:
        n = self.pressure.shape[0]
        return f"Snapshot(step={self.step}, depth={self.depth:.6g}, fields {n}x{n})"


class RunResult:
    """What ``run`` and ``load`` return.

    Attributes:
        curve_arrays: dict of 1-D numpy arrays, one per ``curve.csv`` column with exactly
            its name (docs/cli.md): int64 counts and flags, float64 quantities, str phase.
        curve: a pandas DataFrame of the same columns when pandas is importable, else
            ``curve_arrays``.
        summary: dict equal to the content of ``summary.json`` (inputs, derived, results,
            performance, warnings).
        snapshots: list of ``Snapshot`` of the snapshot steps, by step: the steps the
            scenario's ``[output]`` chooses (``snapshot_steps``, ``snapshot_every``; for a
            translation by default the end of the forward stroke), the deepest step, the
            last step in contact and the step of the largest contact, each once (the
            steps of ``fields.npz``, docs/output.md).
        out: the folder the files were written to, or None.
    """

    def __init__(self, curve_arrays, summary, snapshots, out=None):
        self.curve_arrays: Dict[str, np.ndarray] = curve_arrays
        self.summary: Dict[str, Any] = summary
        self.snapshots: List[Snapshot] = snapshots
        self.out: Optional[Path] = out

    @property
    def curve(self):
        """The curve as a pandas DataFrame when pandas is importable, else ``curve_arrays``."""
        try:
            import pandas
        except ImportError:
            return self.curve_arrays
        return pandas.DataFrame(self.curve_arrays)

    @property
    def results(self) -> Dict[str, Any]:
        """``summary["results"]``: max adhesive force, γ1, γ2, ... (docs/output.md)."""
        return self.summary["results"]

    def __repr__(self) -> str:
        steps = len(next(iter(self.curve_arrays.values()))) if self.curve_arrays else 0
        where = f", out={str(self.out)!r}" if self.out is not None else ""
        return f"RunResult({steps} steps, {len(self.snapshots)} snapshots{where})"


def _plain(value):
    """Paths (os.PathLike) as str, inside dicts and lists too: TOML has no path type."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, Mapping):
        return {key: _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    return value


def _scenario_text(scenario: ScenarioLike):
    """(TOML text, origin for messages, base folder of relative paths)."""
    if isinstance(scenario, Mapping):
        return _adhesim._toml_document(_plain(dict(scenario))), "scenario dict", Path.cwd()
    if isinstance(scenario, os.PathLike) or (
        isinstance(scenario, str)
        and (os.path.isfile(scenario) or ("\n" not in scenario and "=" not in scenario))
    ):
        path = Path(scenario)
        try:
            text = path.read_text()
        except OSError as error:
            raise ValueError(f"cannot read scenario {path}: {error.strerror or error}") from None
        # Relative paths inside the file resolve against its folder, as the command line's.
        return text, str(path), path.parent if str(path.parent) else Path(".")
    if isinstance(scenario, str):
        return scenario, "scenario text", Path.cwd()
    raise TypeError(
        f"scenario must be a path, a TOML string or a dict, got {type(scenario).__name__}"
    )


def _check_overrides(overrides: Any) -> None:
    """TypeError naming ``overrides`` unless it is None or a mapping (a string such as
    ``"grid.n=32"`` failed inside ``dict()`` with a message naming no argument)."""
    if overrides is not None and not isinstance(overrides, Mapping):
        raise TypeError(
            f"overrides must be a mapping of dotted keys to values like {{'grid.n': 32}}, "
            f"got {type(overrides).__name__} {overrides!r}"
        )


def _override_items(overrides: Optional[Mapping[str, Any]], keywords: Mapping[str, Any]):
    """``KEY=VALUE`` items as ``--set`` takes them (VALUE as TOML text)."""
    _check_overrides(overrides)
    merged = dict(overrides or {})
    merged.update(keywords)
    items = []
    for key, value in merged.items():
        if not isinstance(key, str):
            raise TypeError(f"override keys must be str like 'grid.n', got {key!r}")
        try:
            items.append(f"{key}={_adhesim._toml_value(_plain(value))}")
        except (TypeError, ValueError) as error:
            raise type(error)(f"override {key}: {error}") from None
    return items


def _progress_callback(progress):
    """(callback for the run, bar to close afterwards)."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            warnings.warn(
                "progress=True draws a tqdm bar, but tqdm is not installed "
                "(pip install tqdm, or the package's [extras]); running without a bar",
                stacklevel=3,
            )
            return None, None
        bar = tqdm(total=0, unit="step")

        def update(step, total):
            if bar.total != total:
                bar.total = total
            bar.update(step - bar.n)

        return update, bar
    if callable(progress):
        return progress, None
    raise TypeError(f"progress must be None, True or a callable(step, total), got {progress!r}")


# The run folder's marker and outputs, as the command line keeps them
# (crates/adhesim-cli/src/commands/folder.rs): a folder that is not empty must hold the
# marker, and the previous run's outputs are removed before the new ones are written.
RUN_MARKER = ".adhesim-run"
RUN_OUTPUTS = (
    "curve.csv",
    "curve.csv.partial",
    "summary.json",
    "plots",
    "snapshots",
    "fields.npz",
    "fields.npz.partial",
    "fields.nc",
    "fields.nc.partial",
)


def _check_run_folder(out: Path, force: bool):
    """Refuses, before the run, a non-empty folder that is not a run folder."""
    if out.exists() and not out.is_dir():
        raise ValueError(f"out={str(out)!r} exists and is not a folder")
    if out.is_dir() and any(out.iterdir()) and not (out / RUN_MARKER).is_file() and not force:
        raise ValueError(
            f"output folder {out} is not empty and is not an adhesim run folder (no {RUN_MARKER}); "
            "choose another out, or pass force=True to write into it (its curve.csv, summary.json, "
            "plots/ and snapshots/ are then replaced)"
        )


def _write_outputs(out: Path, columns_csv: str, summary_json: str, raw_snapshots, fields):
    """The run marker, curve.csv, summary.json, fields.npz (the command line's bytes) and
    snapshots/step_*_{pressure,displacement}.npy of the chosen steps, each written to a
    temporary name and renamed (a file is always whole), after removing the previous
    run's outputs."""
    import shutil

    out.mkdir(parents=True, exist_ok=True)
    for name in RUN_OUTPUTS:
        path = out / name
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif path.exists() or path.is_symlink():
            path.unlink()
    version = json.loads(summary_json)["adhesim_version"]
    (out / RUN_MARKER).write_text(
        f"adhesim run folder\nresults_revision = {_adhesim.RESULTS_REVISION}\nadhesim_version = {version}\n"
    )

    def atomic(path: Path, write: Callable[[Any], None], mode: str):
        partial = path.with_name(path.name + ".partial")
        with open(partial, mode) as handle:
            write(handle)
        os.replace(partial, path)

    atomic(out / "curve.csv", lambda f: f.write(columns_csv), "w")
    atomic(out / "summary.json", lambda f: f.write(summary_json), "w")
    npz_partial = out / "fields.npz.partial"
    fields.write_npz(str(npz_partial))
    os.replace(npz_partial, out / "fields.npz")
    chosen = [s for s in raw_snapshots if s["chosen"]]
    if chosen:
        folder = out / "snapshots"
        folder.mkdir(exist_ok=True)
        for s in chosen:
            for name in ("pressure", "displacement"):
                array = s[name]
                atomic(folder / f"step_{s['step']:06d}_{name}.npy", lambda f: np.save(f, array), "wb")


def run(
    scenario: ScenarioLike,
    out: Union[str, "os.PathLike[str]", None] = None,
    progress: Union[bool, Callable[[int, int], Any], None] = None,
    overrides: Optional[Mapping[str, Any]] = None,
    allow_large: bool = False,
    force: bool = False,
    **keyword_overrides: Any,
) -> RunResult:
    """Runs a scenario as ``adhesim run`` does and returns its results in memory.

    Args:
        scenario: a path to a scenario TOML file (relative paths inside it, such as height
            maps, resolve against its folder), a TOML string, or a nested dict with the
            file's keys (``{"grid": {"n": 64, ...}, ...}``; relative paths then resolve
            against the working directory).
        out: optional folder to write ``curve.csv`` and ``summary.json`` into (the same
            bytes as the command line's, apart from the timings under ``performance``),
            ``fields.npz`` (the command line's bytes) and the ``.npy`` fields of the
            chosen snapshot steps (``snapshots/step_NNNNNN_{pressure,displacement}.npy``).
            ``fields.nc``, figures and the
            contact-map PNGs are the command line's only. As with ``adhesim run --out``,
            the folder must be new, empty or a run folder (it gets the ``.adhesim-run``
            marker; the previous run's outputs are removed first).
        progress: None; a callable ``progress(step, total)`` called after each step
            (``total`` is an estimate for indentations: approach steps + as many
            retraction steps); or True for a tqdm bar when tqdm is installed.
        overrides: dict of dotted keys to values, like ``--set`` (``{"grid.n": 64}``).
        allow_large: run even when the memory estimate of the grid exceeds the memory
            available (the smallest of RLIMIT_AS, the cgroup's ``memory.max`` and
            ``MemAvailable``, or ``ADHESIM_MEMORY_AVAILABLE``),
            like the command line's ``--allow-large``; by default such a scenario is
            refused with a ValueError before anything is allocated.
        force: write into a non-empty ``out`` that is not a run folder (its outputs are
            replaced), like ``--force``.
        **keyword_overrides: more overrides; dotted keys need ``**{"grid.n": 64}``.

    Returns:
        RunResult with ``.curve``, ``.curve_arrays``, ``.summary``, ``.snapshots``.

    Raises:
        ValueError: an unreadable file or a bad value, naming the key and the value
            (the scenario crate's messages, as the command line prints them).
        TypeError: a scenario or override value of an unsupported type.
        KeyboardInterrupt: Ctrl-C, checked between steps (a step itself runs to its end:
            the library has no cancellation hook inside a step).
        adhesim.SolveError: a solver did not converge.

    The GIL is released during the run, except for the signal check and the progress
    callback between steps.
    """
    text, origin, base = _scenario_text(scenario)
    items = _override_items(overrides, keyword_overrides)
    if out is not None:
        _check_run_folder(Path(out), force)
    callback, bar = _progress_callback(progress)
    try:
        raw = _adhesim._run_scenario(text, origin, str(base), items, callback, not allow_large)
    finally:
        if bar is not None:
            bar.close()
    curve = {name: array for name, array in raw["columns"]}
    snapshots = [
        Snapshot(s["step"], s["depth"], s["pressure"], s["displacement"], s["gap"], s["contact"], s["offset"])
        for s in raw["snapshots"]
    ]
    folder = None
    if out is not None:
        folder = Path(out)
        _write_outputs(folder, raw["csv"], raw["summary"], raw["snapshots"], raw["fields"])
    return RunResult(curve, json.loads(raw["summary"]), snapshots, folder)


def _read_curve(path: Path) -> Dict[str, np.ndarray]:
    kinds = _adhesim._curve_column_kinds()
    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    if not rows:
        raise ValueError(f"{path} is empty (no header)")
    header, body = rows[0], rows[1:]
    curve = {}
    for k, name in enumerate(header):
        kind = kinds.get(name, "float")
        cells = [row[k] for row in body]
        try:
            if kind == "str":
                curve[name] = np.array(cells, dtype=str)
            elif kind == "int":
                curve[name] = np.array([int(c) for c in cells], dtype=np.int64)
            else:
                curve[name] = np.array([float(c) for c in cells], dtype=np.float64)
        except (ValueError, IndexError) as error:
            raise ValueError(f"{path}: column {name}: {error}") from None
    return curve


_NPY_FIELD = re.compile(r"step_(\d+)_(pressure|displacement)\.npy$")


def _read_fields_npz(path: Path) -> List[Snapshot]:
    """The snapshots of a ``fields.npz`` (docs/output.md): ``steps``, ``depths``,
    ``offsets`` and per step ``{pressure,displacement,gap,contact}_SSSSSS``."""
    snapshots = []
    with np.load(path) as archive:
        try:
            steps, depths, offsets = (archive[name] for name in ("steps", "depths", "offsets"))
            for step, depth, offset in zip(steps, depths, offsets):
                step = int(step)
                fields = [archive[f"{name}_{step:06d}"] for name in ("pressure", "displacement", "gap", "contact")]
                snapshots.append(Snapshot(step, depth, *fields[:3], fields[3].astype(bool), offset))
        except KeyError as error:
            raise ValueError(f"{path}: no array {error} (see docs/output.md, fields.npz)") from None
    return snapshots


def _read_snapshots(folder: Path, curve: Dict[str, np.ndarray]) -> List[Snapshot]:
    """fields.npz when there is one; else (a folder of an older adhesim) the ``.npy``
    pressure and displacement of the chosen steps."""
    npz = folder / "fields.npz"
    if npz.is_file():
        return _read_fields_npz(npz)
    fields: Dict[int, Dict[str, np.ndarray]] = {}
    for path in sorted(folder.glob("snapshots/step_*.npy")):
        match = _NPY_FIELD.search(path.name)
        if match:
            fields.setdefault(int(match[1]), {})[match[2]] = np.load(path)
    depths = dict(zip(curve.get("step", []), curve.get("d", [])))
    offsets = dict(zip(curve.get("step", []), curve.get("x", [])))
    return [
        Snapshot(step, depths.get(step, float("nan")), f["pressure"], f["displacement"],
                 offset=offsets.get(step, 0.0))
        for step, f in sorted(fields.items())
        if "pressure" in f and "displacement" in f
    ]


def load(folder: Union[str, "os.PathLike[str]"]) -> RunResult:
    """Reads a finished run folder (of ``adhesim run`` or ``run(..., out=...)``) back.

    Args:
        folder: the run folder, holding ``curve.csv`` and ``summary.json``.

    Returns:
        RunResult: the curve with the same column kinds as ``run`` gives, the summary,
        and the snapshots of ``fields.npz`` (docs/output.md: the same steps and fields
        as ``run`` gives); in a folder without ``fields.npz`` (an older adhesim), the
        chosen steps' ``snapshots/step_NNNNNN_{pressure,displacement}.npy`` (gap and
        contact None).

    Raises:
        ValueError: a missing or unreadable ``curve.csv`` / ``summary.json``, or a
            ``fields.npz`` without an array of the contract, naming it.
    """
    folder = Path(folder)
    curve_path, summary_path = folder / "curve.csv", folder / "summary.json"
    for path in (curve_path, summary_path):
        if not path.is_file():
            raise ValueError(f"{path} does not exist: {folder} is not a finished run folder")
    curve = _read_curve(curve_path)
    try:
        summary = json.loads(summary_path.read_text())
    except json.JSONDecodeError as error:
        raise ValueError(f"{summary_path}: {error}") from None
    return RunResult(curve, summary, _read_snapshots(folder, curve), folder)


class _Stopped(Exception):
    """Raised inside a case's run (through its progress callback) when the sweep stops."""


def sweep(
    scenario: ScenarioLike,
    vary: Mapping[str, Iterable[Any]],
    out: Union[str, "os.PathLike[str]", None] = None,
    progress: Union[Callable[[int, int, Dict[str, Any]], Any], None] = None,
    overrides: Optional[Mapping[str, Any]] = None,
    allow_large: bool = False,
    jobs: int = 1,
    **keyword_overrides: Any,
) -> List[RunResult]:
    """Runs a scenario for every combination of the values in ``vary``.

    Each case is ``run(scenario, overrides=common | case)``: the cases are the Cartesian
    product of the lists in ``vary`` (dotted keys, in the dict's order, the last key
    varying fastest). With ``jobs=1`` they run one after another (each case already uses
    every core for its FFTs); ``jobs > 1`` runs that many cases at once in threads (the
    GIL is released during a run; worth it for many small grids). The results are the
    same bits either way. Resumable case folders, sampling and shards are the command
    line's ``adhesim sweep``.

    Args:
        scenario: as for ``run``.
        vary: dict of dotted key -> list of values, e.g. ``{"adhesion.work_of_adhesion":
            [1e-5, 2e-5], "grid.n": [64, 128]}``.
        out: optional folder; case k is written into ``out/case_KKKK/`` as ``run`` does.
        progress: optional callable ``progress(done, total, case)`` after each case
            (in the calling thread).
        overrides, allow_large, **keyword_overrides: as for ``run``, the same for every case.
        jobs: cases run at once (>= 1).

    Returns:
        list of RunResult in case order; ``result.case`` holds the case's overrides.
        ``adhesim.sweep_table(results, "results.gamma_pulloff")`` makes columns of them.

    Raises:
        TypeError: ``vary`` not a mapping of dotted keys to lists, ``overrides`` not a
            mapping.
        ValueError: an empty ``vary``, a bad ``jobs`` or a bad case (the message names the
            case); the first failing case stops the sweep.
        KeyboardInterrupt: Ctrl-C; with ``jobs > 1`` the running cases stop at their
            next step.
    """
    if not isinstance(vary, Mapping):
        raise TypeError(
            "vary must be a mapping of dotted keys to lists of values like "
            f"{{'grid.n': [32, 64]}}, got {type(vary).__name__} {vary!r}"
        )
    if not vary:
        raise ValueError("vary must name at least one key with a list of values")
    if not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be an integer >= 1, got {jobs!r}")
    _check_overrides(overrides)
    keys = list(vary)
    for key in keys:
        # A string is iterable but is one value, not a list of them.
        if not isinstance(key, str):
            raise TypeError(f"vary keys must be dotted keys (str) like 'grid.n', got {key!r}")
        if isinstance(vary[key], (str, bytes, Mapping)) or not isinstance(vary[key], Iterable):
            raise TypeError(f"vary[{key!r}] must be a list of values, got {type(vary[key]).__name__} {vary[key]!r}")
    values = [list(vary[key]) for key in keys]
    for key, options in zip(keys, values):
        if not options:
            raise ValueError(f"vary[{key!r}] is empty")
    cases = [dict(zip(keys, combo)) for combo in itertools.product(*values)]
    common = dict(overrides or {})
    common.update(keyword_overrides)
    stop = threading.Event()

    def stop_when_asked(step, total):
        if stop.is_set():
            raise _Stopped()

    def one(k):
        folder = None if out is None else Path(out) / f"case_{k:04d}"
        # In a worker thread, the signal check of run() cannot see Ctrl-C: the main
        # thread sets `stop` instead and this callback ends the case at its next step.
        watch = stop_when_asked if jobs > 1 else None
        try:
            result = run(scenario, out=folder, progress=watch, overrides={**common, **cases[k]},
                         allow_large=allow_large)
        except ValueError as error:
            raise ValueError(f"sweep case {k} {cases[k]}: {error}") from None
        result.case = cases[k]
        return result

    results: List[Optional[RunResult]] = [None] * len(cases)
    if jobs == 1:
        for k in range(len(cases)):
            results[k] = one(k)
            if progress is not None:
                progress(k + 1, len(cases), cases[k])
        return results
    from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait

    pool = ThreadPoolExecutor(max_workers=jobs)
    pending = {pool.submit(one, k): k for k in range(len(cases))}
    try:
        while pending:
            finished, _ = wait(pending, timeout=0.1, return_when=FIRST_COMPLETED)
            for future in finished:
                k = pending.pop(future)
                results[k] = future.result()
                if progress is not None:
                    progress(sum(r is not None for r in results), len(cases), cases[k])
    except BaseException:
        stop.set()
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    pool.shutdown()
    return results


def sweep_table(results: List[RunResult], *columns: str) -> Dict[str, np.ndarray]:
    """A table (dict of 1-D arrays) of sweep results: the varied keys and the requested
    summary entries given as dotted paths (``"results.gamma_pulloff"``,
    ``"derived.johnson_parameter"``); a null (None) entry becomes NaN."""
    table: Dict[str, np.ndarray] = {}
    keys = list(getattr(results[0], "case", {})) if results else []
    for key in keys:
        table[key] = np.array([r.case[key] for r in results])
    for column in columns:
        values = []
        for r in results:
            value: Any = r.summary
            for part in column.split("."):
                if not isinstance(value, dict) or part not in value:
                    raise KeyError(f"{column}: summary has no {part!r}")
                value = value[part]
            values.append(np.nan if value is None else value)
        table[column] = np.array(values)
    return table
