"""The model and the storage requests of a run as the deck declares them (the echo of the print file): the compiled
module's own objects (:class:`EchoModel` with its :class:`EchoElement`, :class:`EchoRow`, :class:`Term`,
:class:`EchoCoordinate` and :class:`EchoPoint`; :class:`EchoStorage`, :class:`Buffer`, :class:`EchoPicture`,
:class:`Plot`: owned by Rust, read through their attributes, equal when they hold the same, picklable). The classes
are ``Echo*`` where a class of the model a :class:`~mechfem.Mechanism` is built of has the plain name
(:class:`~mechfem.Element`, :class:`~mechfem.Storage`, ...); ``Model`` is :class:`EchoModel`, ``mechfem.Model``.

Numbers that name things (co-ordinates, elements, rows, buffers) are the deck's own, 1-based and signed.
"""

from __future__ import annotations

from dataclasses import dataclass

from mechfem._core import Buffer as Buffer
from mechfem._core import EchoCoordinate as EchoCoordinate
from mechfem._core import EchoElement as EchoElement
from mechfem._core import EchoModel as EchoModel
from mechfem._core import EchoPicture as EchoPicture
from mechfem._core import EchoPoint as EchoPoint
from mechfem._core import EchoRow as EchoRow
from mechfem._core import EchoStorage as EchoStorage
from mechfem._core import Plot as Plot
from mechfem._core import Term as Term

Model = EchoModel
"""The model as compiled from the deck, for the echo in the print file (``RunResult.model``): the compiled
module's own object, read through its attributes (``elements``, ``prescribed``, ``dependent``, ``dofs``,
``coordinates``, ``mode``, ``dynamics``, ``units``, ``points``, ``labels``, ``n_coords``, ``n_moving``)."""


BUFFER_ARGS: dict[str, str] = {
    "BUFINP": "j",
    "BUFTIME": "",
    "BUFX0": "i",
    "BUFKX1": "ij",
    "BUFKX2": "ijm",
    "BUFVX": "i",
    "BUFAX": "i",
    "BUFE0": "r",
    "BUFKE1": "rj",
    "BUFKE2": "rjm",
    "BUFVE": "r",
    "BUFAE": "r",
    "BUFDET": "",
    "BUFSIG": "r",
    "BUFDRV": "j",
    "BUFREA": "i",
    "BUFEKIN": "",
    "BUFEPOT": "",
    "BUFPOW": "",
    "BUFMRED": "jj",
    "BUFTRA": "ee",
    "BUFPIN": "eii",
    "BUFSHAKE": "",
}
"""The arguments of each BUF keyword before the buffer number.

``i`` a co-ordinate, ``r`` a row, ``j`` and ``m`` an input (a last ``m`` may be left out: it is then ``j``).
BUFSIG takes a prescribed row, BUFREA a fixed co-ordinate; they and the other buffers of the dynamics
(BUFDRV, BUFEKIN, BUFEPOT, BUFPOW, BUFMRED) need masses or loads on the mechanism (mode ``DYN ANA``).
``e`` is an element: BUFTRA takes two, BUFPIN an element and its point's two co-ordinates (it fills buffers b and
b+1 with x and y; BUFSHAKE fills b, b+1 and b+2 with the shaking force's x, y and moment)."""


@dataclass(frozen=True)
class ModelNames:
    """A named model's own names for the deck numbers of its run (:class:`mechfem.Mechanism`), so that labels
    (:mod:`mechfem.results.labels`) speak the model's language instead of the deck's."""

    coordinates: list[str]
    """Co-ordinate i is ``coordinates[i - 1]``, e.g. ``P.x``."""
    prescribed: list[str]
    """Prescribed row r is ``prescribed[r - 1]``."""
    dependent: list[str]
    """Dependent form parameter -k (an output) is ``dependent[k - 1]``."""
    inputs: list[str]
    """The input of DOF j is ``inputs[j - 1]``."""
