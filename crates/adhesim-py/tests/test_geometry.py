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
