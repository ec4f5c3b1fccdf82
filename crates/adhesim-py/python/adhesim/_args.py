"""Checked conversions of the pure-Python functions' arguments: every error names the
argument and its value, in the words of the compiled classes' own checks
(``src/convert.rs``: ``radius must be a number, got str 'x'``), where ``float(x)`` said only
"could not convert string to float: 'x'"."""

from __future__ import annotations

import numbers
from typing import Any, Optional, Tuple

import numpy as np


def _refused(name: str, value: Any, expected: str) -> TypeError:
    return TypeError(f"{name} must be {expected}, got {type(value).__name__} {value!r}")


def number(name: str, value: Any) -> float:
    """``value`` as a float: a Python or numpy real number (not a bool or a string), else a
    ``TypeError`` naming ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _refused(name, value, "a number")
    return float(value)


def optional_number(name: str, value: Any) -> Optional[float]:
    """:func:`number`, with None kept."""
    return None if value is None else number(name, value)


def integer(name: str, value: Any) -> int:
    """``value`` as an int: a Python or numpy integer (not a bool), else a ``TypeError``
    naming ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise _refused(name, value, "an integer")
    return int(value)


def pair(name: str, value: Any, one_for_both: bool = False) -> Tuple[float, float]:
    """A pair of numbers (dx, dy), or with ``one_for_both`` one number for both; a
    ``TypeError`` naming ``name`` for anything else."""
    expected = "a number or a pair of numbers" if one_for_both else "a pair of numbers"
    if isinstance(value, (str, bytes)) or np.ndim(value) not in (0, 1):
        raise _refused(name, value, expected)
    if np.ndim(value) == 0:
        if not one_for_both:
            raise _refused(name, value, expected)
        both = number(name, value)
        return both, both
    items = list(value)
    if len(items) != 2:
        raise _refused(name, value, expected)
    return number(f"{name}[0]", items[0]), number(f"{name}[1]", items[1])


def floats(name: str, values: Any) -> np.ndarray:
    """``values`` as a contiguous float64 array (numpy's array_like), or a ``TypeError``
    naming ``name`` where numpy cannot convert it."""
    try:
        # np.asarray keeps a scalar 0-d (np.ascontiguousarray would make it 1-d, and the
        # results of a scalar input would come back as arrays of one value).
        array = np.asarray(values, dtype=np.float64)
        return array if array.flags.c_contiguous else np.ascontiguousarray(array)
    except (TypeError, ValueError) as error:
        got = f"{type(values).__name__} {values!r}"
        raise TypeError(f"{name} must be array_like of floats, got {got}: {error}") from None
