"""Monte Carlo tolerance studies: how much the outputs of a mechanism spread when its lengths and pivots are made
within their tolerances.

Every named value given a tolerance (a prescribed length or angle ``"E1.length"``, ``"kappa"``; a fixed
co-ordinate ``"B0.x"``; a point ``"B0"``, whose two co-ordinates are drawn independently) is drawn ``n`` times
around its value in the mechanism; the draws run as one :func:`~mechfem.sweep` (locally, or on a cluster with an
``executor``), and every output function (a measure: a function of a variant's :class:`~mechfem.RunResult` that
returns one number) is summarised over the variants that ran through the whole motion::

    tol = mechfem.tolerance_study(
        supply,
        {"E1.length": 0.005, "B0": 0.01},
        outputs={"swing": lambda a: np.ptp(a.output("out1"))},
        n=2000,
        seed=1,
    )
    tol.spread["swing"].std, tol.spread["swing"].percentiles[95]
    print(tol)

The linear bands of the same tolerances from the exact design sensitivities, in one run, are
:func:`~mechfem.studies.bands.tolerance_bands` (re-exported here).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from mechfem.model.mechanism import Coordinate, Mechanism, Motion, Point, Row
from mechfem.studies.bands import Band, Share, ToleranceBands, deck_bands, tolerance_bands
from mechfem.studies.batch import Measure, Progress, Study, sweep


@dataclass
class Spread:
    """The spread of one output over the variants that ran through the whole motion (``n`` of them)."""

    nominal: float
    """Its value for the mechanism as drawn (every value at its nominal)."""
    mean: float
    std: float
    """Standard deviation (``ddof=1``)."""
    min: float
    max: float
    percentiles: dict[float, float]
    n: int


@dataclass
class ToleranceStudy:
    """What :func:`tolerance_study` found: the table of draws (parameters, outputs; one row per draw), the spread of
    every output, and how many draws could not be assembled or moved through the whole motion."""

    study: Study
    spread: dict[str, Spread]
    failed: int
    tolerances: dict[str, float] = field(default_factory=dict)
    distribution: str = "normal"

    def __repr__(self) -> str:
        n = len(self.study)
        lines = [f"ToleranceStudy({n} draws, {self.failed} failed; {self.distribution} within {self.tolerances})"]
        for name, s in self.spread.items():
            ps = ", ".join(f"p{p:g} {v:.6g}" for p, v in s.percentiles.items())
            lines.append(
                f"  {name}: nominal {s.nominal:.6g}, mean {s.mean:.6g}, std {s.std:.3g}, "
                f"min {s.min:.6g}, max {s.max:.6g}; {ps}"
            )
        return "\n".join(lines)


def _nominal(mech: Mechanism, name: str) -> float | tuple[float, float]:
    obj = mech[name]
    if isinstance(obj, Point):
        return (obj.x.value, obj.y.value)
    if isinstance(obj, Coordinate):
        return obj.value
    if isinstance(obj, Row) and obj.kind != "output" and obj.value is not None:
        return float(obj.value)
    raise ValueError(f"{name!r} has no value to draw: name a prescribed row, a co-ordinate or a point")


def tolerance_study(
    mechanism: Mechanism,
    tolerances: Mapping[str, float],
    outputs: Mapping[str, Measure],
    *,
    n: int = 1000,
    seed: int | None = None,
    distribution: Literal["normal", "uniform"] = "normal",
    sigmas: float = 3.0,
    percentiles: Sequence[float] = (5.0, 50.0, 95.0),
    motion: Motion | None = None,
    executor: object | None = None,
    chunk_size: int | None = None,
    workers: int | None = None,
    progress: Progress = False,
    order: int | None = 2,
) -> ToleranceStudy:
    """Draws ``n`` variants of ``mechanism`` with each value of ``tolerances`` (name -> tolerance ``t``) within
    its tolerance, runs them (:func:`~mechfem.sweep`, with ``executor``, ``chunk_size``, ``workers``,
    ``progress``, ``order``) and summarises every output of ``outputs`` (name -> function of an
    :class:`~mechfem.RunResult` returning a number).

    ``distribution="normal"``: value + N(0, (t / ``sigmas``)^2), so that ±t holds ``sigmas`` standard deviations
    (99.7% of the parts for the default 3); ``"uniform"``: uniform within value ± t. The draws come from
    ``numpy.random.default_rng(seed)``, one row per variant and one column per drawn co-ordinate in the order
    given, so a seed gives the same draws locally and on a cluster. Variants that cannot be assembled or stop
    before the end of the motion are counted in ``failed`` and left out of the spread.
    """
    if n < 1:
        raise ValueError(f"a tolerance study needs n >= 1 draws, got {n}")
    if distribution not in ("normal", "uniform"):
        raise ValueError(f"distribution must be 'normal' or 'uniform', got {distribution!r}")
    if not outputs:
        raise ValueError("name at least one output to summarise")
    nominal = {name: _nominal(mechanism, name) for name in tolerances}
    widths = [float(t) for t in tolerances.values()]
    if not all(math.isfinite(t) and t >= 0 for t in widths):
        raise ValueError(f"tolerances must be finite and not negative: {dict(tolerances)}")
    columns = sum(2 if isinstance(v, tuple) else 1 for v in nominal.values())
    rng = np.random.default_rng(seed)
    if distribution == "normal":
        unit = rng.standard_normal((n, columns)) / sigmas
    else:
        unit = rng.uniform(-1.0, 1.0, (n, columns))
    sets: list[dict[str, Any]] = [{} for _ in range(n)]
    c = 0
    for (name, v), t in zip(nominal.items(), widths, strict=True):
        if isinstance(v, tuple):
            for k in range(n):
                sets[k][name] = (v[0] + t * float(unit[k, c]), v[1] + t * float(unit[k, c + 1]))
            c += 2
        else:
            for k in range(n):
                sets[k][name] = v + t * float(unit[k, c])
            c += 1
    # The nominal design runs as the first variant; it is not one of the draws.
    study = sweep(
        mechanism,
        [nominal, *sets],
        outputs,
        motion=motion,
        workers=workers,
        progress=progress,
        order=order,
        executor=executor,
        chunk_size=chunk_size,
    )
    table = Study({k: v[1:] for k, v in study.columns.items()}, study.parameters, study.measures, None)
    complete = np.asarray(table["complete"], dtype=bool)
    spread: dict[str, Spread] = {}
    for name in outputs:
        values = np.asarray(table[name], dtype=np.float64)
        good = values[complete & np.isfinite(values)]
        at_nominal = float(study[name][0])
        if good.size == 0:
            spread[name] = Spread(at_nominal, *(math.nan,) * 4, {p: math.nan for p in percentiles}, 0)
            continue
        spread[name] = Spread(
            nominal=at_nominal,
            mean=float(good.mean()),
            std=float(good.std(ddof=1)) if good.size > 1 else 0.0,
            min=float(good.min()),
            max=float(good.max()),
            percentiles={float(p): float(np.percentile(good, p)) for p in percentiles},
            n=int(good.size),
        )
    return ToleranceStudy(table, spread, int(n - complete.sum()), dict(tolerances), distribution)


__all__ = [
    "Band",
    "Share",
    "Spread",
    "ToleranceBands",
    "ToleranceStudy",
    "deck_bands",
    "tolerance_bands",
    "tolerance_study",
]
