"""What an edit changes of the page's data: the server sends a design whole once (when a deck is opened, or an
optimiser's iteration), and after an edit only the parts that differ from the design the page has (:func:`changes`);
the page puts them into its copy (``merge`` in assets/studio.js). A column's numbers, the mechanism's moving shapes
and the named dimensions change with every edit; the charts' make-up, the columns' names and units, the drawing's
styles, kinds and static shapes do not, and are not sent again."""

from __future__ import annotations

from typing import Any

import numpy as np

#: The key of a change that lists the keys the new data no longer has.
GONE = "__gone__"


def same(old: Any, new: Any) -> bool:
    """Equal as the page would get them (numpy arrays by value, NaN equal to NaN). A list holding arrays (the
    moving shapes per position) is taken as changed without looking: it changes with every edit."""
    if isinstance(new, np.ndarray) or isinstance(old, np.ndarray):
        if not (isinstance(new, np.ndarray) and isinstance(old, np.ndarray)) or old.shape != new.shape:
            return False
        return bool(np.array_equal(old, new, equal_nan=old.dtype.kind == "f" and new.dtype.kind == "f"))
    try:
        return bool(type(old) is type(new) and old == new)
    except ValueError:  # a list of numpy arrays: its truth is ambiguous
        return False


def changes(old: dict[str, Any], new: dict[str, Any]) -> dict[str, Any]:
    """The parts of ``new`` that differ from ``old``, dict by dict: a key whose value is a dict in both is looked
    into, any other value is sent whole when it differs; :data:`GONE` lists the keys of ``old`` that ``new`` has
    not. Merged into ``old`` as the page does, it gives ``new``."""
    out: dict[str, Any] = {}
    for key, value in new.items():
        before = old.get(key, GONE)
        if isinstance(value, dict) and isinstance(before, dict):
            inner = changes(before, value)
            if inner:
                out[key] = inner
        elif before is GONE or not same(before, value):
            out[key] = value
    gone = [key for key in old if key not in new]
    if gone:
        out[GONE] = gone
    return out


def merged(old: dict[str, Any], change: dict[str, Any]) -> dict[str, Any]:
    """``old`` with ``change`` put in, as the page puts it (a new dict; ``old`` is left as it is)."""
    out = dict(old)
    for key, value in change.items():
        if key == GONE:
            continue
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = merged(out[key], value)
        else:
            out[key] = value
    for key in change.get(GONE, []):
        out.pop(key, None)
    return out


__all__ = ["GONE", "changes", "merged", "same"]
