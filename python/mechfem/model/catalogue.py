"""The element catalogue and the solver's defaults and limits, as the compiled core defines them.

The core is the one place these facts are written (``_core.catalogue()``, ``_core.DEFAULTS``); this module reads
them once at import and gives them the shapes the Python front uses. Nothing here is typed in by hand, so an
element type, a form parameter or a default changes in Rust alone.
"""

from __future__ import annotations

from typing import Literal, cast

import mechfem._core as _core

Dimension = Literal["length", "angle", "ratio", "any"]
"""What a co-ordinate or form parameter measures; ``any``: that of the co-ordinate a ``CRD`` element is put on."""


ElementType = _core.ElementKind
"""One element type of the catalogue: ``type`` (the deck's three-letter name), ``coordinates`` (each one's name and
dimension, deck order), ``slots`` (``P`` a point, ``a`` an angle, ``s`` a scalar), ``forms`` (each form parameter's
deck name and dimension) and ``frame`` (whether it has a frame that can carry a mass)."""

CATALOGUE: dict[str, ElementType] = {e.type: e for e in _core.catalogue()}
"""Every element type by its deck name, in the catalogue's order."""

FORMS: dict[str, tuple[str, ...]] = {t: tuple(f for f, _ in e.forms) for t, e in CATALOGUE.items()}
"""The form parameters of every element type (deck names, in the catalogue's order)."""

SLOTS: dict[str, str] = {t: e.slots for t, e in CATALOGUE.items()}
"""What an element type's co-ordinates are, in deck order: ``P`` a point (x, y), ``a`` an angle, ``s`` a scalar."""

FRAMES: tuple[str, ...] = tuple(t for t, e in CATALOGUE.items() if e.frame)
"""The element types with a frame that can carry a mass."""


def form_dimension(type: str, form: str) -> Dimension:
    """What form parameter ``form`` of an element of type ``type`` measures (``any`` for a ``CRD``'s ``COOR``:
    that of its co-ordinate)."""
    return cast(Dimension, dict(CATALOGUE[type].forms)[form])


def coordinate_dimensions(type: str) -> tuple[Dimension, ...]:
    """What each co-ordinate of an element of type ``type`` measures, in deck order."""
    return tuple(cast(Dimension, k) for _, k in CATALOGUE[type].coordinates)


_DEFAULTS = _core.DEFAULTS

DEFAULT_ACCURACY: float = _DEFAULTS.accuracy
"""How closely Newton meets the prescribed values unless a motion says otherwise (ACCURACY)."""

DEFAULT_MAX_ITER: int = _DEFAULTS.max_iter
"""Newton iterations per position unless a motion says otherwise (MAXITER)."""

MIN_INTEGRATION_TOLERANCE: float = _DEFAULTS.min_integration_tolerance
"""The smallest tolerance a simulation's integrator takes (INTTOL, or ACCURACY when INTTOL is not given)."""

MAX_ITER: int = _DEFAULTS.max_iter_limit
"""The most Newton iterations per position a motion may allow (the largest MAXITER the deck reader accepts)."""

MAX_STEPS: int = _DEFAULTS.max_steps
"""The most steps a motion may have (the largest TSTEPE the deck reader accepts)."""

__all__ = [
    "CATALOGUE",
    "DEFAULT_ACCURACY",
    "DEFAULT_MAX_ITER",
    "FORMS",
    "FRAMES",
    "MAX_ITER",
    "MAX_STEPS",
    "MIN_INTEGRATION_TOLERANCE",
    "SLOTS",
    "Dimension",
    "ElementType",
    "coordinate_dimensions",
    "form_dimension",
]
