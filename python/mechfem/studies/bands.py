"""Tolerance bands from the exact design sensitivities: how far a quantity can be from its nominal value at every
position when the dimensions are made within their tolerances, to first order, from one run.

For a quantity y and toleranced dimensions p_k known to +-t_k, with s_k = dy/dp_k the exact first-order design
sensitivity at a position (:mod:`mechfem.design.optimise`, ``docs/optimisation.md``):

* worst case: ``W = sum_k |s_k| t_k``, the largest first-order deviation of y over every combination of the
  dimensions within their tolerances;
* root sum of squares: ``R = sqrt(sum_k (s_k t_k)^2)``; for dimensions drawn independently and uniformly within
  +-t_k, the first-order standard deviation of y is ``R / sqrt(3)``; for normal draws with t_k = 3 sigma_k, it is
  ``R / 3``.

Each dimension's share at a position is ``|s_k| t_k / W`` of the worst case and ``(s_k t_k)^2 / R^2`` of the
variance. A deck's TOLERANCE block (``TOL``, ``TOLX``, ``BUFTOL``) and :func:`tolerance_bands` of a
:class:`~mechfem.Mechanism` compute the same, in the core (``mechfem_core::run::tolerance``), from the same compiled
model: a deck's from its text, a mechanism's from the typed builder, no deck text written (``docs/tolerance.md``)::

    bands = mechfem.tolerance_bands(fourbar, {"crank.length": 0.01, "B0": 0.02}, ["psi"])
    bands["psi"].worst.max(), bands["psi"].at, bands["psi"].shares()
    bands.to_pandas()
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from mechfem import _core

if TYPE_CHECKING:
    from mechfem.design.optimise import Quantity
    from mechfem.model.mechanism import Mechanism, Motion
    from mechfem.results.result import RunResult

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Share:
    """One dimension's part of a band at one position."""

    dimension: str
    sensitivity: float
    """d y / d p at that position, in the quantity's unit per the dimension's unit."""
    tolerance: float
    deviation: float
    """|s| t: how far the dimension alone moves the quantity, in the quantity's unit."""
    of_worst: float
    """|s| t / W, a fraction of the worst case (the shares add up to 1)."""
    of_variance: float
    """(s t)^2 / R^2, a fraction of the RSS band's square (the shares add up to 1)."""


@dataclass
class Band:
    """The band of one quantity at every position."""

    name: str
    """The quantity's name (a deck's buffer label)."""
    unit: str
    value: FloatArray
    """The nominal value at every position."""
    sensitivity: FloatArray
    """Positions x dimensions: d y / d p_k."""
    tolerances: FloatArray
    """t_k of every dimension, in the order of ``dimensions``."""
    dimensions: list[str]
    worst: FloatArray
    """The worst-case band sum_k |s_k| t_k at every position (y lies within value +- worst to first order)."""
    rss: FloatArray
    """The root-sum-of-squares band sqrt(sum_k (s_k t_k)^2) at every position."""
    at: int
    """The position (0-based) where the worst-case band is widest (the first of equal ones)."""
    widest: list[Share]
    """Every dimension's share of the band at :attr:`at`, largest first, as the core computed them."""
    buffer: int | None = None
    """A deck's BUFTOL b (the worst case; the RSS band is b + 1); None from Python."""
    source: int | None = None
    """A deck's buffer bsrc whose band this is."""

    def shares(self, position: int | None = None) -> list[Share]:
        """Every dimension's share of the band at ``position`` (default :attr:`at`), largest first: which
        tolerance to tighten."""
        if position is None or position == self.at:
            return list(self.widest)
        k = position
        s = self.sensitivity[k]
        dev = np.abs(s) * self.tolerances
        w, r2 = float(dev.sum()), float((dev**2).sum())
        out = [
            Share(
                name,
                float(s[i]),
                float(self.tolerances[i]),
                float(dev[i]),
                float(dev[i]) / w if w > 0 else math.nan,
                float(dev[i]) ** 2 / r2 if r2 > 0 else math.nan,
            )
            for i, name in enumerate(self.dimensions)
        ]
        return sorted(out, key=lambda x: -x.deviation)


