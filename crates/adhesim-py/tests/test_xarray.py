"""Fields as data (docs/output.md, "fields.npz", contract 2): `fields.nc` opened with
xarray has a `step` dimension, and `RunResult.to_xarray()` gives the same dataset."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import adhesim

# CI installs xarray and scipy (.ci/run), so these tests run there.
xarray = pytest.importorskip("xarray")
pytest.importorskip("scipy")

REPO = Path(__file__).resolve().parents[3]
JKR = REPO / "scenarios" / "jkr.toml"
SMALL = {"grid.n": 32, "protocol.steps": 20, "output.snapshot_steps": [3, 15]}
RECTANGLE = {"grid.n": [48, 32], "grid.size": [0.375, 0.25], "protocol.steps": 20, "output.snapshot_steps": [3]}


def _cli_run_netcdf(out, overrides):
    """`adhesim run jkr.toml --fields netcdf` through the package's console entry."""
    sets = [a for k, v in overrides.items() for a in ("--set", f"{k}={_toml(v)}")]
    args = [sys.executable, "-m", "adhesim._cli", "run", str(JKR), "--out", str(out), "--quiet", "--fields", "netcdf"]
    subprocess.run(args + sets, check=True)


def _toml(value):
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return str(value)


@pytest.mark.parametrize("overrides", [SMALL, RECTANGLE], ids=["square", "rectangle"])
def test_fields_nc_has_a_step_dimension_and_selects_pressure_by_step(tmp_path, overrides):
    _cli_run_netcdf(tmp_path, overrides)
    result = adhesim.load(tmp_path)
    with xarray.open_dataset(tmp_path / "fields.nc") as ds:
        nx, ny = (overrides["grid.n"], overrides["grid.n"]) if isinstance(overrides["grid.n"], int) else overrides["grid.n"]
        assert ds.pressure.dims == ("step", "y", "x")
        assert dict(ds.sizes) == {"step": len(result.snapshots), "y": ny, "x": nx}
        assert ds.attrs["Conventions"] == "CF-1.8"
        assert ds.step.dtype.kind == "i"
        assert list(ds.step.values) == [s.step for s in result.snapshots]
        assert 3 in ds.step.values
        # centred coordinates: the npz's x, y, with units
        with np.load(tmp_path / "fields.npz") as npz:
            assert np.array_equal(ds.x.values, npz["x"]) and np.array_equal(ds.y.values, npz["y"])
            assert np.array_equal(ds.pressure.values, npz["pressure"])
        assert ds.x.attrs["units"] == "length" and ds.x.values[nx // 2] == 0.0
        for snapshot in result.snapshots:
            chosen = ds.pressure.sel(step=snapshot.step)
            assert chosen.dims == ("y", "x")
            assert np.array_equal(chosen.values, snapshot.pressure)
            assert float(ds.depth.sel(step=snapshot.step)) == snapshot.depth
            assert np.array_equal(ds.contact.sel(step=snapshot.step).values.astype(bool), snapshot.contact)


def test_to_xarray_equals_fields_nc(tmp_path):
    _cli_run_netcdf(tmp_path / "cli", RECTANGLE)
    in_memory = adhesim.run(JKR, overrides=RECTANGLE).to_xarray()
    with xarray.open_dataset(tmp_path / "cli" / "fields.nc") as ds:
        for name in ("pressure", "displacement", "gap"):
            assert in_memory[name].dims == ("step", "y", "x")
            assert np.array_equal(in_memory[name].values, ds[name].values), name
        assert np.array_equal(in_memory.contact.values, ds.contact.values.astype(bool))
        for coord in ("step", "x", "y", "depth", "offset"):
            assert np.array_equal(in_memory[coord].values, ds[coord].values), coord
    assert float(in_memory.pressure.sel(step=3).sum()) == float(in_memory.pressure.isel(step=0).sum())


def test_to_xarray_without_xarray_says_what_to_install(monkeypatch):
    result = adhesim.run(JKR, overrides={"grid.n": 16, "protocol.steps": 6})
    monkeypatch.setitem(sys.modules, "xarray", None)
    with pytest.raises(ImportError, match="pip install xarray"):
        result.to_xarray()
