"""Indenter heights on a grid, evaluated by the library's profiles.

Heights z >= 0 are measured from the indenter's reference point (the apex of a sphere,
the face of a punch) with its axis at the origin, at every element centre; +inf where the
indenter has no surface (such elements never touch). Arrays are float64 (n, n),
[row = y, column = x]. Any other height map of that shape and dtype works as well.
"""

from __future__ import annotations

import numpy as np

from ._adhesim import Grid, flat_punch_heights, sphere_heights

__all__ = ["sphere", "flat_punch"]


def sphere(grid: Grid, radius: float) -> np.ndarray:
    """Paraboloid z = (x^2 + y^2)/(2R) of radius R (length, > 0).

    Raises ValueError for a radius that is not finite and > 0.
    """
    return sphere_heights(grid, float(radius))


def flat_punch(grid: Grid, radius: float) -> np.ndarray:
    """Flat circular punch of radius a (length, > 0): 0 on the face, +inf outside.

    Raises ValueError for a radius that is not finite and > 0.
    """
    return flat_punch_heights(grid, float(radius))
