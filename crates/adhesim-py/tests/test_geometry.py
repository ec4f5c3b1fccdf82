"""Every curved and flat shape of the scenario file as a heights function: the wavy sphere
(paper Eq. 1) and the elliptic punch against their formulas at the element centres
(rounding only: 1e-12 of the height scale), with angles in degrees as in the file."""

import math

import numpy as np
import pytest

import adhesim


def centres(grid):
    x = grid.coordinates()
    return np.meshgrid(x, x)  # [row = y, column = x]


def test_wavy_sphere_is_the_papers_equation_1():
    grid = adhesim.Grid(64, 0.8)
    radius, amplitude, wavelength = 1.0, 0.0025, 0.05
    for angle in (0.0, 30.0):
        z = adhesim.geometry.wavy_sphere(grid, radius, amplitude, wavelength, angle)
        x, y = centres(grid)
        phi = math.radians(angle)
        xr, yr = x * math.cos(phi) + y * math.sin(phi), -x * math.sin(phi) + y * math.cos(phi)
        expected = (x**2 + y**2) / (2 * radius) + amplitude * np.sin(2 * np.pi * xr / wavelength) * np.sin(
            2 * np.pi * yr / wavelength
        )
        assert z.shape == (64, 64) and z.dtype == np.float64
        assert np.max(np.abs(z - expected)) <= 1e-12 * np.max(np.abs(expected)), angle
    # no waviness: the sphere itself
    flat_wave = adhesim.geometry.wavy_sphere(grid, radius, 0.0, wavelength)
    assert np.array_equal(flat_wave, adhesim.geometry.sphere(grid, radius))


def test_elliptic_punch_face_and_rotation():
    grid = adhesim.Grid(64, 2.4)
    z = adhesim.geometry.elliptic_punch(grid, (1.0, 0.5))
    x, y = centres(grid)
    inside = (x / 1.0) ** 2 + (y / 0.5) ** 2 <= 1.0
    assert np.all(z[inside] == 0.0) and np.all(np.isinf(z[~inside]))
    # a quarter turn swaps the axes
    turned = adhesim.geometry.elliptic_punch(grid, (1.0, 0.5), 90.0)
    assert np.array_equal(np.isinf(turned), np.isinf(z).T)


def test_bad_shape_parameters_name_the_value():
    grid = adhesim.Grid(16, 1.0)
    with pytest.raises(ValueError, match="-0.05"):
        adhesim.geometry.wavy_sphere(grid, 1.0, 0.001, -0.05)
    with pytest.raises(ValueError, match="angle"):
        adhesim.geometry.wavy_sphere(grid, 1.0, 0.001, 0.05, float("nan"))
    with pytest.raises(ValueError, match="semi_axes"):
        adhesim.geometry.elliptic_punch(grid, (1.0, 0.0))


SCENARIOS = __import__("pathlib").Path(__file__).resolve().parents[3] / "scenarios"


def test_from_scenario_gives_what_the_run_presses():
    # The wavy sphere of fig1.toml is exactly the analytic function (same code, same grid).
    grid, heights = adhesim.geometry.from_scenario(SCENARIOS / "fig1.toml", {"grid.n": 64})
    assert (grid.nx, grid.ny, grid.size_x) == (64, 64, 0.8)
    expected = adhesim.geometry.wavy_sphere(grid, 1.0, 0.0025, 0.05)
    assert np.array_equal(heights, expected)
    # rough_sphere.toml: the paraboloid minus its [roughness] (peaks towards the body),
    # shifted by a constant; the roughness is adhesim.surface.self_affine with the file's keys
    # (the same generator): the difference is constant to rounding (1e-15 of the rms height).
    grid, heights = adhesim.geometry.from_scenario(SCENARIOS / "rough_sphere.toml", **{"grid.n": 64})
    roughness = adhesim.surface.self_affine(
        grid, 0.8, seed=1, rms_height=2e-4, rolloff_wavelength=0.05, cutoff_wavelength=0.015625
    )
    offset = heights - adhesim.geometry.sphere(grid, 1.0) + roughness
    assert offset.std() < 1e-15 * 2e-4 * 1e3
    with pytest.raises(adhesim.ScenarioError) as error:
        adhesim.geometry.from_scenario(SCENARIOS / "fig1.toml", {"grid.n": -3})
    assert error.value.key == "grid.n"


def test_from_scenario_reads_a_topography_indenter(tmp_path):
    ny, nx = 64, 96
    rng = np.random.default_rng(3)
    measured = rng.normal(size=(ny, nx)) * 1e-6
    np.save(tmp_path / "map.npy", measured)
    scenario = {
        "grid": {"n": [nx, ny], "size": [nx * 1e-5, ny * 1e-5]},
        "material": {"contact_modulus": 1.0},
        "adhesion": {"work_of_adhesion": 0.0},
        "indenter": {"shape": "topography", "file": str(tmp_path / "map.npy"), "spacing": 1e-5},
        "protocol": {"kind": "indent_pulloff", "max_depth": 1e-5, "steps": 2},
    }
    grid, heights = adhesim.geometry.from_scenario(scenario)
    assert heights.shape == (ny, nx)
    # The map's points span (n − 1) spacings, the grid n elements: bilinear resampling onto
    # the element centres leaves one row and one column without surface (+inf, never
    # touching), and cannot widen the map's range of heights.
    finite = np.isfinite(heights)
    assert (~finite).sum() == nx + ny - 1
    assert np.ptp(heights[finite]) <= np.ptp(measured) * (1 + 1e-12)
