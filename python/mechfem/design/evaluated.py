"""What one evaluation of a design gives the optimiser: the core's typed ``_core.Evaluation`` (feasibility, the
buffers at every position, their exact gradients, the extrema found), and new ones made from it by the models that
wrap a design model and speak other variables or units (:mod:`~mechfem.design.model_units`,
:mod:`~mechfem.design.frame_angle`, :mod:`~mechfem.design.timing`, :mod:`~mechfem.design.full_rotation`)."""

from __future__ import annotations

from typing import Any

import numpy as np

import mechfem._core as _core

FIELDS = ("feasible", "reason", "reason_kind", "positions", "position_one", "report", "values", "gradient", "extrema")
"""The fields of an evaluation, in the order of its constructor."""

EXTREMUM_FIELDS = ("spec", "after", "input", "reference", "value", "gradient")
"""The fields of an extremum, in the order of its constructor."""


def replaced(ev: _core.Evaluation, **changes: Any) -> _core.Evaluation:
    """``ev`` with the fields ``changes`` given anew."""
    fields = {name: getattr(ev, name) for name in FIELDS}
    fields.update(changes)
    return _core.Evaluation(**fields)


def replaced_extremum(x: _core.Extremum, **changes: Any) -> _core.Extremum:
    """The extremum ``x`` with the fields ``changes`` given anew."""
    fields = {name: getattr(x, name) for name in EXTREMUM_FIELDS}
    fields.update(changes)
    return _core.Extremum(**fields)


def infeasible(reason: str, kind: str, buffers: int, variables: int) -> _core.Evaluation:
    """An infeasible design without positions, of kind ``kind``, ``buffers`` wide and ``variables`` deep."""
    empty = np.zeros((0, buffers)), np.zeros((0, buffers, variables))
    return _core.Evaluation(False, reason, kind, 0, None, None, *empty, [])


__all__ = ["EXTREMUM_FIELDS", "FIELDS", "infeasible", "replaced", "replaced_extremum"]