@dataclass
class ToleranceBands:
    """The bands of every quantity over the motion (see :func:`tolerance_bands`): ``bands`` by name, and the
    input(s) at every position."""

    tolerances: dict[str, float]
    """Every toleranced dimension and its tolerance t (value +- t), in the model's units."""
    units: dict[str, str]
    """The unit of each dimension ("" without units)."""
    inputs: FloatArray
    """Positions x inputs: the input values (in the model's units)."""
    input_names: list[str]
    input_units: list[str]
    bands: dict[str, Band] = field(default_factory=dict)
    positions: int = 0
    """Positions computed (fewer than the motion's when it stopped at a limit position)."""

    def __getitem__(self, name: str) -> Band:
        return self.bands[name]

    def __repr__(self) -> str:
        lines = [f"ToleranceBands({self.positions} positions; tolerances {self.tolerances})"]
        for b in self.bands.values():
            k = b.at
            top = b.shares(k)[0]
            unit = f" {b.unit}" if b.unit else ""
            lines.append(
                f"  {b.name}: worst case +-{b.worst[k]:.6g}{unit} (RSS +-{b.rss[k]:.6g}{unit}) at "
                f"{self.input_names[0]} = {self.inputs[k, 0]:.6g}; largest share {top.dimension} "
                f"{100 * top.of_worst:.1f}%"
            )
        return "\n".join(lines)

    def to_pandas(self) -> Any:
        """One row per position: the inputs, then for every quantity its value, worst-case and RSS band. Needs pandas
        (``pip install 'mechfem[pandas]'``)."""
        from mechfem._util import optional

        pd = optional.pandas()

        columns: dict[str, FloatArray] = {n: self.inputs[:, j] for j, n in enumerate(self.input_names)}
        for name, b in self.bands.items():
            columns[name] = b.value
            columns[f"{name} worst"] = b.worst
            columns[f"{name} rss"] = b.rss
        return pd.DataFrame(columns, index=pd.RangeIndex(self.positions, name="position"))


def _of_core(
    core: _core.ToleranceBands, dim_names: Sequence[str], names: Sequence[str | None] | None
) -> ToleranceBands:
    """The bands the core computed (:class:`mechfem._core.ToleranceBands`), each named by ``names`` or else by its
    buffer's label."""
    t = core.tolerances
    inputs = core.inputs
    out = ToleranceBands(
        tolerances=dict(zip(dim_names, t.tolist(), strict=True)),
        units=dict(zip(dim_names, core.dim_units, strict=True)),
        inputs=inputs,
        input_names=[f"input{j + 1}" for j in range(inputs.shape[1])],
        input_units=list(core.input_units),
        positions=core.positions,
    )
    values, worst, rss, sensitivity = core.values, core.worst, core.rss, core.sensitivity
    labels, bands, widest, shares = core.labels, core.bands, core.widest, core.shares
    for q, ((src, b, _), (label, unit)) in enumerate(zip(bands, labels, strict=True)):
        name = (names[q] if names is not None else None) or label
        at = widest[q]
        top = [Share(dim_names[k], s, float(t[k]), dev, w, v) for k, s, dev, w, v in shares[q]]
        out.bands[name] = Band(
            name,
            unit,
            values[:, q],
            sensitivity[:, q, :],
            t,
            list(dim_names),
            worst[:, q],
            rss[:, q],
            0 if at is None else at,
            top,
            b,
            src,
        )
    return out


def _deck_names(result: RunResult, core: _core.ToleranceBands) -> tuple[list[str], list[str]]:
    """The names of a deck's toleranced dimensions and inputs: NAMES, else ``row r`` (with its formula) or ``x i``."""
    model = result.model
    dims = []
    for kind, number, _, _ in core.dims:
        if int(kind) == 1:
            row = model.prescribed[int(number) - 1]
            dims.append(row.name or f"row {number} ({row.formula()})")
        else:
            c = model.coordinates[int(number) - 1]
            dims.append(c.name or f"x{number}")
    inputs = [model.prescribed[row - 1].name or f"input{j}" for j, row in enumerate(model.dofs, 1)]
    return dims, inputs


def deck_bands(result: RunResult) -> ToleranceBands | None:
    """The bands of the TOLERANCE block of the deck ``result`` ran (None when it has none), named as the deck
    names them. One more run of the motion, with the design sensitivities."""
    deck = Path(result.deck)
    # A named model's run has no deck file of its own (its ``deck`` is the name of the deck written for it).
    if result.named or not deck.is_file():
        return None
    text = deck.read_text(encoding="utf-8", errors="replace")
    if "TOLERANCE" not in text.upper():
        return None
    base = deck.parent if str(deck.parent) else Path(".")
    core = _core.deck_tolerance(text, os.fspath(deck), os.fspath(base))
    if core is None:
        return None
    dims, inputs = _deck_names(result, core)
    bands = _of_core(core, dims, None)
    bands.input_names = inputs
    return bands


def _expanded(mech: Mechanism, tolerances: Mapping[str, float]) -> dict[str, float]:
    """``tolerances`` with a point's name given as its two co-ordinates, each with the point's tolerance."""
    from mechfem.model.mechanism import Point

    out: dict[str, float] = {}
    for name, t in tolerances.items():
        obj = mech[name]
        if isinstance(obj, Point):
            out[f"{obj.name}.x"] = float(t)
            out[f"{obj.name}.y"] = float(t)
        else:
            out[name] = float(t)
    return out


