"""``adhesim.sweep``: the command line's sweep engine (``adhesim sweep``, docs/sweeps.md)
driven from Python, with the cases on any ``concurrent.futures.Executor``.

The parent process builds the plan in Rust (the same case list, pseudo-keys such as
``alpha`` and ``size_over_a_jkr``, case ids and hashes as a sweep file), takes the folder's
lock and writes ``sweep.json``. Each case still to do is then one picklable call,
``_run_case(out, index)``, that any worker process with ``adhesim`` installed runs through
the Rust engine into ``out/cases/<id>/`` (computed in ``out/tmp/`` and renamed into place
with its ``done`` marker, so a lost worker loses only its unfinished case). The parent
rebuilds ``table.csv`` from the case folders at the end, as ``adhesim sweep merge`` does.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Tuple, Union

import numpy as np

from ._args import number
from . import _adhesim
from ._run import RunResult, ScenarioLike, _check_overrides, _check_threads, _plain, _scenario_text, load

__all__ = ["SweepResult", "sweep"]


class SweepResult(list):
    """The cases of a sweep, a list of ``RunResult`` in case order (each with ``.case``,
    the varied keys and their values, and ``.case_id``), with:

    Attributes
    ----------
    out : pathlib.Path or None
        The sweep folder (None for a sweep run in a temporary folder).
    table : dict of str to numpy array
        The columns of ``table.csv`` (one row per case): float64 where every cell is a
        number (an empty cell NaN), as ``sweep_table`` gives them, else str.
    ran : int
        Cases computed by this call; the others were finished in ``out`` already.
    """

    out: Optional[Path]
    table: Dict[str, np.ndarray]
    ran: int

    def __repr__(self) -> str:
        """The number of cases, the varied keys, the cases computed by the call and the
        folder (not the list of results: ``list(result)`` shows those)."""
        keys = list(getattr(self[0], "case", {})) if self else []
        out = getattr(self, "out", None)
        return (
            f"SweepResult(cases={len(self)}, keys={keys!r}, ran={getattr(self, 'ran', None)}, "
            f"out={None if out is None else str(out)!r})"
        )


def _run_case(out: str, index: int, checkpoint_every: float = 0.0,
              resume: Optional[str] = None, threads: Optional[int] = None) -> Tuple[bool, Optional[str]]:
    """Runs case ``index`` of the sweep in ``out`` (in whatever process calls it):
    (whether it ran, the error of a failed case or None). A finished case is not redone.
    With ``checkpoint_every`` > 0 the run writes a mid-run checkpoint that often (seconds)
    and goes on from the one in ``resume``, the folder of a killed run; ``threads`` as in
    ``sweep``."""
    return _adhesim._sweep_run_case(out, index, checkpoint_every, resume, threads)


def _cell(text: str) -> Any:
    """A table cell as the value it spells: int, float, else the text."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _table_of(mapping: Any, name: str) -> Dict[str, Any]:
    """A sweep table argument (``vary``, ``zip``, ...) checked and made TOML-ready."""
    if mapping is None:
        return {}
    if not isinstance(mapping, Mapping):
        raise TypeError(
            f"{name} must be a mapping of dotted keys to lists of values like "
            f"{{'grid.n': [32, 64]}}, got {type(mapping).__name__} {mapping!r}"
        )
    table = {}
    for key, values in mapping.items():
        if not isinstance(key, str):
            raise TypeError(f"{name} keys must be dotted keys (str) like 'grid.n', got {key!r}")
        if name in ("vary", "zip"):
            # A string is iterable but is one value, not a list of them.
            if isinstance(values, (str, bytes, Mapping)) or not isinstance(values, Iterable):
                raise TypeError(
                    f"{name}[{key!r}] must be a list of values, got {type(values).__name__} {values!r}"
                )
            values = [_plain(v.item() if hasattr(v, "item") else v) for v in values]
        table[key] = _plain(values)
    return table


def _column(cells: List[str]) -> np.ndarray:
    """A table.csv column as ``sweep_table`` gives it: float64 where every cell is a number
    (an empty cell NaN), else the text."""
    try:
        return np.array([float(cell) if cell != "" else np.nan for cell in cells], dtype=np.float64)
    except ValueError:
        return np.array(cells, dtype=str)


