"""Indenter heights on a grid, evaluated by the library's profiles.

Heights z >= 0 are measured from the indenter's reference point (the apex of a sphere,
the face of a punch) with its axis at the origin, at every element centre; +inf where the
indenter has no surface (such elements never touch). Arrays are float64 (ny, nx),
[row = y, column = x]. Any other height map of that shape and dtype works as well.
"""

from __future__ import annotations

import numpy as np

from ._args import number, pair
from ._adhesim import Grid, elliptic_punch_heights, flat_punch_heights, sphere_heights, wavy_sphere_heights

__all__ = ["sphere", "flat_punch", "wavy_sphere", "elliptic_punch", "from_scenario"]


def sphere(grid: Grid, radius: float) -> np.ndarray:
    """Paraboloid z = (x^2 + y^2)/(2R) of radius R (length, > 0).

    Raises ValueError for a radius that is not finite and > 0.
    """
    return sphere_heights(grid, number("radius", radius))


def flat_punch(grid: Grid, radius: float) -> np.ndarray:
    """Flat circular punch of radius a (length, > 0): 0 on the face, +inf outside.

    Raises ValueError for a radius that is not finite and > 0.
    """
    return flat_punch_heights(grid, number("radius", radius))


def wavy_sphere(grid: Grid, radius: float, amplitude: float, wavelength: float, angle: float = 0.0) -> np.ndarray:
    """The paper's wavy sphere (Eq. 1): z = (x^2 + y^2)/(2R) + h sin(2 pi x'/lambda) sin(2 pi y'/lambda).

    The waviness of amplitude h (length, >= 0) and wavelength lambda (length, > 0) is
    rotated by ``angle`` degrees; heights are measured from the paraboloid's apex, as the
    scenario file's ``shape = "wavy_sphere"``.

    Raises ValueError for a radius or wavelength that is not finite and > 0, a negative
    amplitude or a non-finite angle.
    """
    return wavy_sphere_heights(
        grid,
        number("radius", radius),
        number("amplitude", amplitude),
        number("wavelength", wavelength),
        number("angle", angle),
    )


def elliptic_punch(grid: Grid, semi_axes, angle: float = 0.0) -> np.ndarray:
    """Flat punch with an elliptic face of semi-axes (a, b) (length, > 0), rotated by
    ``angle`` degrees: 0 on the face, +inf outside (the scenario file's ``elliptic_punch``).

    Raises ValueError for semi-axes that are not finite and > 0 or a non-finite angle.
    """
    a, b = pair("semi_axes", semi_axes)
    return elliptic_punch_heights(grid, (a, b), number("angle", angle))



def from_scenario(scenario, overrides=None, **keyword_overrides):
    """The grid and indenter heights a scenario presses, without running it.

    Every ``indenter.shape`` of the scenario file is covered, built by the same code as
    its run: the analytic shapes, ``"topography"`` (a measured map, read and resampled as
    the run reads it) and ``"rough_sphere"`` / ``"rough_flat"`` with their
    ``[roughness]``.

    Parameters
    ----------
    scenario : str, os.PathLike or dict
        A scenario file, TOML text or a nested dict, as for ``adhesim.run``.
    overrides : dict, optional
        ``{"grid.n": 64, ...}``, as for ``adhesim.run``.
    **keyword_overrides
        More overrides.

    Returns
    -------
    grid : Grid
        The scenario's grid.
    heights : numpy.ndarray
        float64 (ny, nx), [row = y, column = x]; +inf where the indenter has no surface.

    Raises
    ------
    adhesim.ScenarioError
        a bad scenario, naming the key and the value.
    """
    from . import _adhesim
    from ._run import _override_items, _scenario_text

    text, origin, base = _scenario_text(scenario)
    items = _override_items(overrides, keyword_overrides)
    return _adhesim._scenario_heights(text, origin, str(base), items)
