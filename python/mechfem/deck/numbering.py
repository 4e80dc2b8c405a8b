"""How a written deck numbers a model (co-ordinates, elements, rows, inputs) and the written deck itself.

Below the deck writer (:mod:`mechfem.deck.deckio`) so that the loads, the error messages in the model's words and the
run can read the numbering without importing the writer.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from mechfem.model.motion import InputKey, input_dof
from mechfem.model.parts import Coordinate, Element, Row


def number(v: float) -> str:
    """A float as deck text that reads back as exactly the same double."""
    return repr(float(v))


@dataclass
class Numbering:
    """How a written deck numbers the model: co-ordinates, elements, rows and inputs."""

    coords: list[Coordinate]
    """Co-ordinate number i is ``coords[i - 1]``."""
    elements: list[Element]
    """Element number k is ``elements[k - 1]``."""
    prescribed: list[Row]
    """Prescribed row r is ``prescribed[r - 1]``; the last ``n_dof`` are the inputs, in DOF order."""
    dependent: list[Row]
    """Dependent form parameter -k (an output) is ``dependent[k - 1]``."""
    coord_number: dict[Coordinate, int] = field(default_factory=dict)
    row_dest: dict[Row, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.coord_number = {c: i for i, c in enumerate(self.coords, 1)}
        self.row_dest = {r: k for k, r in enumerate(self.prescribed, 1)}
        self.row_dest.update({r: -k for k, r in enumerate(self.dependent, 1)})

    @property
    def inputs(self) -> list[Row]:
        """The input rows in DOF order."""
        return [r for r in self.prescribed if r.kind == "input"]

    @property
    def rows(self) -> list[Row]:
        """Prescribed rows, then outputs: the row order of the results."""
        return self.prescribed + self.dependent

    def dof(self, key: InputKey) -> int:
        """The DOF number (1-based) of an input given by name, DOF number, row or form parameter (None: the only
        input)."""
        return input_dof(key, self.inputs)


@dataclass
class DeckText:
    """A written deck: its text, what each line declares, the numbering and the files of its table motions."""

    text: str
    path: str
    """The name diagnostics show."""
    notes: dict[int, tuple[str, str]]
    """Line -> (what, name), e.g. ``(element, crank)``."""
    numbering: Numbering
    tables: dict[str, str]
    """MOV_FUNC file name -> its text."""
    simulated: list[str] = field(default_factory=list)
    """The inputs that move under the forces (MOV_DYN)."""
