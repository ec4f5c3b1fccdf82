"""Measured height maps from instrument files (x3p, gwy, sur, ASCII, xyz, npy, npz)."""

from __future__ import annotations

import os
from typing import Dict, NamedTuple, Optional, Tuple, Union

import numpy as np

from ._args import pair
from ._adhesim import _read_topography

__all__ = ["Topography", "read_topography"]


class Topography(NamedTuple):
    """A measured height map in metres.

    heights: float64 (ny, nx) [row = y, column = x], NaN at invalid points; valid: bool
    (ny, nx); dx, dy: spacings in metres; x_offset, y_offset: position of the first point;
    channel, format; height_unit and lateral_unit: the units the file stored; metadata.
    """

    heights: np.ndarray
    valid: np.ndarray
    dx: float
    dy: float
    x_offset: float
    y_offset: float
    channel: str
    format: str
    height_unit: str
    lateral_unit: str
    metadata: Dict[str, str]


def read_topography(
    path: Union[str, os.PathLike],
    *,
    channel: Optional[str] = None,
    spacing: Optional[Union[float, Tuple[float, float]]] = None,
    height_unit: Optional[str] = None,
    lateral_unit: Optional[str] = None,
) -> Topography:
    """Reads a height map, choosing the format by the file extension.

    Files that record no spacing or unit (npy, npz, bare ASCII, xyz without header, a .gwy
    with empty units) need spacing (metres: dx, or (dx, dy)), height_unit ("nm", "um", "m",
    ...) or lateral_unit: there is no default, the ValueError names the missing argument.
    channel picks a Gwyddion channel by title, an npz member or the ASCII "Channel". Raises
    OSError when the file cannot be read, ValueError for a malformed or unsupported file.
    """
    if spacing is not None:
        spacing = pair("spacing", spacing, one_for_both=True)
    fields = _read_topography(
        os.fspath(path), channel=channel, spacing=spacing, height_unit=height_unit, lateral_unit=lateral_unit
    )
    return Topography(**fields)
