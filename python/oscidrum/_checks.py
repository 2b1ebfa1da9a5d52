"""Type checks of the Python API's arguments, shared by its modules."""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np


def is_integer(x: Any) -> bool:
    """An integer, Python's or NumPy's (np.int64 from np.arange or a size), but not a bool."""
    return isinstance(x, numbers.Integral) and not isinstance(x, (bool, np.bool_))


def is_number(x: Any) -> bool:
    """A real number, Python's or NumPy's (int, float, np.float64, ...), but not a bool."""
    return isinstance(x, numbers.Real) and not isinstance(x, (bool, np.bool_))
