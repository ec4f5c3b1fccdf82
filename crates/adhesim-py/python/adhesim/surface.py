"""Rough surfaces: the random self-affine generator, and the statistics, PSD and filling of
any height map.

The generator is the library's `SelfAffine` (isotropic power spectrum
C(q) = C0 q^(-2-2H) between a roll-off and a cutoff wavevector; the spectrum convention of
SurfaceTopography's `fourier_synthesis`). The statistics take a map of shape (ny, nx)
[row = y, column = x] with its own spacings dx and dy and, optionally, a boolean `valid`
mask: invalid points are left out of every statistic, as SurfaceTopography does
(docs/topography-files.md, "Which statistics").
"""

from __future__ import annotations

from typing import Dict, NamedTuple, Optional, Tuple, Union

import numpy as np

from ._args import floats, integer, number, optional_number, pair
from ._adhesim import Grid, _fill_invalid, _height_map_statistics, _isotropic_psd, _self_affine

# The most PSD bins (adhesim::surface::MAX_PSD_BINS): 4e9 bins asked for 96 GB and killed
# the interpreter.
_MAX_PSD_BINS = 1_000_000

__all__ = ["self_affine", "statistics", "psd", "fill_invalid", "Psd"]

Spacing = Union[float, Tuple[float, float]]


def self_affine(
    grid: Grid,
    hurst: float,
    *,
    seed: int,
    rms_height: Optional[float] = None,
    rms_slope: Optional[float] = None,
    rolloff_wavelength: Optional[float] = None,
    cutoff_wavelength: Optional[float] = None,
    mode: str = "random_phase",
) -> np.ndarray:
    """A random self-affine surface on `grid`: float64 heights of shape (n, n).

    hurst: the Hurst exponent H in (0, 1]; exactly one of rms_height and rms_slope fixes the
    amplitude; seed (int >= 0) fixes the surface on every platform; rolloff_wavelength gives
    a plateau of the spectrum beyond it, cutoff_wavelength (default two elements) removes
    shorter modes; mode "random_phase" (exact amplitudes: a periodic grid has the requested
    rms to rounding) or "filtered" (Gaussian amplitudes). The same as a scenario's
    [roughness] with these keys. Raises ValueError naming a bad argument.
    """
    if integer("seed", seed) < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    return _self_affine(
        grid,
        number("hurst", hurst),
        int(seed),
        rms_height=optional_number("rms_height", rms_height),
        rms_slope=optional_number("rms_slope", rms_slope),
        rolloff_wavelength=optional_number("rolloff_wavelength", rolloff_wavelength),
        cutoff_wavelength=optional_number("cutoff_wavelength", cutoff_wavelength),
        mode=mode,
    )


def _spacings(spacing: Spacing) -> Tuple[float, float]:
    return pair("spacing", spacing, one_for_both=True)


def _map(heights: np.ndarray, valid: Optional[np.ndarray]) -> Tuple[np.ndarray, Optional[np.ndarray]]:
    heights = floats("heights", heights)
    if heights.ndim != 2:
        raise ValueError(f"heights must be a 2-D array (ny, nx), got shape {heights.shape}")
    if valid is not None:
        valid = np.ascontiguousarray(valid, dtype=bool)
    return heights, valid


def statistics(
    heights: np.ndarray, spacing: Spacing, *, valid: Optional[np.ndarray] = None, periodic: bool = False
) -> Dict[str, Optional[float]]:
    """rms height and rms slope and curvature of a height map, each by its definition.

    heights: (ny, nx) array; spacing: dx (= dy) or (dx, dy); valid: optional bool mask
    (False = no data: left out; such points may hold NaN); periodic: the map repeats.
    Returns a dict: rms_height (valid points), rms_slope_finite_differences and
    rms_curvature_finite_differences (SurfaceTopography's rms_gradient and
    rms_curvature_from_area stencils with the true spacings; None for a map too small),
    rms_slope_spectral and rms_curvature_spectral (periodic maps with every point valid,
    else None), valid_points.
    """
    heights, valid = _map(heights, valid)
    dx, dy = _spacings(spacing)
    return dict(_height_map_statistics(heights, dx, dy, valid=valid, periodic=bool(periodic)))


class Psd(NamedTuple):
    """An isotropic power spectrum in logarithmic bins (arrays of one value per bin)."""

    q_low: np.ndarray
    q_high: np.ndarray
    q: np.ndarray
    psd: np.ndarray
    modes: np.ndarray


def psd(
    heights: np.ndarray,
    spacing: Spacing,
    bins: int = 30,
    *,
    valid: Optional[np.ndarray] = None,
    periodic: bool = False,
) -> Psd:
    """Isotropic PSD C(q) = A/N^2 |H(q)|^2 of the valid heights minus their mean.

    Logarithmic bins from 2 pi / max(Lx, Ly) to min(pi/dx, pi/dy); a free map is Hann-windowed,
    invalid points enter as zero, and both are compensated so that sum(C * modes)/A is the
    variance of the valid heights for power spread evenly. Returns Psd(q_low, q_high, q, psd,
    modes), empty bins left out.
    """
    heights, valid = _map(heights, valid)
    dx, dy = _spacings(spacing)
    if not 1 <= integer("bins", bins) <= _MAX_PSD_BINS:
        raise ValueError(f"bins must be an integer 1 … {_MAX_PSD_BINS}, got {bins!r}")
    q_low, q_high, q, power, modes = _isotropic_psd(heights, dx, dy, int(bins), valid=valid, periodic=bool(periodic))
    return Psd(q_low, q_high, q, power, modes.astype(np.int64))


def fill_invalid(heights: np.ndarray, valid: np.ndarray, *, periodic: bool = False) -> np.ndarray:
    """The heights with every invalid point (False in `valid`) filled by harmonic interpolation.

    The filled heights solve the discrete Laplace equation with the valid points fixed and a
    zero normal derivative at the edge of a free map: SurfaceTopography's
    interpolate_undefined_data. Raises ValueError when no point is valid.
    """
    heights, mask = _map(heights, valid)
    assert mask is not None
    return _fill_invalid(heights, mask, periodic=bool(periodic))