def _dimension(mech: Mechanism, nb: Any, name: str) -> tuple[int, int]:
    """``(kind, number)`` of a toleranced dimension in the model's numbering: 1 and the row of a prescribed value,
    0 and the co-ordinate of a fixed co-ordinate."""
    from mechfem.model.mechanism import Coordinate, FormParameter, Row

    obj = mech[name]
    if isinstance(obj, FormParameter):
        rows = [r for r in nb.prescribed if r.terms == ((1.0, obj),)]
        if not rows:
            raise ValueError(
                f"{name!r} is not prescribed: only a prescribed value or a fixed co-ordinate has a tolerance"
            )
        obj = rows[0]
    if isinstance(obj, Coordinate):
        if not obj.fixed:
            raise ValueError(
                f"{name!r} moves: its place follows from the prescribed rows; give those rows tolerances, or tolerance "
                "a fixed co-ordinate"
            )
        return 0, int(nb.coord_number[obj])
    if not isinstance(obj, Row) or obj.kind != "prescribed" or obj.value is None:
        raise ValueError(f"{name!r} is no prescribed dimension with a value: it cannot have a tolerance")
    if obj in nb.inputs:
        raise ValueError(f"{name!r} is an input: the motion gives its value at every position")
    return 1, int(nb.row_dest[obj])


def tolerance_bands(
    mechanism: Mechanism,
    tolerances: Mapping[str, float],
    quantities: Sequence[Quantity],
    *,
    motion: Motion | None = None,
) -> ToleranceBands:
    """The worst-case and RSS bands of every quantity of ``quantities`` over the motion, when every dimension of
    ``tolerances`` (name -> t, in the model's units: a prescribed length or angle ``"E1.length"``, a fixed
    co-ordinate ``"B0.x"``, a point ``"B0"`` whose co-ordinates each get t) is made within value +- t.

    Quantities are named as for :func:`~mechfem.optimize` (a co-ordinate, a row or an output, or a
    :class:`~mechfem.Q` for a transfer function). The mechanism is built through the typed builder (as
    :meth:`Mechanism.run <mechfem.Mechanism.run>` builds it, no deck text written or read) and the core computes the
    bands in one run of the motion (default the mechanism's), from the exact first-order design sensitivities at
    every position; see the module's docstring for the formulas."""
    from mechfem.deck import deckio
    from mechfem.design.optimise import _Deck
    from mechfem.errors import MechfemError
    from mechfem.run import building

    motion = motion or mechanism.motion
    if motion is None:
        raise ValueError("tolerance bands need a motion: its positions are where the bands are computed")
    if not tolerances:
        raise ValueError("give at least one dimension and its tolerance")
    if not quantities:
        raise ValueError("give at least one quantity whose band to compute")
    dims = _expanded(mechanism, tolerances)
    for name, t in dims.items():
        if not (math.isfinite(t) and t > 0):
            raise ValueError(f"the tolerance of {name!r} must be positive and finite, not {t}")
    deck = _Deck(mechanism)
    sources = [deck.buffer(q) for q in quantities]
    built = building.builder(mechanism, motion, deck.storage)
    if built.simulated:
        raise ValueError(
            "tolerance bands need a prescribed motion: the forces move "
            + ", ".join(repr(n) for n in built.simulated)
            + " (a Dynamic motion), and a simulation has no design sensitivities"
        )
    nb = built.numbering
    items = [(*_dimension(mechanism, nb, name), t) for name, t in dims.items()]
    with deckio.tables_dir(built.tables) as base:
        try:
            core = _core.built_tolerance(built.builder, built.path, base, items, sources)
        except MechfemError as e:
            # The core names the model's numbers; the model's names are the user's.
            raise building.explain(e, built, mechanism, motion, deck.storage) from None
    if core.positions < motion.steps + 1:
        import warnings

        from mechfem.errors import IncompleteRunWarning

        warnings.warn(
            f"the motion stopped after position {core.positions} of {motion.steps + 1} (run the mechanism to see "
            "why): the bands are those of the positions up to there",
            IncompleteRunWarning,
            stacklevel=2,
        )
    # A quantity given by name keeps it; an object or a transfer function (Q) takes its buffer's label (dpsi/dphi).
    out = _of_core(core, list(dims), [q if isinstance(q, str) else None for q in quantities])
    out.input_names = [r.name for r in nb.inputs]
    for band in out.bands.values():
        band.source = None
        band.buffer = None
    return out


def bands_of(result: RunResult) -> ToleranceBands | None:
    """The bands a deck run's TOLERANCE block records, computed once per result."""
    cached = result.__dict__.get("_tolerance_bands", False)
    if cached is not False:
        return cached  # type: ignore[no-any-return]
    bands = deck_bands(result)
    result.__dict__["_tolerance_bands"] = bands
    return bands


__all__ = ["Band", "Share", "ToleranceBands", "bands_of", "deck_bands", "tolerance_bands"]
