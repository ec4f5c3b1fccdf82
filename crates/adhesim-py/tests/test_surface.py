"""adhesim.surface and adhesim.read_topography (docs/topography-files.md): the generator's
rms, the statistics against closed forms and numpy, invalid points left out, the harmonic
filling, and SurfaceTopography's values on its x3p fixture read through Python."""

import pathlib

import numpy as np
import pytest

import adhesim
from adhesim import surface

FIXTURES = pathlib.Path(__file__).resolve().parents[2] / "adhesim-topography" / "tests" / "data" / "surfacetopography"


def test_generator_has_the_requested_rms_on_a_periodic_grid():
    # random_phase on a periodic grid: exact amplitudes, the rms to rounding (1e-10)
    grid = adhesim.Grid(64, 2.0, "periodic")
    heights = surface.self_affine(grid, 0.8, seed=7, rms_height=0.01)
    assert heights.shape == (64, 64)
    stats = surface.statistics(heights, grid.element_size, periodic=True)
    assert stats["rms_height"] == pytest.approx(0.01, rel=1e-10)
    by_slope = surface.self_affine(grid, 0.8, seed=7, rms_slope=0.2)
    slope = surface.statistics(by_slope, grid.element_size, periodic=True)["rms_slope_spectral"]
    assert slope == pytest.approx(0.2, rel=1e-10)
    # the same seed gives the same surface; another seed another one
    assert np.array_equal(heights, surface.self_affine(grid, 0.8, seed=7, rms_height=0.01))
    assert not np.array_equal(heights, surface.self_affine(grid, 0.8, seed=8, rms_height=0.01))
    with pytest.raises(ValueError, match="exactly one of rms_height and rms_slope"):
        surface.self_affine(grid, 0.8, seed=1)
    with pytest.raises(ValueError, match="hurst"):
        surface.self_affine(grid, 1.5, seed=1, rms_height=1.0)
    with pytest.raises(ValueError, match="seed"):
        surface.self_affine(grid, 0.8, seed=-1, rms_height=1.0)


def test_statistics_of_a_rectangle_with_unequal_spacings():
    # h = a sin(qx x) on a free 30 x 20 map, dx != dy: the finite-difference values are
    # SurfaceTopography's stencils, here recomputed with numpy (to rounding, 1e-12)
    ny, nx, dx, dy = 20, 30, 0.5, 1.5
    x = np.arange(nx) * dx
    y = np.arange(ny) * dy
    h = 0.3 * np.sin(2 * np.pi * x / 7.0)[None, :] + 0.1 * np.cos(2 * np.pi * y / 11.0)[:, None]
    stats = surface.statistics(h, (dx, dy))
    slope_x = (h[:-1, 1:] - h[:-1, :-1]) / dx
    slope_y = (h[1:, :-1] - h[:-1, :-1]) / dy
    assert stats["rms_slope_finite_differences"] == pytest.approx(np.sqrt(np.mean(slope_x**2 + slope_y**2)), rel=1e-12)
    laplacian = (h[1:-1, 2:] - 2 * h[1:-1, 1:-1] + h[1:-1, :-2]) / dx**2 + (h[2:, 1:-1] - 2 * h[1:-1, 1:-1] + h[:-2, 1:-1]) / dy**2
    assert stats["rms_curvature_finite_differences"] == pytest.approx(np.sqrt(np.mean(laplacian**2)) / 2, rel=1e-12)
    assert stats["rms_height"] == pytest.approx(np.std(h), rel=1e-12)
    assert stats["rms_slope_spectral"] is None  # a free map has no spectral form


def test_invalid_points_are_left_out_and_filled_harmonically():
    ny, nx = 16, 24
    yy, xx = np.mgrid[0:ny, 0:nx]
    plane = 0.2 + 0.01 * xx - 0.03 * yy
    valid = np.ones((ny, nx), bool)
    valid[5:9, 7:12] = False
    holed = np.where(valid, plane, np.nan)
    stats = surface.statistics(holed, 1.0, valid=valid)
    assert stats["rms_height"] == pytest.approx(np.std(plane[valid]), rel=1e-12)
    assert stats["valid_points"] == valid.sum()
    # a plane is harmonic: the filling restores it (CG to a relative residual of 1e-13)
    filled = surface.fill_invalid(holed, valid)
    np.testing.assert_allclose(filled, plane, rtol=0, atol=1e-12)
    power = surface.psd(holed, 1.0, 8, valid=valid)
    assert np.all(np.isfinite(power.psd)) and power.modes.sum() > 0


def test_psd_of_one_mode_holds_its_power():
    n = 32
    y = np.arange(n)[:, None] * np.ones((1, n))
    h = 0.5 * np.cos(2 * np.pi * 4 * y / n)
    result = surface.psd(h, 1.0, 10, periodic=True)
    total = np.sum(result.psd * result.modes) / n**2
    assert total == pytest.approx(0.125, rel=1e-12)


def test_read_topography_agrees_with_surfacetopography():
    # x3p-2.x3p: 650 x 650, dx != dy; SurfaceTopography 1.27.1: rms_height_from_area
    # 7.728033273597876e-08, rms_gradient 0.06207007399844295 (same stencils: 1e-9)
    map_ = adhesim.read_topography(FIXTURES / "x3p-2.x3p")
    assert map_.heights.shape == (650, 650) and map_.valid.all()
    assert map_.dx * 650 == pytest.approx(8.29767313942749e-05, rel=1e-12)
    assert map_.dy * 650 == pytest.approx(0.0002044783737930349, rel=1e-12)
    stats = surface.statistics(map_.heights, (map_.dx, map_.dy))
    assert stats["rms_height"] == pytest.approx(7.728033273597876e-08, rel=1e-9)
    assert stats["rms_slope_finite_differences"] == pytest.approx(0.06207007399844295, rel=1e-9)


def test_read_topography_needs_a_unit_where_the_file_has_none(tmp_path):
    values = np.arange(12.0).reshape(3, 4)
    values[1, 2] = np.nan
    path = tmp_path / "map.npy"
    np.save(path, values)
    with pytest.raises(ValueError, match="spacing"):
        adhesim.read_topography(path)
    with pytest.raises(ValueError, match="height_unit"):
        adhesim.read_topography(path, spacing=1e-6)
    map_ = adhesim.read_topography(path, spacing=(1e-6, 2e-6), height_unit="nm")
    assert (map_.dx, map_.dy) == (1e-6, 2e-6)
    assert not map_.valid[1, 2] and np.isnan(map_.heights[1, 2])
    np.testing.assert_allclose(map_.heights[0], values[0] * 1e-9, rtol=1e-15)
    with pytest.raises(OSError, match="no_such.x3p"):
        adhesim.read_topography(tmp_path / "no_such.x3p")
