"""Rectangular grids (docs/validation.md §12): Grid(nx, ny, size_x, size_y) beside
Grid(n, size), fields of shape (ny, nx), and Hertz on a 96 x 64 grid equal to the same case
on a square.

The contact (a = sqrt(R d) = 0.2 = 12.8 dx) lies far from every edge of both grids, which
have the same elements: the free half-space sees the same case, so the forces agree to
the solver's tolerance (1e-6 relative), as in the Rust test validation_rectangle.rs.
"""

import numpy as np
import pytest

import adhesim


def test_rectangular_grid_attributes():
    grid = adhesim.Grid(96, 64, 1.5, 1.0)
    assert (grid.nx, grid.ny, grid.shape) == (96, 64, (64, 96))
    assert (grid.size_x, grid.size_y) == (1.5, 1.0)
    assert grid.dx == grid.dy == 1.0 / 64
    assert grid.element_area == pytest.approx(1.0 / 64**2, rel=1e-15)
    assert grid.x().shape == (96,) and grid.y().shape == (64,)
    assert grid.x()[48] == 0.0 and grid.y()[32] == 0.0
    assert "nx=96" in repr(grid)
    with pytest.raises(ValueError, match="for square grids"):
        grid.n
    periodic = adhesim.Grid(8, 4, 2.0, 1.0, "periodic")
    assert periodic.boundary == "periodic"
    assert adhesim.Grid(8, 4, 2.0, 1.0, boundary="periodic") == periodic
    square = adhesim.Grid(16, 1.0)
    assert (square.n, square.size, square.nx, square.ny) == (16, 1.0, 16, 16)
    assert repr(square) == 'Grid(n=16, size=1, boundary="free")'


@pytest.mark.parametrize(
    "make, fragments",
    [
        (lambda: adhesim.Grid(96, 1, 1.5, 1.0), ["ny", "1"]),
        (lambda: adhesim.Grid(96, 64, 1.5, -1.0), ["size_y", "-1"]),
        (lambda: adhesim.Grid(96, 64, 1.5), ["3 arguments"]),
        (lambda: adhesim.Grid(96, 64, 1.0, 1.0).element_size, ["square elements", "dy"]),
    ],
)
def test_rectangular_errors_name_the_argument(make, fragments):
    with pytest.raises(ValueError) as error:
        make()
    for fragment in fragments:
        assert fragment in str(error.value)


def test_hertz_on_a_rectangle_is_the_square_case():
    depth = 0.04
    forces = {}
    for name, grid in [("square", adhesim.Grid(64, 1.0)), ("rectangle", adhesim.Grid(96, 64, 1.5, 1.0))]:
        operator = adhesim.HalfSpace(grid, adhesim.Material(1.0))
        heights = adhesim.geometry.sphere(grid, 1.0)
        assert heights.shape == grid.shape
        report = adhesim.NestedActiveSet(operator).solve(heights, depth)
        assert report.state.pressure.shape == grid.shape
        assert report.state.contact.shape == grid.shape
        forces[name] = report.force
        with pytest.raises(ValueError, match=r"shape \(%d, %d\)" % grid.shape):
            operator.apply(np.zeros((grid.nx, grid.ny + 1)))
    assert forces["rectangle"] == pytest.approx(forces["square"], rel=1e-6)
    hertz = adhesim.reference.hertz(1.0, 1.0, depth)["force"]
    assert forces["square"] == pytest.approx(hertz, rel=0.01)
