"""One-call runs of a scenario: ``run``, ``load`` (``sweep`` is ``_sweep.py``).

A scenario is the TOML file of the command line (docs/cli.md), given as a path, as TOML
text, or as a nested dict with the same keys. ``run`` goes through the same Rust code as
``adhesim run`` (reading, ``--set`` overrides, validation, the run pipeline, the
``curve.csv`` columns and the ``summary.json`` content), so its curve is bit-identical to
the command line's.
"""

from __future__ import annotations

import csv
import json
import os
import re
import sys
import warnings
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Union

import numpy as np

from . import _adhesim, _display

__all__ = ["RunResult", "Snapshot", "run", "load", "sweep_table"]

ScenarioLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]


def _read_only(array):
    """``array`` as a numpy array with ``flags.writeable`` False (None stays None)."""
    if array is None:
        return None
    array = np.asarray(array)
    array.flags.writeable = False
    return array


class Snapshot:
    """The contact fields of one step, float64 (n, n) arrays indexed [row = y, column = x].

    The arrays are read-only (``flags.writeable`` is False; ``numpy.array(field)`` makes a
    writeable copy), and each access returns the same array.

    The fields are those of ``fields.npz`` (docs/output.md): ``run`` and ``load`` give the
    same snapshots for the same run.

    Attributes
    ----------
    step : int
        step number (0-based, as in curve.csv).
    depth : float
        indentation depth d of the step (> 0 into the body).
    offset : float
        lateral position X of the indenter axis (0 for indentation).
    pressure : numpy.ndarray
        p (> 0 compressive, < 0 tensile).
    displacement : numpy.ndarray
        u (> 0 into the body).
    gap : numpy.ndarray or None
        g = u + z - d (0 in contact, > 0 outside; 0 where the indenter has no
        surface); None only when read back from an old run folder without
        ``fields.npz``.
    contact : numpy.ndarray or None
        bool (n, n) contact mask; None as ``gap``.
    """

    def __init__(self, step, depth, pressure, displacement, gap=None, contact=None, offset=0.0):
        self.step = int(step)
        self.depth = float(depth)
        self.offset = float(offset)
        self.pressure = _read_only(pressure)
        self.displacement = _read_only(displacement)
        self.gap = _read_only(gap)
        self.contact = _read_only(contact)

    def __repr__(self) -> str:
        ny, nx = self.pressure.shape
        return (
            f"Snapshot(step={self.step}, depth={self.depth:.6g}, offset={self.offset:.6g}, "
            f"fields={ny}x{nx})"
        )


class RunResult:
    """What ``run`` and ``load`` return.

    Its arrays (the ``curve_arrays`` columns, the snapshots' fields) are read-only and the
    same objects at every access.

    Attributes
    ----------
    curve_arrays : dict of str to numpy.ndarray
        dict of 1-D numpy arrays, one per ``curve.csv`` column with exactly
        its name (docs/cli.md): int64 counts and flags, float64 quantities, str phase.
    curve : pandas.DataFrame or dict
        a pandas DataFrame of the same columns when pandas is importable, else
        ``curve_arrays``.
    summary : dict
        dict equal to the content of ``summary.json`` (inputs, derived, results,
        performance, warnings).
    snapshots : list of Snapshot
        list of ``Snapshot`` of the snapshot steps, by step: the steps the
        scenario's ``[output]`` chooses (``snapshot_steps``, ``snapshot_every``; for a
        translation by default the end of the forward stroke), the deepest step, the
        last step in contact and the step of the largest contact, each once (the
        steps of ``fields.npz``, docs/output.md).
    out : pathlib.Path or None
        the folder the files were written to, or None.
    """

    # Set by ``adhesim.sweep`` on each case's result only: the varied keys with their
    # values, and the case's folder name under ``cases/``.
    case: Dict[str, Any]
    case_id: str

    def __init__(self, curve_arrays, summary, snapshots, out=None):
        self.curve_arrays: Dict[str, np.ndarray] = {
            name: _read_only(column) for name, column in curve_arrays.items()
        }
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
        """The run's grid, steps, snapshots, folder and headline results (those of
        ``_repr_html_``'s table, not None) in one line."""
        rows = dict(_display.summary_rows(self))
        parts = [f"grid={rows.pop('grid')!r}"] if "grid" in rows else []
        parts += [f"steps={rows.pop('steps')}", f"snapshots={rows.pop('snapshots')}"]
        if "out" in rows:
            parts.append(f"out={rows.pop('out')!r}")
        rows.pop("wall_seconds", None)
        parts += [f"{name}={value}" for name, value in rows.items()]
        return f"RunResult({', '.join(parts)})"

    def to_xarray(self):
        """The snapshots as an ``xarray.Dataset``, laid out as ``fields.nc`` (docs/output.md).

        Returns
        -------
        xarray.Dataset
            ``pressure``, ``displacement``, ``gap`` and ``contact`` on the dimensions
            ``(step, y, x)``; the coordinates ``step`` (int64 step numbers), ``x``, ``y``
            (element centres relative to the indenter axis, the scenario's length unit) and
            ``depth``, ``offset`` on ``step``. ``ds.pressure.sel(step=3)`` is the pressure
            of step 3.

        Raises
        ------
        ImportError
            xarray is not installed (``pip install xarray``).
        ValueError
            the element centres are unknown: no grid in ``summary["inputs"]`` and no
            ``fields.npz`` in ``out``.
        """
        try:
            import xarray
        except ImportError:
            raise ImportError(
                "RunResult.to_xarray needs xarray, which is not installed: pip install xarray"
            ) from None
        x, y = _centres(self)
        dims = ("step", "y", "x")
        fields = {}
        for kind in ("pressure", "displacement", "gap", "contact"):
            layers = [getattr(s, kind) for s in self.snapshots]
            if any(layer is None for layer in layers):
                continue
            stacked = np.stack(layers) if layers else np.zeros((0, y.size, x.size))
            unit = {"pressure": "pressure", "contact": None}.get(kind, "length")
            fields[kind] = xarray.Variable(dims, stacked, {"units": unit} if unit else {})
        coords = {
            "step": ("step", np.array([s.step for s in self.snapshots], dtype=np.int64)),
            "x": ("x", x, {"units": "length", "axis": "X"}),
            "y": ("y", y, {"units": "length", "axis": "Y"}),
            "depth": ("step", np.array([s.depth for s in self.snapshots]), {"units": "length"}),
            "offset": ("step", np.array([s.offset for s in self.snapshots]), {"units": "length"}),
        }
        attrs = {"Conventions": "CF-1.8", "title": "adhesim contact fields",
                 "results_revision": str(_adhesim.RESULTS_REVISION)}
        return xarray.Dataset(fields, coords=coords, attrs=attrs)

    def _repr_html_(self) -> str:
        """A notebook's display: a table of the grid, steps, snapshots, folder and key
        results, and the force curve F(d) as an inline PNG when matplotlib is importable."""
        return _display.run_result_html(self)