def _read_table(path: Path) -> Dict[str, np.ndarray]:
    import csv

    with open(path, newline="") as handle:
        rows = list(csv.reader(handle))
    header, body = rows[0], rows[1:]
    return {name: _column([row[k] for row in body]) for k, name in enumerate(header)}


def _case_progress(progress: Any) -> Tuple[Optional[Callable[[int, int, Dict[str, Any]], Any]], Any]:
    """(callback after each case, bar to close afterwards) of the ``progress`` argument:
    None or False, True (a tqdm bar of the cases, as ``run``'s of the steps) or a callable.
    True was called as a function after the first case and crashed the sweep."""
    if progress is None or progress is False:
        return None, None
    if progress is True:
        try:
            from tqdm.auto import tqdm
        except ImportError:
            import warnings

            warnings.warn(
                "progress=True draws a tqdm bar, but tqdm is not installed "
                "(pip install tqdm, or the package's [extras]); running without a bar",
                stacklevel=4,
            )
            return None, None
        bar = tqdm(total=0, unit="case")

        def update(done: int, total: int, case: Dict[str, Any]) -> None:
            if bar.total != total:
                bar.total = total
            bar.update(done - bar.n)

        return update, bar
    if callable(progress):
        return progress, None
    raise TypeError(f"progress must be None, True or a callable(done, total, case), got {progress!r}")


def sweep(
    scenario: ScenarioLike,
    vary: Optional[Mapping[str, Iterable[Any]]] = None,
    out: Union[str, "os.PathLike[str]", None] = None,
    executor: Any = None,
    *,
    zip: Optional[Mapping[str, Iterable[Any]]] = None,
    random: Optional[Mapping[str, Any]] = None,
    derived: Optional[Mapping[str, str]] = None,
    series: Optional[str] = None,
    progress: Union[bool, Callable[[int, int, Dict[str, Any]], Any], None] = None,
    overrides: Optional[Mapping[str, Any]] = None,
    allow_large: bool = False,
    retry_failed: bool = False,
    checkpoint_every: float = 600.0,
    threads: Optional[int] = None,
    **keyword_overrides: Any,
) -> SweepResult:
    """Runs a parameter sweep of a scenario as ``adhesim sweep`` does.

    Parameters
    ----------
    scenario : path, TOML str or dict
        The base scenario, as for ``run``.
    vary : dict of str to list
        The sweep file's ``[vary]``: dotted scenario keys or the pseudo-keys
        ``alpha``, ``size_over_a_jkr``, ``lambda_over_radius``, ``h_over_lambda``,
        ``maugis_parameter``, each with a list of values; the cases are their Cartesian
        product (last key fastest).
    out : path, optional
        The sweep folder (``sweep.json``, ``cases/<id>/``, ``table.csv``, ``plots/``: the
        command line's layout). Cases already finished there are not computed again, so a
        call after a lost worker or cluster runs only the unfinished cases. None runs in a
        temporary folder, removed afterwards.
    executor : concurrent.futures.Executor, optional
        Runs the cases: a ``ProcessPoolExecutor``, ``dask.distributed.Client.get_executor()``,
        ``mpi4py.futures.MPIPoolExecutor``, ... Each case is the call
        ``adhesim._sweep._run_case(out, index)``; its workers must see ``out`` (a shared
        file system on a cluster). None runs the cases one after another in this process
        (each uses every core for its FFTs).
    zip, random, derived : dict, optional
        The sweep file's ``[zip]``, ``[random]`` and ``[derived]`` tables (docs/sweeps.md).
    series : str, optional
        The label of the table's rows; by default the name of ``out``.
    progress : bool or callable, optional
        True draws a tqdm bar of the cases (as ``run``'s of the steps); a callable
        ``progress(done, total, case)`` is called in this process as each case ends.
    overrides, **keyword_overrides
        Keys set in every case, the sweep file's ``[set]``.
    allow_large : bool
        Run even when a case's grid is estimated to need more memory than is available
        (but within the address-space limit RLIMIT_AS, which nothing gets past).
    retry_failed : bool
        Also redo the cases that finished with an error.
    checkpoint_every : float
        Seconds of wall time between mid-run checkpoints of a running case (0: none), as
        ``adhesim sweep --checkpoint-every``: a case whose worker was killed goes on from
        its last checkpoint when the sweep is called again with the same ``out``
        (docs/sweeps.md, "Resuming a case mid-run").
    threads : int, optional
        Threads of each case's own pool, like ``adhesim sweep --threads`` (more than the
        cores are clamped to them with a ``UserWarning``); by default the cores of the
        process that runs the case. With an executor of k worker processes on c cores,
        ``threads = c // k`` keeps them from contending (on 2 cores two one-thread cases
        side by side took 0.51 of the wall of one two-thread case at a time,
        BENCHMARKS.md "Cases or threads"). The results are the same bits for every count.

    Returns
    -------
    SweepResult
        The cases' ``RunResult`` in case order, read back from their folders.

    Raises
    ------
    TypeError
        ``vary`` (or ``zip``) not a mapping of dotted keys to lists.
    ValueError
        A bad key or value (naming the case and the key), ``out`` holding another sweep
        or in use by another sweep.
    RuntimeError
        Cases that failed (their messages are in ``out/cases/<id>/error.txt``); the
        others are finished and kept, and ``table.csv`` is written.
    """
    _check_overrides(overrides)
    threads = _check_threads(threads)
    tables = {
        "vary": _table_of(vary, "vary"),
        "zip": _table_of(zip, "zip"),
        "random": _table_of(random, "random"),
        "derived": _table_of(derived, "derived"),
        "set": _table_of({**(overrides or {}), **keyword_overrides}, "overrides"),
    }
    tables = {name: table for name, table in tables.items() if table}
    if not tables.get("vary") and not tables.get("zip") and not tables.get("random"):
        raise ValueError("vary (or zip, random) must name at least one key with a list of values")
    callback, bar = _case_progress(progress)
    try:
        if out is None:
            with tempfile.TemporaryDirectory(prefix="adhesim-sweep-") as temporary:
                result = _sweep_into(scenario, tables, Path(temporary) / "sweep", executor, series or "sweep",
                                     callback, allow_large, retry_failed, checkpoint_every, threads)
                result.out = None
                return result
        out = Path(out)
        return _sweep_into(scenario, tables, out, executor, series or out.resolve().name, callback,
                           allow_large, retry_failed, checkpoint_every, threads)
    finally:
        if bar is not None:
            bar.close()


