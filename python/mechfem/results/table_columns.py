"""The columns of a run's :meth:`~mechfem.RunResult.table` and the unit of each (:meth:`~mechfem.RunResult.table_units`,
``to_pandas().attrs["units"]``): every input, output and moving co-ordinate with its transfer functions, velocity and
acceleration, then the dynamics' columns, each unit worked out from the quantity's and its inputs' in the words of
the unit algebra (:mod:`mechfem.results.labels`) and said in the run's units."""

from __future__ import annotations

from typing import Any

from mechfem.results import designer, labels
from mechfem.results.result_tables import FloatArray, NotOfKindError


def columns(result: Any, coordinates: bool, unit: str | None) -> tuple[dict[str, FloatArray], dict[str, str]]:
    """The columns of ``result.table(coordinates, unit)`` and the unit of each, in the run's units or in ``unit``
    where it applies to a column (:meth:`~mechfem.RunResult.table_units`)."""
    me = result
    inputs, outputs, coords = me._names.columns(coordinates)
    names = [r.name for r in inputs]
    single = len(names) == 1
    out: dict[str, FloatArray] = {"time": me.time.copy(), "det": me.det.copy()}
    units = {"time": labels.unit_in(me, "s"), "det": labels.unit_in(me, labels.det_unit(me))}
    per = [labels.input_unit(me, j) for j in range(1, len(names) + 1)]

    def put(key: str, words: str, get: Any, *args: Any) -> None:
        try:
            try:
                out[key] = get(*args, unit=unit)
                units[key] = labels.unit_in(me, words, unit)
            except NotOfKindError:
                out[key] = get(*args)
                units[key] = labels.unit_in(me, words)
        except KeyError:
            if me.named:
                raise

    def add(name: str, ref: object, base: str) -> None:
        put(name, base, me.value, ref)
        for j, a in enumerate(names):
            put(f"{name}'" if single else f"{name}'({a})", labels.over(base, per[j]), me.value, ref, 1, j + 1)
            for m, b in enumerate(names[j:], j):
                den = labels.squared(per[j], per[m])
                key = f"{name}''" if single else f"{name}''({a},{b})"
                put(key, labels.over(base, den), me.value, ref, 2, j + 1, m + 1)
        put(f"{name}_dot", labels.over(base, "s"), me.velocity, ref)
        put(f"{name}_ddot", labels.over(base, "s^2"), me.acceleration, ref)

    def unit_of(ref: object) -> str:
        try:
            return labels.value_unit(me, ref)
        except KeyError:
            return ""

    for j, r in enumerate(inputs):
        put(r.name, per[j], me.input, r)
        put(f"{r.name}_dot", labels.over(per[j], "s"), me.velocity, r)
        put(f"{r.name}_ddot", labels.over(per[j], "s^2"), me.acceleration, r)
    for r in outputs:
        add(r.name, r, unit_of(r))
    for c in coords:
        add(c.name, c, unit_of(c))
    out.update(designer.dynamic_columns(me))
    units.update(designer.dynamic_units(me))
    return out, {k: units.get(k, "") for k in out}


__all__ = ["columns"]
