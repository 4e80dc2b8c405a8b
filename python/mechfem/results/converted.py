"""What Python made of the dictionaries the compiled module hands out again, kept so that it is made once.

A deck file run again unchanged, to the same position 1, gets the very same model echo and storage dictionaries
(``_core`` keeps them with the compiled deck), and the same report when its run met nothing but its numbers:
:mod:`mechfem.results.result` converts each of them once through a :class:`Converted`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

T = TypeVar("T")


class Converted:
    """Values made from dictionaries, keyed by the dictionary itself, which is held here so that its id is not
    reused; the oldest of ``size`` goes first."""

    def __init__(self, size: int = 48) -> None:
        self._size = size
        self._kept: dict[int, tuple[object, object]] = {}

    def get(self, d: object, make: Callable[[Any], T]) -> T:
        hit = self._kept.get(id(d))
        if hit is not None and hit[0] is d:
            return hit[1]  # type: ignore[return-value]
        value = make(d)
        if len(self._kept) >= self._size:
            self._kept.pop(next(iter(self._kept)))
        self._kept[id(d)] = (d, value)
        return value


__all__ = ["Converted"]
