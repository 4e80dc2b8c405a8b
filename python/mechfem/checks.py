"""Checks of the values the model API is given: finite numbers and names."""

from __future__ import annotations

import math


def finite(value: float, what: str) -> float:
    """``value`` as a float; a ValueError naming ``what`` when it is NaN or infinite."""
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{what} must be a finite number, not {value!r}")
    return v


def check_name(name: str) -> str:
    """``name`` when it can name a part of a mechanism (it is written into deck comments); else a ValueError."""
    if not isinstance(name, str) or not name or name != name.strip() or any(c in name for c in "\r\n\t"):
        raise ValueError(f"a name must be a non-empty string without surrounding blanks or line breaks: {name!r}")
    return name
