"""Effective works of adhesion and power laws fitted to simulated or measured curves
(Popov et al. 2021, Sect. 2.3), by the library's least-squares fits.

Raise ValueError naming the argument for arrays of different lengths, a radius or
modulus that is not finite and > 0, or no usable point.
"""

from __future__ import annotations

import warnings
from typing import Dict, Tuple

import numpy as np
from numpy.typing import ArrayLike

from ._args import number
from . import _adhesim
from ._adhesim import johnson_parameter

__all__ = ["jkr_work_of_adhesion", "jkr_depth_work_of_adhesion", "power_law", "johnson_parameter"]


def _vector(values: ArrayLike) -> np.ndarray:
    return np.ascontiguousarray(np.asarray(values, dtype=np.float64).ravel())


def _warn_left_out(function: str, left_out: int, total: int, why: str) -> None:
    """A UserWarning counting the points a fit leaves out (it dropped them silently)."""
    if left_out:
        warnings.warn(f"{function}: {left_out} of {total} points left out ({why})", stacklevel=3)


def jkr_work_of_adhesion(
    contact_radius: ArrayLike, force: ArrayLike, radius: float, contact_modulus: float
) -> Dict[str, float]:
    """Effective gamma of one branch from force-contact-radius pairs: least squares of
    F = 4E*a^3/(3R) - (8 pi gamma E* a^3)^(1/2), linear in gamma^(1/2).

    Parameters
    ----------
    contact_radius : array_like
        a per point (length); points with a <= 0 are skipped.
    force : array_like
        F per point (> 0 compressive).
    radius : float
        R of the indenter (length, > 0).
    contact_modulus : float
        E* (pressure, > 0).

    Returns
    -------
    dict
        ``work_of_adhesion`` gamma (>= 0, energy per area), ``residual_rms`` (force),
        ``points`` used; a ``UserWarning`` counts the points left out.
    """
    result = _adhesim._fit_jkr_force(
        _vector(contact_radius), _vector(force), number("radius", radius), number("contact_modulus", contact_modulus)
    )
    total = _vector(contact_radius).size
    _warn_left_out("jkr_work_of_adhesion", total - int(result["points"]), total, "contact_radius <= 0")
    return result


def jkr_depth_work_of_adhesion(
    contact_radius: ArrayLike, depth: ArrayLike, radius: float, contact_modulus: float
) -> Dict[str, float]:
    """Effective gamma from depth-contact-radius pairs, d = a^2/R - (2 pi gamma a/E*)^(1/2)
    (paper Eq. 13, used for gamma_3 of rolling contacts). Same arguments and result as
    :func:`jkr_work_of_adhesion` with depths (length, > 0 into the body) for forces.
    """
    result = _adhesim._fit_jkr_depth(
        _vector(contact_radius), _vector(depth), number("radius", radius), number("contact_modulus", contact_modulus)
    )
    total = _vector(contact_radius).size
    _warn_left_out("jkr_depth_work_of_adhesion", total - int(result["points"]), total, "contact_radius <= 0")
    return result


def power_law(t: ArrayLike, y: ArrayLike) -> Tuple[float, float]:
    """y = c t^n by least squares in log-log (paper Eq. 15), over points with t, y > 0
    (a ``UserWarning`` counts the others, left out).

    Returns
    -------
    c, n : float
        The prefactor and the exponent.
    """
    t, y = _vector(t), _vector(y)
    result = _adhesim._fit_power_law(t, y)
    if t.size == y.size:
        _warn_left_out("power_law", int(np.count_nonzero(~((t > 0) & (y > 0)))), t.size, "t <= 0 or y <= 0")
    return result
