"""Dynamic design for the optimiser: a DYN ANA deck's designs evaluated with inverse dynamics at every position
(``_core.DynamicDesignModel``: the dynamic buffers with their exact sensitivities to dimensions and to the mass
model), the variables of the mass model by deck number and by name, the magnitude of a planar force as one
objective (RMS or peak shaking force), and the reduction of a buffer's values over the positions to one number.

Imports only the compiled core and numpy, so that :mod:`mechfem.design.engine` imports it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import numpy.typing as npt

import mechfem._core as _core

FloatArray = npt.NDArray[np.float64]

MASS_ITEMS = ("MASS", "U", "V", "J", "PMASS", "INERTIA")
"""The VARYM items in the order of their variable kinds 10..15."""

MASS_UNITS = {10: "mass", 11: "length", 12: "length", 13: "mass·length^2", 14: "mass", 15: "mass·length^2"}
"""The unit of each variable kind of the mass model, in the words of the unit algebra
(:func:`mechfem.results.labels.shown`)."""


def mass_kind(item: str) -> int:
    """The variable kind of a VARYM item (``"U"`` -> 3)."""
    return 10 + MASS_ITEMS.index(item.upper())


def mass_name(kind: int, number: int) -> str:
    """``U 1``: a mass variable as its VARYM line writes it."""
    return f"{MASS_ITEMS[kind - 10]} {number}"


def dynamic_deck_model(
    text: str, path: str, base_dir: str
) -> Callable[[list[tuple[int, int]], list[int], list[tuple[int, int]]], _core.DynamicDesignModel]:
    """The design model of the DYN ANA deck ``text`` (named ``path``, its files read from ``base_dir``)."""

    def of(
        variables: list[tuple[int, int]], buffers: list[int], extrema: list[tuple[int, int]]
    ) -> _core.DynamicDesignModel:
        return _core.DynamicDesignModel(text, path, base_dir, variables, buffers, extrema)

    return of


def magnitude(a: FloatArray, ga: FloatArray, b: FloatArray, gb: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``sqrt(a^2 + b^2)`` at every position and its gradient (positions x variables); 0 where the magnitude is
    0, where its RMS is smooth and its largest value is decided elsewhere."""
    m = np.hypot(a, b)
    safe = np.where(m > 0, m, 1.0)
    g = (a[:, None] * ga + b[:, None] * gb) / safe[:, None]
    return m, np.where((m > 0)[:, None], g, 0.0)


def reduced(reduce: str, v: FloatArray, g: FloatArray) -> tuple[float, FloatArray]:
    """One number from a buffer's values over the positions, and its gradient (at the position that decides it,
    for MAX and MAXABS)."""
    if reduce == "max":
        k = int(np.argmax(v))
        return float(v[k]), g[k]
    if reduce == "maxabs":
        k = int(np.argmax(np.abs(v)))
        return float(abs(v[k])), np.sign(v[k]) * g[k]
    if reduce == "rms":
        rms = float(np.sqrt(np.mean(v**2)))
        return rms, (v @ g) / (len(v) * rms) if rms > 0 else np.zeros(g.shape[1])
    return float(v[-1]), g[-1]
