"""The command line in the wheel: `pip install` puts `adhesim` into the environment's bin
folder (the console script `adhesim._cli:main`), and it behaves as the native binary:
the same output and the same exit codes (0, 1 for an error, 2 for a usage error)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import adhesim


def console_script():
    """The `adhesim` script next to this interpreter (the venv's bin folder)."""
    folder = Path(sys.executable).parent
    for name in ("adhesim", "adhesim.exe"):
        if (folder / name).is_file():
            return folder / name
    pytest.fail(f"no `adhesim` console script in {folder}: the wheel did not install it")


def native_binary():
    """The native binary named by ADHESIM_BIN (`.ci/run` sets it)."""
    path = os.environ.get("ADHESIM_BIN")
    if not (path and Path(path).is_file()):
        pytest.skip("ADHESIM_BIN does not name the native binary")
    return Path(path)


def run(program, *args, cwd=None):
    return subprocess.run([str(program), *args], capture_output=True, text=True, cwd=cwd, timeout=300)


def test_version_is_the_crates_version():
    parts = adhesim.__version__.split(".")
    assert len(parts) == 3 and all(p.isdigit() for p in parts), adhesim.__version__
    assert run(console_script(), "--version").stdout.strip() == f"adhesim {adhesim.__version__}"


def test_help_runs_from_the_venv_bin_folder():
    result = run(console_script(), "--help")
    assert result.returncode == 0, result.stderr
    assert "Usage: adhesim" in result.stdout
    for command in ("run", "sweep", "study", "reference", "topography"):
        assert command in result.stdout


def test_console_script_equals_the_native_binary(tmp_path):
    script, native = console_script(), native_binary()
    jkr = ("reference", "jkr", "--radius", "1", "--work-of-adhesion", "1e-4")
    a, b = run(script, *jkr), run(native, *jkr)
    assert (a.returncode, a.stdout) == (b.returncode, b.stdout) == (0, b.stdout)
    # an error (a missing scenario file) and a usage error (an unknown flag)
    for args, code in ((("run", str(tmp_path / "missing.toml")), 1), (("run", "--no-such-flag"), 2)):
        a, b = run(script, *args), run(native, *args)
        assert a.returncode == b.returncode == code, (a.stderr, b.stderr)
        assert a.stderr == b.stderr


def test_a_run_through_the_console_script_writes_its_folder(tmp_path):
    out = tmp_path / "hertz"
    scenario = Path(__file__).resolve().parents[3] / "scenarios" / "hertz.toml"
    result = run(console_script(), "run", str(scenario), "--out", str(out), "--quiet", "--set", "grid.n=32")
    assert result.returncode == 0, result.stderr
    assert (out / "summary.json").is_file() and (out / "curve.csv").is_file()


def test_the_entry_runs_twice_in_one_process_with_threads(tmp_path):
    """The console script's entry called twice in one interpreter, each with `--threads`:
    the option sized rayon's global pool, which a process sizes once, so the second run
    was refused ("The global thread pool has already been initialized"); each run now has
    a pool of its own."""
    from adhesim import _adhesim

    jkr = Path(__file__).resolve().parents[3] / "scenarios" / "jkr.toml"
    for k in range(2):
        args = ["adhesim", "run", str(jkr), "--set", "grid.n=32", "--threads", "1", "--quiet"]
        assert _adhesim.cli_main([*args, "--out", str(tmp_path / f"run{k}")]) == 0
    assert (tmp_path / "run0" / "curve.csv").read_bytes() == (tmp_path / "run1" / "curve.csv").read_bytes()
