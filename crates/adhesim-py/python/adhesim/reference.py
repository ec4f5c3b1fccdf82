"""Closed-form references for a rigid indenter on an elastic half-space of contact
modulus E*, evaluated by the library's own formulas (bit-identical to Rust).

Signs as everywhere in adhesim: force > 0 compressive (< 0 tensile), depth > 0 into the
body. Array arguments may be scalars or array-likes of any shape; results have the same
shape. Every function raises ValueError naming the argument for a radius or modulus that
is not finite and > 0, a negative work of adhesion, or a non-finite depth.
"""

from __future__ import annotations

from typing import Dict, Optional, Tuple

import numpy as np
from numpy.typing import ArrayLike

from ._args import floats, integer, number
from . import _adhesim
from ._adhesim import johnson_parameter

__all__ = ["hertz", "jkr", "jkr_at_depth", "jkr_scales", "flat_punch", "johnson_parameter"]


def _flat(name: str, values: ArrayLike):
    array = floats(name, values)
    return np.ascontiguousarray(array.ravel()), array.shape


def _scalars(radius: float, contact_modulus: float, work_of_adhesion: float) -> Tuple[float, float, float]:
    """R, E* and gamma as floats, or a TypeError naming the one that is not a number."""
    return (
        number("radius", radius),
        number("contact_modulus", contact_modulus),
        number("work_of_adhesion", work_of_adhesion),
    )


def hertz(radius: float, contact_modulus: float, depth: ArrayLike) -> Dict[str, np.ndarray]:
    """Hertz (1882) contact of a paraboloid of radius R pressed to depth d.

    Parameters
    ----------
    radius : float
        R (length, > 0).
    contact_modulus : float
        E* (pressure, > 0).
    depth : array_like
        d (length); d <= 0 gives no contact.

    Returns
    -------
    dict of arrays shaped like `depth`
        ``depth``, ``force`` F = (4/3) E* R^(1/2) d^(3/2)
        (> 0 compressive), ``contact_radius`` a = (R d)^(1/2).
    """
    flat, shape = _flat("depth", depth)
    force, contact_radius = _adhesim._hertz(number("radius", radius), number("contact_modulus", contact_modulus), flat)
    return {
        "depth": flat.reshape(shape),
        "force": force.reshape(shape),
        "contact_radius": contact_radius.reshape(shape),
    }


def jkr(
    radius: float,
    contact_modulus: float,
    work_of_adhesion: float,
    contact_radius: Optional[ArrayLike] = None,
    points: int = 200,
) -> Dict[str, np.ndarray]:
    """Johnson-Kendall-Roberts (1971) curve of a paraboloid, parametric in the contact
    radius a (both branches, stable and unstable), with the paper's normalisation
    (Popov et al. 2021, Eqs. 2-4).

    Parameters
    ----------
    radius : float
        R (length, > 0).
    contact_modulus : float
        E* (pressure, > 0).
    work_of_adhesion : float
        gamma (energy per area, >= 0).
    contact_radius : array_like, optional
        a values (length, >= 0); default `points` values from 0 to
        3 a_JKR.
    points : int
        number of default a values.

    Returns
    -------
    dict of arrays
        ``contact_radius`` a, ``force`` F = 4E*a^3/(3R) - (8 pi gamma E* a^3)^(1/2)
        (< 0 tensile), ``depth`` d = a^2/R - (2 pi gamma a / E*)^(1/2).
    """
    if contact_radius is None:
        scale = _adhesim.jkr_scales(*_scalars(radius, contact_modulus, work_of_adhesion))
        if scale["contact_radius"] == 0.0:
            # gamma = 0 has no JKR scale: the default radii were all 0 (a curve of zeros).
            raise ValueError(
                f"work_of_adhesion = {work_of_adhesion!r} gives no JKR contact radius a_JKR to "
                "place the default contact radii: give contact_radius= (with gamma = 0 the curve is Hertz's)"
            )
        contact_radius = np.linspace(0.0, 3.0 * scale["contact_radius"], integer("points", points))
    flat, shape = _flat("contact_radius", contact_radius)
    force, depth = _adhesim._jkr_curve(*_scalars(radius, contact_modulus, work_of_adhesion), flat)
    return {"contact_radius": flat.reshape(shape), "force": force.reshape(shape), "depth": depth.reshape(shape)}


def jkr_at_depth(
    radius: float, contact_modulus: float, work_of_adhesion: float, depth: ArrayLike
) -> Dict[str, np.ndarray]:
    """JKR force and contact radius at given depths on the branch that is stable under
    displacement control (a >= 9^(-1/3) a_JKR): what a quasi-static retraction follows.

    Returns
    -------
    dict of arrays shaped like `depth`
        ``depth``, ``force``, ``contact_radius``,
        ``in_contact`` (bool). Below the jump depth -9^(1/3)|d_JKR| the contact is lost:
        in_contact False, force 0, contact_radius 0.
    """
    flat, shape = _flat("depth", depth)
    force, contact_radius, contact = _adhesim._jkr_at_depth(
        *_scalars(radius, contact_modulus, work_of_adhesion), flat
    )
    return {
        "depth": flat.reshape(shape),
        "force": force.reshape(shape),
        "contact_radius": contact_radius.reshape(shape),
        "in_contact": contact.reshape(shape),
    }


def jkr_scales(radius: float, contact_modulus: float, work_of_adhesion: float) -> Dict[str, float]:
    """JKR scales, signed: ``force`` F_JKR = -(3/2) pi gamma R (pull-off force under load
    control, < 0 tensile), ``depth`` d_JKR = -(3 pi^2 gamma^2 R / (64 E*^2))^(1/3) and
    ``contact_radius`` a_JKR = (9 pi gamma R^2 / (8 E*))^(1/3) at that point, and
    ``jump_depth`` -9^(1/3)|d_JKR|, where contact is lost under displacement control.
    """
    return _adhesim.jkr_scales(*_scalars(radius, contact_modulus, work_of_adhesion))


def flat_punch(
    radius: float,
    contact_modulus: float,
    depth: Optional[ArrayLike] = None,
    work_of_adhesion: float = 0.0,
) -> Dict[str, object]:
    """Flat circular punch of radius a (Boussinesq 1885; Kendall 1971 for adhesion).

    Parameters
    ----------
    radius : float
        punch radius a (length, > 0).
    contact_modulus : float
        E* (pressure, > 0).
    depth : array_like, optional
        optional depths d (length) at which to give the force while in full
        contact, F = 2E*a d (< 0 tensile for d < 0, down to the Kendall pull-off).
    work_of_adhesion : float
        gamma (energy per area, >= 0) for the pull-off values.

    Returns
    -------
    dict
        ``stiffness`` 2E*a (scalar), ``pull_off_force`` -(8 pi a^3 E* gamma)^(1/2)
        (Kendall, < 0 tensile), ``pull_off_depth`` -(2 pi a gamma / E*)^(1/2); with
        `depth` also ``depth`` and ``force`` arrays.
    """
    stiffness, pull_off_force, pull_off_depth = _adhesim._flat_punch(
        *_scalars(radius, contact_modulus, work_of_adhesion)
    )
    result: Dict[str, object] = {
        "stiffness": stiffness,
        "pull_off_force": pull_off_force,
        "pull_off_depth": pull_off_depth,
    }
    if depth is not None:
        flat, shape = _flat("depth", depth)
        if not np.all(np.isfinite(flat)):
            raise ValueError(f"depth must be finite, got {flat[~np.isfinite(flat)][0]}")
        result["depth"] = flat.reshape(shape)
        result["force"] = (stiffness * flat).reshape(shape)
    return result
