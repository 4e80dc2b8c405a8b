"""Tolerance bands from the exact design sensitivities: how far a quantity can be from its nominal value at every
position when the dimensions are made within their tolerances, to first order, from one run.

For a quantity y and toleranced dimensions p_k known to +-t_k, with s_k = dy/dp_k the exact first-order design
sensitivity at a position (:mod:`mechfem.optimise`, ``docs/optimisation.md``):

* worst case: ``W = sum_k |s_k| t_k``, the largest first-order deviation of y over every combination of the
  dimensions within their tolerances;
* root sum of squares: ``R = sqrt(sum_k (s_k t_k)^2)``; for dimensions drawn independently and uniformly within
  +-t_k, the first-order standard deviation of y is ``R / sqrt(3)``; for normal draws with t_k = 3 sigma_k, it is
  ``R / 3``.

Each dimension's share at a position is ``|s_k| t_k / W`` of the worst case and ``(s_k t_k)^2 / R^2`` of the
variance. A deck's TOLERANCE block (``TOL``, ``TOLX``, ``BUFTOL``) and :func:`tolerance_bands` of a
:class:`~mechfem.Mechanism` compute the same, through the same deck reader and core (``docs/tolerance.md``)::

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
    from mechfem.model import Mechanism, Motion
    from mechfem.optimise import Quantity
    from mechfem.result import RunResult

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
    buffer: int | None = None
    """A deck's BUFTOL b (the worst case; the RSS band is b + 1); None from Python."""
    source: int | None = None
    """A deck's buffer bsrc whose band this is."""

    @property
    def worst(self) -> FloatArray:
        """The worst-case band sum_k |s_k| t_k at every position (y lies within value +- worst to first order)."""
        return np.asarray(np.abs(self.sensitivity) @ self.tolerances, dtype=np.float64)

    @property
    def rss(self) -> FloatArray:
        """The root-sum-of-squares band sqrt(sum_k (s_k t_k)^2) at every position."""
        return np.asarray(np.sqrt(((self.sensitivity * self.tolerances) ** 2).sum(axis=1)), dtype=np.float64)

    @property
    def at(self) -> int:
        """The position (0-based) where the worst-case band is widest (the first of equal ones)."""
        return int(np.argmax(self.worst))

    def shares(self, position: int | None = None) -> list[Share]:
        """Every dimension's share of the band at ``position`` (default :attr:`at`), largest first: which
        tolerance to tighten."""
        k = self.at if position is None else position
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
        from mechfem import optional

        pd = optional.pandas()

        columns: dict[str, FloatArray] = {n: self.inputs[:, j] for j, n in enumerate(self.input_names)}
        for name, b in self.bands.items():
            columns[name] = b.value
            columns[f"{name} worst"] = b.worst
            columns[f"{name} rss"] = b.rss
        return pd.DataFrame(columns, index=pd.RangeIndex(self.positions, name="position"))


def _of_core(d: Mapping[str, Any], dim_names: Sequence[str], names: Sequence[str | None] | None) -> ToleranceBands:
    """The bands from what :func:`mechfem._core.deck_tolerance` computed, each named by ``names`` or else by its
    buffer's label."""
    n, nj = int(d["positions"]), int(d["dofs"])
    dims = [(int(k), int(num), float(t)) for k, num, t, _ in d["dims"]]
    bands = [(int(src), int(b)) for src, b, _ in d["bands"]]
    nb, nv = len(bands), len(dims)
    values = np.asarray(d["values"], dtype=np.float64).reshape(n, nb)
    gradient = np.asarray(d["gradient"], dtype=np.float64).reshape(n, nb, nv)
    t = np.array([x[2] for x in dims], dtype=np.float64)
    labels = [(str(a), str(u)) for a, u in d["labels"]]
    out = ToleranceBands(
        tolerances=dict(zip(dim_names, t.tolist(), strict=True)),
        units=dict(zip(dim_names, map(str, d["dim_units"]), strict=True)),
        inputs=np.asarray(d["inputs"], dtype=np.float64).reshape(n, nj),
        input_names=[f"input{j + 1}" for j in range(nj)],
        input_units=[str(u) for u in d["input_units"]],
        positions=n,
    )
    for q, ((src, b), (label, unit)) in enumerate(zip(bands, labels, strict=True)):
        name = (names[q] if names is not None else None) or label
        out.bands[name] = Band(name, unit, values[:, q], gradient[:, q, :], t, list(dim_names), b, src)
    return out