def _centres(result: RunResult):
    """The element centres (x, y) of ``result``'s grid: ``fields.npz``'s ``x``, ``y`` when
    ``out`` has one, else (j - Nx//2)·Δx, (i - Ny//2)·Δy from ``summary["inputs"]["grid"]``."""
    npz = None if result.out is None else Path(result.out) / "fields.npz"
    if npz is not None and npz.is_file():
        with np.load(npz) as archive:
            return np.array(archive["x"]), np.array(archive["y"])
    grid = result.summary.get("inputs", {}).get("grid", {})
    if "n" not in grid or "size" not in grid:
        raise ValueError("to_xarray: the grid is unknown (no summary['inputs']['grid'], no fields.npz)")
    n, size = grid["n"], grid["size"]
    nx, ny = (n, n) if isinstance(n, int) else n
    sx, sy = (size, size) if isinstance(size, (int, float)) else size
    x = (np.arange(nx) - nx // 2) * (sx / nx)
    y = (np.arange(ny) - ny // 2) * (sy / ny)
    return x, y


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
        # Read as the command line reads it: a FIFO, a device or a folder is refused by
        # name (a FIFO blocked forever); a missing file is a FileNotFoundError.
        text = _adhesim._read_input_text(str(path), "scenario")
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


def _check_threads(threads: Optional[int]) -> Optional[int]:
    """The thread count to pass on: None (the default pool), or an integer >= 1; anything
    else is refused by name. A count beyond what a machine word holds is clamped here to
    the cores this process may use, with the warning the run gives any count above them
    (naming the count given, which the run could not receive)."""
    if threads is None:
        return None
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
        raise ValueError(f"threads must be an integer >= 1, got {threads!r}")
    if threads > sys.maxsize:
        cores = _cores()
        warnings.warn(
            f"threads = {threads} exceeds the {cores} cores this process may use; using {cores}",
            UserWarning,
            stacklevel=3,
        )
        return cores
    return threads


def _cores() -> int:
    """The cores this process may run on (its affinity where the system has one)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def run(
    scenario: ScenarioLike,
    out: Union[str, "os.PathLike[str]", None] = None,
    progress: Union[bool, Callable[[int, int], Any], None] = None,
    overrides: Optional[Mapping[str, Any]] = None,
    allow_large: bool = False,
    force: bool = False,
    threads: Optional[int] = None,
    **keyword_overrides: Any,
) -> RunResult:
    """Runs a scenario as ``adhesim run`` does and returns its results in memory.

    Parameters
    ----------
    scenario : str, os.PathLike or dict
        a path to a scenario TOML file (relative paths inside it, such as height
        maps, resolve against its folder), a TOML string, or a nested dict with the
        file's keys (``{"grid": {"n": 64, ...}, ...}``; relative paths then resolve
        against the working directory).
    out : str or os.PathLike, optional
        optional folder to write ``curve.csv`` and ``summary.json`` into (the same
        bytes as the command line's, apart from the timings under ``performance``),
        ``fields.npz`` (the command line's bytes) and the ``.npy`` fields of the
        chosen snapshot steps (``snapshots/step_NNNNNN_{pressure,displacement}.npy``).
        ``fields.nc``, figures and the
        contact-map PNGs are the command line's only. As with ``adhesim run --out``,
        the folder must be new, empty or a run folder (it gets the ``.adhesim-run``
        marker; the previous run's outputs are removed first).
    progress : bool or callable, optional
        None; a callable ``progress(step, total)`` called after each step
        (``total`` is an estimate for indentations: approach steps + as many
        retraction steps); or True for a tqdm bar when tqdm is installed.
    overrides : dict, optional
        dict of dotted keys to values, like ``--set`` (``{"grid.n": 64}``).
    allow_large : bool
        run even when the memory estimate of the grid exceeds the memory
        available (the smallest of RLIMIT_AS, the cgroup's ``memory.max`` and
        ``MemAvailable``, or ``ADHESIM_MEMORY_AVAILABLE``),
        like the command line's ``--allow-large``; by default such a scenario is
        refused with a ValueError before anything is allocated. The address-space
        limit RLIMIT_AS, which nothing gets past, is checked even so.
    force : bool
        write into a non-empty ``out`` that is not a run folder (its outputs are
        replaced), like ``--force``.
    threads : int, optional
        threads of the run's own pool, like ``--threads`` (more than the cores this
        process may use are clamped to them with a ``UserWarning``); by default the
        cores. The results are the same bits for every count. The pool is the run's,
        not a global one, so a run in a fork-started worker process (a
        ``ProcessPoolExecutor`` on Linux) after one in its parent does not wait forever
        for the parent's threads.
    **keyword_overrides
        more overrides; dotted keys need ``**{"grid.n": 64}``.

    Returns
    -------
    RunResult
        With ``.curve``, ``.curve_arrays``, ``.summary``, ``.snapshots``.

    Raises
    ------
    FileNotFoundError
        the scenario file does not exist.
    ValueError
        an unreadable file (a FIFO, a device or a folder is refused by name) or a
        bad value, naming the key and the value
        (the scenario crate's messages, as the command line prints them); for a
        bad scenario an ``adhesim.ScenarioError`` with ``.key``, ``.value``,
        ``.requirement`` and ``.kind``.
    TypeError
        a scenario or override value of an unsupported type.
    KeyboardInterrupt
        Ctrl-C, checked between steps (a step itself runs to its end:
        the library has no cancellation hook inside a step).
    adhesim.SolveError
        a solver did not converge.

    The GIL is released during the run, except for the signal check and the progress
    callback between steps.
    """
    threads = _check_threads(threads)
    text, origin, base = _scenario_text(scenario)
    items = _override_items(overrides, keyword_overrides)
    folder = None if out is None else Path(out)
    callback, bar = _progress_callback(progress)
    try:
        # With `out`, the Rust run pipeline makes the folder ready (marker, clearing) and
        # writes the files as `adhesim run --out` does, without the figures.
        raw = _adhesim._run_scenario(
            text, origin, str(base), items, callback, not allow_large,
            None if folder is None else str(folder), force, threads,
        )
    finally:
        if bar is not None:
            bar.close()
    curve = {name: array for name, array in raw["columns"]}
    snapshots = [
        Snapshot(s["step"], s["depth"], s["pressure"], s["displacement"], s["gap"], s["contact"], s["offset"])
        for s in raw["snapshots"]
    ]
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
                pressure, displacement, gap, contact = (
                    archive[f"{name}_{step:06d}"] for name in ("pressure", "displacement", "gap", "contact")
                )
                snapshots.append(Snapshot(step, depth, pressure, displacement, gap, contact.astype(bool), offset))
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

    Parameters
    ----------
    folder : str or os.PathLike
        the run folder, holding ``curve.csv`` and ``summary.json``.

    Returns
    -------
    RunResult
        the curve with the same column kinds as ``run`` gives, the summary,
        and the snapshots of ``fields.npz`` (docs/output.md: the same steps and fields
        as ``run`` gives); in a folder without ``fields.npz`` (an older adhesim), the
        chosen steps' ``snapshots/step_NNNNNN_{pressure,displacement}.npy`` (gap and
        contact None).

    Raises
    ------
    ValueError
        a missing or unreadable ``curve.csv`` / ``summary.json``, or a
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