def _sweep_into(scenario, tables, out: Path, executor, series, progress, allow_large, retry_failed,
                checkpoint_every, threads):
    text, origin, base = _scenario_text(scenario)
    sweep_text = _adhesim._toml_document(tables)
    folder = _adhesim._sweep_open(str(out), sweep_text, text, origin, str(base), series, not allow_large, 1,
                                  number("checkpoint_every", checkpoint_every))
    try:
        cases = folder.cases()
        todo = folder.pending(retry_failed)
        _run_cases(out, cases, todo, executor, progress, number("checkpoint_every", checkpoint_every), threads)
        table_path, failed = folder.finish()
    finally:
        folder.close()
    if failed:
        raise RuntimeError(
            f"{len(failed)} of {len(cases)} cases failed: {', '.join(failed[:10])} "
            f"(each case's error is in {out}/cases/<id>/error.txt; the finished cases are kept)"
        )
    results = SweepResult()
    for case in cases:
        result: RunResult = load(out / "cases" / case["id"])
        result.case = {key: _cell(value) for key, value in case["values"].items()}
        result.case_id = case["id"]
        results.append(result)
    results.out = out
    results.table = _read_table(Path(table_path))
    results.ran = len(todo)
    return results


def _run_cases(out: Path, cases, todo: List[Tuple[int, Optional[str]]], executor, progress,
               checkpoint_every: float, threads: Optional[int]) -> None:
    """Runs the cases ``todo`` ((index, folder of a killed run to go on from or None)) in
    this process or on ``executor``; waits for all of them."""
    if executor is None:
        for done, (index, resume) in enumerate(todo, start=1):
            _run_case(str(out), index, checkpoint_every, resume, threads)
            if progress is not None:
                progress(done, len(todo), cases[index])
        return
    from concurrent.futures import FIRST_COMPLETED, wait

    pending = {executor.submit(_run_case, str(out), index, checkpoint_every, resume, threads): index
               for index, resume in todo}
    done = 0
    try:
        while pending:
            finished, _ = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
            for future in finished:
                index = pending.pop(future)
                future.result()
                done += 1
                if progress is not None:
                    progress(done, len(todo), cases[index])
    except BaseException:
        # Ctrl-C or a worker's failure: cases not started are cancelled; those running
        # finish into their folders (a later call keeps them).
        for future in pending:
            future.cancel()
        raise