def _deck_names(result: RunResult, d: Mapping[str, Any]) -> tuple[list[str], list[str]]:
    """The names of a deck's toleranced dimensions and inputs: NAMES, else ``row r`` (with its formula) or ``x i``."""
    model = result.model
    dims = []
    for kind, number, _, _ in d["dims"]:
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
    d = _core.deck_tolerance(text, os.fspath(deck), os.fspath(base))
    if d is None:
        return None
    dims, inputs = _deck_names(result, d)
    bands = _of_core(d, dims, None)
    bands.input_names = inputs
    return bands


def _expanded(mech: Mechanism, tolerances: Mapping[str, float]) -> dict[str, float]:
    """``tolerances`` with a point's name given as its two co-ordinates, each with the point's tolerance."""
    from mechfem.model import Point

    out: dict[str, float] = {}
    for name, t in tolerances.items():
        obj = mech[name]
        if isinstance(obj, Point):
            out[f"{obj.name}.x"] = float(t)
            out[f"{obj.name}.y"] = float(t)
        else:
            out[name] = float(t)
    return out


def _dimension(mech: Mechanism, nb: Any, name: str) -> tuple[str, int]:
    """``(keyword, deck number)`` of a toleranced dimension: ``TOL`` of a prescribed row, ``TOLX`` of a fixed
    co-ordinate."""
    from mechfem.model import Coordinate, FormParameter, Row

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
        return "TOLX", int(nb.coord_number[obj])
    if not isinstance(obj, Row) or obj.kind != "prescribed" or obj.value is None:
        raise ValueError(f"{name!r} is no prescribed dimension with a value: it cannot have a tolerance")
    return "TOL", int(nb.row_dest[obj])


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
    :class:`~mechfem.Q` for a transfer function). The mechanism is written as a deck with a TOLERANCE block and
    evaluated by the deck reader and the core in one run of the motion (default the mechanism's), with the exact
    first-order design sensitivities at every position; see the module's docstring for the formulas."""
    from mechfem import deckio
    from mechfem.errors import MechfemError
    from mechfem.optimise import _Deck

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
    written = deckio.write(mechanism, motion, deck.storage)
    if written.simulated:
        raise ValueError(
            "tolerance bands need a prescribed motion: the forces move "
            + ", ".join(repr(n) for n in written.simulated)
            + " (a Dynamic motion), and a simulation has no design sensitivities"
        )
    nb = written.numbering
    lines = ["TOLERANCE"]
    for name, t in dims.items():
        kw, number = _dimension(mechanism, nb, name)
        lines.append(f"{kw} {number} {t!r}")
    first = max(sources) + 1
    for k, b in enumerate(sources):
        lines.append(f"BUFTOL {b} {first + 2 * k}")
    head, end = written.text.rsplit("END\n", 1)
    text = head + "\n".join(lines) + "\nEND\n" + end
    with deckio.tables_dir(written.tables) as base:
        try:
            d = _core.deck_tolerance(text, written.path, base)
        except MechfemError as e:
            # The core names the deck's numbers; the model's names are the user's.
            raise deckio.translate(e, written, mechanism.name) from None
    if d is None:
        raise ValueError(f"{mechanism.name!r} gave no tolerance bands")
    if int(d["positions"]) < motion.steps + 1:
        import warnings

        from mechfem.errors import IncompleteRunWarning

        warnings.warn(
            f"the motion stopped after position {d['positions']} of {motion.steps + 1} (run the mechanism to see "
            "why): the bands are those of the positions up to there",
            IncompleteRunWarning,
            stacklevel=2,
        )
    # A quantity given by name keeps it; an object or a transfer function (Q) takes its buffer's label (dpsi/dphi).
    out = _of_core(d, list(dims), [q if isinstance(q, str) else None for q in quantities])
    inputs = nb.inputs
    out.input_names = [r.name for r in inputs]
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
