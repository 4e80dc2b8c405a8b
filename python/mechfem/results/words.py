"""How a run's stop reason, its limit positions and its warnings name things.

:class:`Words` speaks the deck's language (an input by its DOF and row, the keywords MOV_FREE, TSTEPE and
INTTOL), as ``mechfem run`` and :func:`mechfem.run_deck` say it; :class:`mechfem.deck.explain.PythonWords` speaks
that of the Python API for a named model.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import mechfem._core as _core
    from mechfem.model.echo import Model

Part = str | tuple[str, object, str]
"""A piece of a message of the core (the ``parts`` of a solver error or of a stop): plain words, or a thing the
message names, as ``(kind, value, deck words)``:

* ``element``, ``coordinate``, ``row``: the deck number; ``coords``, ``rows``: the deck numbers, said in the
  plural;
* ``term``: a term the deck spells its own way, by its code: ``a_degree_of_freedom``, ``free_motion``
  (MOV_FREE), ``dynamic`` (MOV_DYN), ``simulation`` (DYN SIM);
* ``detail``: why an element cannot be evaluated, a dict of ``element`` (its number) and ``kind``:
  ``coincident_points``, ``no_belt_span`` (with ``distance`` and ``difference``, as the message writes them) or
  ``zero_radius`` (with ``radius``, ``R_a`` or ``R_c``).

The deck words are the message's own: joined with the plain words, they give the message as the deck says it."""


class InputName(str):
    """How a sentence names the input of a DOF: its row as the text (``row 6: beta1``, ``row 6: ANGB(1)``), with
    the row's ``name`` ("" unnamed), the ``unit`` its values are in (``deg``; ``rad`` for an angle of a deck without
    UNITS, "" for a length of one) and ``det_unit``, the unit of the model's det(D^c)."""

    name: str
    unit: str
    det_unit: str
    labels: _core.Labels | None
    """The names of the model's co-ordinates and rows, for a message that names them."""

    def __new__(
        cls, text: str, name: str = "", unit: str = "", det_unit: str = "", labels: _core.Labels | None = None
    ) -> InputName:
        self = super().__new__(cls, text)
        self.name, self.unit, self.det_unit, self.labels = name, unit, det_unit, labels
        return self

    def __reduce__(self) -> tuple[object, ...]:
        return (InputName, (str(self), self.name, self.unit, self.det_unit, self.labels))


def input_names(model: Model) -> list[str]:
    """The inputs of ``model`` as sentences name them, with their units from the core (:class:`InputName`)."""
    labels = model.labels
    det_unit = labels.det()[2] if labels is not None else ""
    out: list[str] = []
    for j, dest in enumerate(model.dofs, 1):
        row = model.prescribed[dest - 1]
        unit = labels.input(j)[4] if labels is not None else ""
        text = f"row {row.dest}: {row.name or row.formula()}"
        out.append(InputName(text, row.name or "", unit, det_unit, labels))
    return out


def with_unit(value: str, unit: str) -> str:
    """``value unit``; ``value`` alone without a unit (and for a pure number, ``-``)."""
    return f"{value} {unit}" if unit and unit != "-" else value


def count(n: int, singular: str, plural: str | None = None) -> str:
    """``1 stage``, ``2 stages``; ``plural`` when adding an s is not right."""
    return f"{n} {singular if n == 1 else plural or singular + 's'}"


def input_name(j: int, names: Sequence[str] = ()) -> str:
    """``the input of DOF j``, with its row and form parameters when ``names`` has them."""
    return f"the input of DOF {j} ({names[j - 1]})" if len(names) >= j else f"the input of DOF {j}"


def free_motion_line(j: int, ds: float) -> str:
    """The deck line ``MOV_FREE j ds``, with ds rounded to two significant digits."""
    return f"MOV_FREE {j} {float(f'{ds:.2g}'):g}"


class Words:
    """How a stop reason, a limit or a warning names things. This class speaks the deck's language (an input by
    its DOF, the keywords MOV_FREE, TSTEPE, INTTOL); :class:`mechfem.deck.explain.PythonWords` speaks that of the
    Python API. ``names`` are the inputs' rows (:attr:`RunReport.input_names`)."""

    more_steps = "a larger n in TSTEPE"
    """What gives a motion more, smaller steps."""
    smaller_free_step = "Try a smaller ds in MOV_FREE, with a larger n in TSTEPE to cover the same path."
    free_needs_one_input = "free motion, MOV_FREE, needs a mechanism with one degree of freedom"
    tolerances = "INTTOL"
    """What sets a simulation's tolerances."""
    singular_results = "every buffer made from them (first and second order, velocities, accelerations) holds NaN there"

    def __init__(self, names: Sequence[str] = ()) -> None:
        self.names = list(names)

    def input(self, j: int) -> str:
        """The input of DOF ``j`` as the subject of a sentence."""
        return input_name(j, self.names)

    def _input(self, j: int) -> str:
        return self.names[j - 1] if 1 <= j <= len(self.names) else ""

    def unit(self, j: int) -> str:
        """The unit of the values of the input of DOF ``j`` ("" when not known)."""
        return getattr(self._input(j), "unit", "")

    def at(self, j: int, value: float, digits: int) -> str:
        """The input of DOF ``j`` at ``value``, with its unit: ``input 1 = 2.5 rad``, ``beta1 = 94.9 deg`` for a
        named row."""
        name = getattr(self._input(j), "name", "") or f"input {j}"
        return f"{name} = {with_unit(f'{value:.{digits}g}', self.unit(j))}"

    def det(self, value: float, digits: int) -> str:
        """``det(D^c) = value`` with its unit (the product of the rows' units over the moving co-ordinates')."""
        unit = getattr(self._input(1), "det_unit", "")
        return f"det(D^c) = {with_unit(f'{value:.{digits}g}', unit)}"

    def free_advice(self, ds: float, known: bool, steps: int) -> str:
        """The free motion to use instead of a driven one through a limit position: step ``ds`` (``known``: about
        the steps made so far), over ``steps`` steps."""
        line = free_motion_line(1, ds)
        size = "about the size of the steps made so far" if known else "choose it small against the mechanism"
        return (
            f"Replace the MOV_ line of DOF 1 by `{line}`: each of the n steps of TSTEPE then moves the co-ordinates "
            f"a Euclidean distance {abs(float(line.split()[-1])):g} ({size}) through the limit positions, the "
            f"sign of ds keeps the input's direction, and BUFINP 1 records where the input goes."
        )

    def render(self, parts: Sequence[Part]) -> str:
        """A message of the core from its parts: the plain words as they are, every thing it names by
        :meth:`thing`."""
        return "".join(p if isinstance(p, str) else self.thing(*p) for p in parts)

    def thing(self, kind: str, value: object, deck: str) -> str:
        """A thing a message names (see :data:`Part`), in the deck's words as the core gives them, with the names
        the model gives them beside the numbers: ``element 3 (TR2)``, ``point K (co-ordinates 13, 14)``,
        ``co-ordinate 9 (C.x)``, ``row 6 (phi)``."""
        return deck


def words_of(names: Sequence[str] | Words) -> Words:
    """``names`` when they are :class:`Words`, else the deck's words with those input names."""
    return names if isinstance(names, Words) else Words(names)


__all__ = ["InputName", "Part", "Words", "free_motion_line", "input_name", "input_names", "with_unit", "words_of"]
