"""What one evaluation of a design gives the optimiser: the core's typed ``_core.Evaluation`` (feasibility, the
buffers at every position, their exact gradients, the extrema found), and new ones made from it by the models that
wrap a design model and speak other variables or units (:mod:`~mechfem.design.model_units`,
:mod:`~mechfem.design.frame_angle`, :mod:`~mechfem.design.timing`, :mod:`~mechfem.design.full_rotation`)."""

from __future__ import annotations

from typing import Any, TypeVar

import mechfem._core as _core

T = TypeVar("T", _core.Evaluation, _core.Extremum)

_FIELDS: dict[type, tuple[str, ...]] = {
    _core.Evaluation: (
        "feasible",
        "reason",
        "reason_kind",
        "positions",
        "position_one",
        "report",
        "values",
        "gradient",
        "extrema",
    ),
    _core.Extremum: ("spec", "after", "input", "reference", "value", "gradient"),
}
"""The fields of an evaluation and of an extremum, in the order of their constructors."""


def replaced(obj: T, **changes: Any) -> T:
    """The evaluation or extremum ``obj`` with the fields ``changes`` given anew."""
    fields = {name: getattr(obj, name) for name in _FIELDS[type(obj)]}
    fields.update(changes)
    return type(obj)(**fields)


__all__ = ["replaced"]
