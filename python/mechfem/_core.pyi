"""Types of ``mechfem._core`` (crates/mechfem-py); private: use :mod:`mechfem`. Numbers are the deck's, 1-based."""

import os
from collections.abc import Callable, Sequence
from typing import Any, Literal, final

import numpy as np
import numpy.typing as npt

# The names of the compiled module.
__all__ = [
    "MechfemError",
    "DeckError",
    "AssemblyError",
    "ConvergenceError",
    "LimitPositionError",
    "ResourceError",
    "UnitWarning",
    "DEFAULTS",
    "Defaults",
    "ElementKind",
    "catalogue",
    "check_deck",
    "run_deck",
    "read_deck_text",
    "deck_files",
    "run_deck_text",
    "describe_deck_text",
    "run_deck_variants",
    "Run",
    "Check",
    "DeckFiles",
    "Simulation",
    "Adjust",
    "Limit",
    "Stop",
    "Report",
    "EchoStorage",
    "Buffer",
    "EchoPicture",
    "Plot",
    "DesignModel",
    "Model",
    "ModelBuilder",
    "Labels",
    "EchoModel",
    "EchoElement",
    "EchoRow",
    "Term",
    "EchoCoordinate",
    "EchoPoint",
    "EchoDynamics",
    "EchoBody",
    "EchoPointMass",
    "EchoInertia",
    "EchoForce",
    "EchoLoad",
    "DeckDescription",
    "DeckMotion",
    "DeckInput",
    "OptimiseBlock",
    "DeckVary",
    "DeckTarget",
    "DeckBound",
    "DeckObjective",
    "DeckMassVary",
    "DeckSynthesis",
    "optimised_deck_text",
    "deck_tolerance",
    "built_tolerance",
    "ToleranceBands",
    "DynamicDesignModel",
    "Diagnostic",
    "ElementFault",
    "Evaluation",
    "Extremum",
    "deck_with_masses",
]

_F64 = npt.NDArray[np.float64]
_Part = str | tuple[str, Any, str]  # words, or a thing named as (kind, value, deck words): mechfem.results.words.Part

class MechfemError(Exception):
    """Base class of every error mechfem raises."""

class DeckError(MechfemError):
    """The deck has a mistake: str() is the rendered diagnostic."""

    path: str
    line: int
    """Line of the first mistake (0: the file as a whole)."""
    column: int
    """1-based character of the line where the mistake starts (0 with line 0)."""
    kind: str
    """Stable code of the diagnostic's kind, snake case (``coordinate_unused``)."""
    text: str
    message: str
    hint: str | None
    element: int | None
    coordinate: int | None
    detail: str | None
    detail_fields: ElementFault | None
    diagnostics: list[Diagnostic]
    """Every mistake; the attributes above are the first one's."""

@final
class Diagnostic:
    """One mistake of a deck: ``kind`` (a stable code, snake case), ``path``, ``line`` and ``column`` (1-based; 0: the
    file as a whole), ``text`` (the line), ``message``, ``hint``, and what it is about: ``element``, ``coordinate``
    (deck numbers), ``detail`` (the core's reason in its words) and ``detail_fields`` (the same as an
    ``ElementFault``), None when it is about none."""

    def __new__(
        cls,
        kind: str,
        path: str,
        line: int,
        column: int,
        text: str,
        message: str,
        hint: str | None,
        element: int | None,
        coordinate: int | None,
        detail: str | None,
        detail_fields: ElementFault | None,
    ) -> Diagnostic: ...
    def __getnewargs__(
        self,
    ) -> tuple[str, str, int, int, str, str, str | None, int | None, int | None, str | None, ElementFault | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def kind(self) -> str: ...
    @property
    def path(self) -> str: ...
    @property
    def line(self) -> int: ...
    @property
    def column(self) -> int: ...
    @property
    def text(self) -> str: ...
    @property
    def message(self) -> str: ...
    @property
    def hint(self) -> str | None: ...
    @property
    def element(self) -> int | None: ...
    @property
    def coordinate(self) -> int | None: ...
    @property
    def detail(self) -> str | None: ...
    @property
    def detail_fields(self) -> ElementFault | None: ...

@final
class ElementFault:
    """Why an element (deck number) cannot be evaluated: ``kind`` (``coincident_points``, ``no_belt_span``,
    ``zero_radius``) and the numbers and names of the reason as the core's message writes them: ``distance`` and
    ``difference`` of a belt, ``radius`` (``R_a`` or ``R_c``) of a gear; None where the kind has none."""

    def __new__(
        cls,
        element: int,
        kind: str,
        distance: str | None = None,
        difference: str | None = None,
        radius: str | None = None,
    ) -> ElementFault: ...
    def __getnewargs__(self) -> tuple[int, str, str | None, str | None, str | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def element(self) -> int: ...
    @property
    def kind(self) -> str: ...
    @property
    def distance(self) -> str | None: ...
    @property
    def difference(self) -> str | None: ...
    @property
    def radius(self) -> str | None: ...

class AssemblyError(MechfemError):
    """The model cannot be evaluated at position 1."""

    position: int
    reason: str
    element: int
    element_type: str | None
    detail: str
    detail_fields: ElementFault
    parts: list[_Part]

class ConvergenceError(MechfemError):
    """Newton iteration cannot reach position 1."""

    position: int
    reason: str
    """``no_convergence``, ``branch_jump``, ``non_finite`` or ``simulation``."""
    iterations: int
    """Only with reason ``no_convergence``, as ``residual``."""
    residual: float
    parts: list[_Part]

class ResourceError(MechfemError):
    """The results would take more memory than the limit; the run was refused before it started."""

class UnitWarning(UserWarning):
    """A number of a deck that looks as if it were written in another unit than the deck's (an angle of 720 where
    angles are radians); the run goes on with the number as written."""

class LimitPositionError(MechfemError):
    """D^c is singular at position 1."""

    rows: list[int]
    """Prescribed rows that depend on each other (empty when not found)."""
    coords: list[int]
    """Co-ordinates that can move with every prescribed value held (empty when not found)."""
    rank: int | None
    size: int | None
    """Rank and order of D^c (None when the analysis did not find them)."""
    coordinate: int | None
    """The co-ordinate at whose column the pivot vanished."""
    position: int
    reason: str
    parts: list[_Part]

@final
class Adjust:
    """The Newton adjustment of the given co-ordinates that makes position 1."""

    def __new__(cls, iterations: int, stages: int, initial_deformations: list[float], residual: float) -> Adjust: ...
    def __getnewargs__(self) -> tuple[int, int, list[float], float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __repr__(self) -> str: ...
    @property
    def iterations(self) -> int: ...
    @property
    def stages(self) -> int: ...
    @property
    def initial_deformations(self) -> list[float]:
        """Per prescribed row: value at the given co-ordinates minus the prescribed value."""
    @property
    def residual(self) -> float: ...

@final
class Limit:
    """A limit position met during the motion."""

    def __new__(cls, kind: str, after: int, inputs: list[float], coords: list[float], det: float) -> Limit: ...
    def __getnewargs__(self) -> tuple[str, int, list[float], list[float], float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __repr__(self) -> str: ...
    @property
    def kind(self) -> str:
        """``near_zero``, ``input_limit`` or ``passed``."""
    @property
    def after(self) -> int:
        """The position before it."""
    @property
    def inputs(self) -> list[float]: ...
    @property
    def coords(self) -> list[float]: ...
    @property
    def det(self) -> float: ...

@final
class Stop:
    """Why a motion stopped before its last position."""

    def __new__(
        cls,
        last_good: int,
        inputs: list[float],
        last_inputs: list[float],
        kind: str,
        message: str,
        parts: list[_Part],
        limit: Limit | None,
    ) -> Stop: ...
    def __getnewargs__(self) -> tuple[int, list[float], list[float], str, str, list[_Part], Limit | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __repr__(self) -> str: ...
    @property
    def last_good(self) -> int: ...
    @property
    def inputs(self) -> list[float]: ...
    @property
    def last_inputs(self) -> list[float]: ...
    @property
    def kind(self) -> str:
        """``singular``, ``no_convergence``, ``branch_jump``, ``element``, ``non_finite``, ``non_finite_dynamics``,
        ``unsupported``, ``not_computed``, ``interrupted`` or ``simulation`` (the integrator of a simulation gave
        up)."""
    @property
    def message(self) -> str: ...
    @property
    def parts(self) -> list[_Part]: ...
    @property
    def limit(self) -> Limit | None: ...

@final
class Report:
    """What a run did (``Run.report``)."""

    def __new__(
        cls,
        adjust: Adjust,
        positions: int,
        steps: int,
        subdivided_steps: int,
        limits: list[Limit],
        singular_positions: list[int],
        stop: Stop | None,
    ) -> Report: ...
    def __getnewargs__(self) -> tuple[Adjust, int, int, int, list[Limit], list[int], Stop | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    def __repr__(self) -> str: ...
    @property
    def adjust(self) -> Adjust: ...
    @property
    def positions(self) -> int: ...
    @property
    def steps(self) -> int: ...
    @property
    def subdivided_steps(self) -> int: ...
    @property
    def limits(self) -> list[Limit]: ...
    @property
    def singular_positions(self) -> list[int]: ...
    @property
    def stop(self) -> Stop | None: ...

@final
class EchoBody:
    """A MASS line: the body on element ``element``: its mass, centre of mass (u, v) in the element's frame and
    moment of inertia."""

    def __new__(cls, element: int, mass: float, u: float, v: float, inertia: float) -> EchoBody: ...
    def __getnewargs__(self) -> tuple[int, float, float, float, float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def element(self) -> int: ...
    @property
    def mass(self) -> float: ...
    @property
    def u(self) -> float: ...
    @property
    def v(self) -> float: ...
    @property
    def inertia(self) -> float: ...

@final
class EchoPointMass:
    """A PMASS line: a point mass at the point of co-ordinates ``x`` and ``y``."""

    def __new__(cls, x: int, y: int, mass: float) -> EchoPointMass: ...
    def __getnewargs__(self) -> tuple[int, int, float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def x(self) -> int: ...
    @property
    def y(self) -> int: ...
    @property
    def mass(self) -> float: ...

@final
class EchoInertia:
    """An INERTIA line: an inertia on co-ordinate ``coord``."""

    def __new__(cls, coord: int, inertia: float) -> EchoInertia: ...
    def __getnewargs__(self) -> tuple[int, float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def coord(self) -> int: ...
    @property
    def inertia(self) -> float: ...

@final
class EchoForce:
    """A FORCE line: a constant force (fx, fy) at the point of co-ordinates ``x`` and ``y``."""

    def __new__(cls, x: int, y: int, fx: float, fy: float) -> EchoForce: ...
    def __getnewargs__(self) -> tuple[int, int, float, float]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def x(self) -> int: ...
    @property
    def y(self) -> int: ...
    @property
    def fx(self) -> float: ...
    @property
    def fy(self) -> float: ...

@final
class EchoLoad:
    """A load on a row (``dest``: r > 0 prescribed, -k dependent): ``LOAD`` (``value``), ``LOADFUNC`` (``rows`` of
    time and value, the ``file`` the deck names where known), ``SPRING`` (``k``, ``e0``, ``c``) or ``MOTOR``
    (``t0``, ``w0``); the numbers of the other kinds are None."""

    def __new__(
        cls,
        dest: int,
        kind: str,
        value: float | None = None,
        rows: list[tuple[float, float]] = ...,
        file: str | None = None,
        k: float | None = None,
        e0: float | None = None,
        c: float | None = None,
        t0: float | None = None,
        w0: float | None = None,
    ) -> EchoLoad: ...
    def __getnewargs__(
        self,
    ) -> tuple[
        int,
        str,
        float | None,
        list[tuple[float, float]],
        str | None,
        float | None,
        float | None,
        float | None,
        float | None,
        float | None,
    ]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def dest(self) -> int: ...
    @property
    def kind(self) -> str: ...
    @property
    def value(self) -> float | None: ...
    @property
    def rows(self) -> list[tuple[float, float]]: ...
    @property
    def file(self) -> str | None: ...
    @property
    def k(self) -> float | None: ...
    @property
    def e0(self) -> float | None: ...
    @property
    def c(self) -> float | None: ...
    @property
    def t0(self) -> float | None: ...
    @property
    def w0(self) -> float | None: ...

@final
class EchoDynamics:
    """The DYNAMICS block as compiled, in the deck's numbering and units: gravity, bodies, point masses, inertias,
    forces and loads."""

    def __new__(
        cls,
        gravity: tuple[float, float],
        bodies: list[EchoBody],
        point_masses: list[EchoPointMass],
        inertias: list[EchoInertia],
        forces: list[EchoForce],
        loads: list[EchoLoad],
    ) -> EchoDynamics: ...
    def __getnewargs__(
        self,
    ) -> tuple[
        tuple[float, float],
        list[EchoBody],
        list[EchoPointMass],
        list[EchoInertia],
        list[EchoForce],
        list[EchoLoad],
    ]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def gravity(self) -> tuple[float, float]:
        """``(gx, gy)``, zero without GRAVITY."""
    @property
    def bodies(self) -> list[EchoBody]: ...
    @property
    def point_masses(self) -> list[EchoPointMass]: ...
    @property
    def inertias(self) -> list[EchoInertia]: ...
    @property
    def forces(self) -> list[EchoForce]: ...
    @property
    def loads(self) -> list[EchoLoad]: ...

@final
class Term:
    """One FORM line: ``factor * form`` of element ``element``."""

    def __new__(cls, element: int, form: str, factor: float, seq: int, line: int) -> Term: ...
    def __getnewargs__(self) -> tuple[int, str, float, int, int]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def element(self) -> int: ...
    @property
    def form(self) -> str: ...
    @property
    def factor(self) -> float: ...
    @property
    def seq(self) -> int:
        """The FORM line's sequence number."""
    @property
    def line(self) -> int: ...

@final
class EchoElement:
    """One ELEM line."""

    def __new__(
        cls, number: int, kind: str, coords: list[int], coord_names: list[str], line: int, name: str | None = None
    ) -> EchoElement: ...
    def __getnewargs__(self) -> tuple[int, str, list[int], list[str], int, str | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def number(self) -> int: ...
    @property
    def type(self) -> str: ...
    @property
    def coords(self) -> list[int]: ...
    @property
    def coord_names(self) -> list[str]: ...
    @property
    def line(self) -> int: ...
    @property
    def name(self) -> str | None:
        """Its name in the deck's NAMES block (``ELEM 1 crank``), or None."""

@final
class EchoRow:
    """A prescribed row of D^c (``dest > 0``) or a dependent form parameter (``dest < 0``)."""

    def __new__(
        cls, dest: int, terms: list[Term], para: float | None, input: int | None, value: float, name: str | None = None
    ) -> EchoRow: ...
    def __getnewargs__(self) -> tuple[int, list[Term], float | None, int | None, float, str | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    def formula(self) -> str:
        """The combination, e.g. ``ANGB(2) - ANGB(4)``."""
    @property
    def dest(self) -> int: ...
    @property
    def terms(self) -> list[Term]: ...
    @property
    def para(self) -> float | None:
        """The value PARA prescribes, if any."""
    @property
    def input(self) -> int | None:
        """The DOF whose input this row is, if it is one."""
    @property
    def value(self) -> float:
        """Value at position 1."""
    @property
    def name(self) -> str | None:
        """Its name in the deck's NAMES block (``ROW 6 phi``, ``DEP 1 psi``), or None."""

@final
class EchoCoordinate:
    """One co-ordinate: fixed or moving, its given value and its value at position 1."""

    def __new__(
        cls, number: int, moving: bool, given: float, adjusted: float, name: str | None = None
    ) -> EchoCoordinate: ...
    def __getnewargs__(self) -> tuple[int, bool, float, float, str | None]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def number(self) -> int: ...
    @property
    def moving(self) -> bool: ...
    @property
    def given(self) -> float: ...
    @property
    def adjusted(self) -> float: ...
    @property
    def name(self) -> str | None:
        """Its name from the deck's NAMES block (``C.x`` for ``POINT 9 10 C``, ``s`` for ``COORD 11 s``), or None."""

@final
class EchoPoint:
    """A point the NAMES block names: co-ordinates ``x`` and ``y`` (1-based) are ``name.x`` and ``name.y``."""

    def __new__(cls, x: int, y: int, name: str) -> EchoPoint: ...
    def __getnewargs__(self) -> tuple[int, int, str]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def x(self) -> int: ...
    @property
    def y(self) -> int: ...
    @property
    def name(self) -> str: ...

@final
class EchoModel:
    """The model as compiled from the deck, for the echo in the print file (``Run.model``, ``Check.model``); its lists
    are shared by every run of one compiled deck where they do not change (read them, do not change them)."""

    def __new__(
        cls,
        elements: list[EchoElement],
        prescribed: list[EchoRow],
        dependent: list[EchoRow],
        dofs: list[int],
        coordinates: list[EchoCoordinate],
        mode: str,
        dynamics: EchoDynamics | None,
        units: dict[str, str | None],
        points: list[EchoPoint],
        labels: Labels | None,
    ) -> EchoModel: ...
    def __getnewargs__(
        self,
    ) -> tuple[
        list[EchoElement],
        list[EchoRow],
        list[EchoRow],
        list[int],
        list[EchoCoordinate],
        str,
        EchoDynamics | None,
        dict[str, str | None],
        list[EchoPoint],
        Labels | None,
    ]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def elements(self) -> list[EchoElement]: ...
    @property
    def prescribed(self) -> list[EchoRow]: ...
    @property
    def dependent(self) -> list[EchoRow]: ...
    @property
    def dofs(self) -> list[int]:
        """For DOF j (1-based, list index j - 1): the prescribed row that is its input."""
    @property
    def coordinates(self) -> list[EchoCoordinate]: ...
    @property
    def mode(self) -> str:
        """``KIN ANA``, ``DYN ANA`` or ``DYN SIM``."""
    @property
    def dynamics(self) -> EchoDynamics | None:
        """The masses and loads (None for a KIN ANA deck), in the deck's units."""
    @property
    def units(self) -> dict[str, str | None]:
        """The deck's UNITS: length, angle, mass, force, time to a symbol (``mm``, ``deg``) or None where the deck
        declares none (all None without a UNITS line; with one, angle and time default to rad and s)."""
    @property
    def points(self) -> list[EchoPoint]:
        """The points the NAMES block names (``POINT 9 10 C``)."""
    @property
    def labels(self) -> Labels | None:
        """The names and units of its co-ordinates, rows, inputs and buffers, as the core decides them."""
    @property
    def n_coords(self) -> int: ...
    @property
    def n_moving(self) -> int: ...

@final
class Buffer:
    """One BUF... line: buffer ``number`` holds the quantity ``keyword args``."""

    def __new__(
        cls, number: int, keyword: str, args: list[int], line: int, name: str = ..., unit: str = ..., part: int = 0
    ) -> Buffer: ...
    def __getnewargs__(self) -> tuple[int, str, list[int], int, str, str, int]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def number(self) -> int: ...
    @property
    def keyword(self) -> str: ...
    @property
    def args(self) -> list[int]: ...
    @property
    def line(self) -> int: ...
    @property
    def name(self) -> str:
        """Its label: the NAMES block's ``BUF b label``, else from the names of what it records (``psi``,
        ``dpsi/dphi``, ``C.x``), else the deck's numbers (``x9``, ``ANGB(8)``, ``dANGB(3)/dinput1``)."""
    @property
    def unit(self) -> str:
        """The unit its values are in: ``mm``, ``deg``, ``mm/deg``, ``-`` (deg/deg), ``N·mm``, ``kg·mm²``; "" without
        UNITS (or where the deck declares no unit of a kind it needs)."""
    @property
    def part(self) -> int:
        """Which buffer of a BUFPIN (1: y) or BUFSHAKE (1: y, 2: moment) line it is; 0 for the first."""
    def label(self) -> str:
        """The definition as written in a deck, e.g. ``BUFKE1 -1 1``."""

@final
class Plot:
    """One PLOTFUNC, PLOTCURV or PLOTHODO line."""

    def __new__(cls, keyword: str, a: int, b: int) -> Plot: ...
    def __getnewargs__(self) -> tuple[str, int, int]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def keyword(self) -> str: ...
    @property
    def a(self) -> int: ...
    @property
    def b(self) -> int: ...

@final
class EchoPicture:
    """One BEGINPIC ... ENDPIC block."""

    def __new__(cls, title: str, line: int, plots: list[Plot]) -> EchoPicture: ...
    def __getnewargs__(self) -> tuple[str, int, list[Plot]]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def title(self) -> str: ...
    @property
    def line(self) -> int: ...
    @property
    def plots(self) -> list[Plot]: ...

@final
class EchoStorage:
    """What the STORAGE block asks to be done with the buffers."""

    def __new__(
        cls,
        buffers: list[Buffer],
        printbuf: list[int] | None,
        savedata: list[int],
        animate: str | None,
        pictures: list[EchoPicture],
    ) -> EchoStorage: ...
    def __getnewargs__(
        self,
    ) -> tuple[list[Buffer], list[int] | None, list[int], str | None, list[EchoPicture]]: ...
    def __eq__(self, other: object, /) -> bool: ...
    @property
    def buffers(self) -> list[Buffer]: ...
    @property
    def printbuf(self) -> list[int] | None:
        """Buffers to tabulate in the print file (all of them for a PRINTBUF without numbers); None without
        PRINTBUF."""
    @property
    def savedata(self) -> list[int]:
        """Buffers of the data set, in column order (empty: no data set)."""
    @property
    def animate(self) -> str | None: ...
    @property
    def pictures(self) -> list[EchoPicture]: ...
    def replace(self, **changes: Any) -> EchoStorage:
        """This storage with the requests named changed (``buffers``, ``printbuf``, ``savedata``, ``animate``,
        ``pictures``)."""
    def buffer(self, number: int) -> Buffer:
        """The definition of buffer ``number`` (KeyError when there is none)."""

@final
class Check:
    """Position 1 of a deck, computed without its motion (``check_deck``)."""

    @property
    def n_coords(self) -> int: ...
    @property
    def n_moving(self) -> int: ...
    @property
    def n_prescribed(self) -> int: ...
    @property
    def n_dependent(self) -> int: ...
    @property
    def n_dof(self) -> int: ...
    @property
    def det(self) -> float:
        """det(D^c) at position 1."""
    @property
    def coords(self) -> _F64:
        """Every co-ordinate at position 1, in the deck's units."""
    @property
    def adjust(self) -> Adjust: ...
    @property
    def model(self) -> EchoModel: ...

@final
class Simulation:
    """What the integrator of a DYN SIM run did."""

    def __new__(
        cls,
        method: str,
        rtol: float,
        atol: float,
        steps: int,
        rejected: int,
        evaluations: int,
        jacobians: int,
        reached: float,
        segments: list[tuple[str, float, float, int, int]],
        event: tuple[int, float, float, list[float]] | None,
        tolerance_warning: str | None,
    ) -> Simulation: ...
    def __getnewargs__(
        self,
    ) -> tuple[
        str,
        float,
        float,
        int,
        int,
        int,
        int,
        float,
        list[tuple[str, float, float, int, int]],
        tuple[int, float, float, list[float]] | None,
        str | None,
    ]: ...
    def __eq__(self, value: object, /) -> bool: ...
    @property
    def method(self) -> str: ...
    @property
    def rtol(self) -> float: ...
    @property
    def atol(self) -> float: ...
    @property
    def steps(self) -> int:
        """Steps accepted."""
    @property
    def rejected(self) -> int: ...
    @property
    def evaluations(self) -> int:
        """Evaluations of the equations of motion (one Newton position each)."""
    @property
    def jacobians(self) -> int: ...
    @property
    def reached(self) -> float:
        """The time the integration reached."""
    @property
    def segments(self) -> list[tuple[str, float, float, int, int]]: ...
    @property
    def event(self) -> tuple[int, float, float, list[float]] | None: ...
    @property
    def tolerance_warning(self) -> str | None: ...

@final
class Run:
    """One run, however it was started (``run_deck``, ``run_deck_text``, ``Model.run``, ``run_deck_variants``):
    the core's columns as numpy arrays made on first access (owning the core's buffers; the same array on every
    access: read them, do not change them), the model's sizes, and the report, model echo, storage requests and
    simulation report."""

    @property
    def positions(self) -> int: ...
    @property
    def n_coords(self) -> int: ...
    @property
    def n_dof(self) -> int: ...
    @property
    def n_prescribed(self) -> int: ...
    @property
    def n_dependent(self) -> int: ...
    @property
    def dynamic(self) -> bool:
        """The deck has masses and loads (DYN ANA, DYN SIM): the table holds the inverse dynamics."""
    @property
    def interrupted(self) -> bool:
        """Ctrl-C stopped the run; the positions before it are here."""
    @property
    def stopped(self) -> bool:
        """The motion stopped before its end (``report.stop`` says why)."""
    @property
    def table(self) -> _F64:
        """positions x the columns of ``layout`` (Fortran order: each column contiguous)."""
    @property
    def layout(self) -> dict[str, tuple[int, tuple[int, ...]]]:
        """Block name -> (first column, shape at one position); the blocks cover the columns once, in order.
        A deck file's run (``run_deck``) records for B buffers, H co-ordinates in ``hodograph_coords`` and D inputs:
        ``buffers`` (B, in the order of ``buffer_numbers``), ``hodograph`` (H: d x_i / d input 1, NaN where D^c is
        singular); for a DYN deck ``inputs``, ``drive`` (D), ``ekin``, ``epot``, ``power``, ``loadpow`` (the loads'
        power; one value each), ``vin`` (D: the inputs' speeds); then ``time`` and ``det``. A run of deck text or
        of a kept ``Model`` records the core's full layout, for N
        co-ordinates, D inputs and R rows (prescribed, then dependent): ``inputs`` (D), ``kx1`` (N, D), ``kx2`` (N,
        D, D), ``vx``, ``ax`` (N), ``e0`` (R), ``ke1`` (R, D), ``ke2`` (R, D, D), ``ve``, ``ae`` (R); when
        ``dynamic``, ``sigma`` (prescribed rows), ``drive`` (D), ``reaction`` (N; NaN for a moving co-ordinate),
        ``ekin``, ``epot``, ``power`` (one value each), ``mass`` (D, D), ..., ``loadpow`` (one value); then ``time``
        and ``det``. Every run of one
        deck shares this dict and the lists ``buffer_numbers`` and ``hodograph_coords``."""
    def column(self, c: int) -> _F64:
        """Column ``c`` of ``table`` at every position, without making the whole table when it is not made yet
        (IndexError past its last column)."""
    @property
    def coords(self) -> _F64:
        """positions x co-ordinates."""
    @property
    def buffers(self) -> _F64:
        """positions x the deck's buffers, in the order of ``buffer_numbers``."""
    @property
    def buffer_numbers(self) -> list[int]: ...
    @property
    def hodograph_coords(self) -> list[int]:
        """The co-ordinates of the ``hodograph`` block (empty without it)."""
    @property
    def report(self) -> Report: ...
    @property
    def model(self) -> EchoModel: ...
    @property
    def storage(self) -> EchoStorage: ...
    @property
    def simulation(self) -> Simulation | None:
        """What the integrator did, for a DYN SIM deck whose motion was simulated; None otherwise."""

# --- the element catalogue and the solver's defaults (crates/mechfem-py/src/catalogue.rs) ---

@final
class ElementKind:
    """One element type of the catalogue; dimensions are ``length``, ``angle``, ``ratio`` or ``any`` (that of the
    co-ordinate a ``CRD`` element is put on)."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def type(self) -> str:
        """The deck's three-letter name (``BIN``)."""
    @property
    def coordinates(self) -> list[tuple[str, str]]:
        """Name and dimension of each co-ordinate, deck order."""
    @property
    def slots(self) -> str:
        """``P`` a point (x, y), ``a`` an angle, ``s`` a scalar, in deck order."""
    @property
    def forms(self) -> list[tuple[str, str]]:
        """Deck name and dimension of each form parameter."""
    @property
    def frame(self) -> bool:
        """Whether the element has a frame that can carry a mass."""

@final
class Defaults:
    """The solver's defaults and the deck reader's limits."""

    @property
    def accuracy(self) -> float: ...
    @property
    def max_iter(self) -> int: ...
    @property
    def max_halvings(self) -> int: ...
    @property
    def min_integration_tolerance(self) -> float: ...
    @property
    def max_iter_limit(self) -> int: ...
    @property
    def max_steps(self) -> int: ...

DEFAULTS: Defaults

def catalogue() -> list[ElementKind]: ...
def check_deck(path: str | os.PathLike[str]) -> Check: ...

@final
class DeckFiles:
    """What a deck reads and writes, from its text alone (``deck_files``)."""

    @property
    def mode(self) -> str:
        """``KIN ANA``, ``KIN OPT``, ``DYN ANA`` or ``DYN SIM``."""
    @property
    def tables(self) -> list[str]:
        """The files of MOV_FUNC, LOADFUNC and TARGET tables as the deck names them (relative to its folder)."""
    @property
    def savedata(self) -> bool: ...
    @property
    def pictures(self) -> int: ...
    @property
    def animate(self) -> str | None: ...

def deck_files(path: str | os.PathLike[str]) -> DeckFiles:
    """What the deck reads and writes, from its text alone (nothing compiled, no table read)."""

def read_deck_text(path: str | os.PathLike[str]) -> str:
    """The deck's text up to its END line; a DeckError for a file that is no regular file or is larger than 16 MiB
    before END."""

def run_deck(
    path: str | os.PathLike[str],
    progress: Callable[[int, int], object] | None = None,
    memory_limit: int = ...,
    det: bool = True,
) -> Run: ...

# --- deck text, for the model API (mechfem.Mechanism) and batch runs ---

@final
class DeckInput:
    """The motion of one input of a deck."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def kind(self) -> str:
        """``by`` (MOV_RELE), ``to`` (MOV_ABSE), ``table`` (MOV_FUNC), ``free`` (MOV_FREE) or ``dynamic`` (MOV_DYN)."""
    @property
    def value(self) -> float | None:
        """delta, end, ds or the initial speed v0; None for a table."""
    @property
    def rows(self) -> list[list[float]] | None:
        """A table's rows ``t value velocity acceleration``."""
    @property
    def file(self) -> str | None:
        """A table's file name as the deck gives it."""

@final
class DeckMotion:
    """A deck's MOVEMENT block."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def steps(self) -> int: ...
    @property
    def dt(self) -> float: ...
    @property
    def inputs(self) -> list[DeckInput]: ...

@final
class DeckVary:
    """A design variable: VARY (``kind`` 1, prescribed row ``number``) or VARYX (``kind`` 0, fixed co-ordinate
    ``number``); its numbers are the core's (SI with UNITS): times ``scale`` they are in ``unit`` ("" and 1 without
    UNITS)."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def kind(self) -> int: ...
    @property
    def number(self) -> int: ...
    @property
    def lo(self) -> float: ...
    @property
    def hi(self) -> float: ...
    @property
    def line(self) -> int: ...
    @property
    def unit(self) -> str: ...
    @property
    def scale(self) -> float: ...

@final
class DeckTarget:
    """TARGET (``kind`` ``values`` from ``file``, None where not compared), TARGETAT (``at``: ``position``, 1-based,
    and ``value``) or TARGETEXT (``extremum``: ``reference`` and ``value``); the other fields are None. Numbers in
    the core's units: times ``scale`` they are in ``unit``."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def buffer(self) -> int: ...
    @property
    def kind(self) -> Literal["values", "at", "extremum"]: ...
    @property
    def values(self) -> list[float | None] | None: ...
    @property
    def file(self) -> str | None: ...
    @property
    def position(self) -> int | None: ...
    @property
    def reference(self) -> int | None: ...
    @property
    def value(self) -> float | None: ...
    @property
    def weight(self) -> float: ...
    @property
    def line(self) -> int: ...
    @property
    def unit(self) -> str: ...
    @property
    def scale(self) -> float: ...

@final
class DeckBound:
    """A BOUND: ``buffer`` within ``lo``..``hi`` (core units; times ``scale`` in ``unit``)."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def buffer(self) -> int: ...
    @property
    def lo(self) -> float: ...
    @property
    def hi(self) -> float: ...
    @property
    def line(self) -> int: ...
    @property
    def unit(self) -> str: ...
    @property
    def scale(self) -> float: ...

@final
class DeckObjective:
    """The MINIMISE or MAXIMISE term."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def sense(self) -> Literal["minimise", "maximise"]: ...
    @property
    def reduce(self) -> Literal["max", "maxabs", "rms", "end"]: ...
    @property
    def buffer(self) -> int: ...
    @property
    def with_buffer(self) -> int | None:
        """MINIMISE kind b b2: b2, the magnitude sqrt(b^2 + b2^2) judged."""
    @property
    def line(self) -> int: ...

@final
class DeckMassVary:
    """A VARYM line: ``item`` (MASS, U, V, J, PMASS, INERTIA), the element or co-ordinate ``number``, the variable
    ``kind`` of ``DynamicDesignModel`` (10..15), ``lo``, ``hi`` (core units; times ``scale`` in ``unit``)."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def item(self) -> str: ...
    @property
    def number(self) -> int: ...
    @property
    def kind(self) -> int: ...
    @property
    def lo(self) -> float: ...
    @property
    def hi(self) -> float: ...
    @property
    def line(self) -> int: ...
    @property
    def unit(self) -> str: ...
    @property
    def scale(self) -> float: ...

@final
class DeckSynthesis:
    """A synthesis statement: FREETIME (``row``, ``ordered``, ``within`` in the core's units with the input's deck
    ``unit`` and ``scale``), FULLROT (``row``) or VARYFRAME (the pivot's x ``coordinate``, ``lo`` and ``hi`` in
    radians, its deck ``unit`` and ``scale``); the other fields are None."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def row(self) -> int | None: ...
    @property
    def coordinate(self) -> int | None: ...
    @property
    def lo(self) -> float | None: ...
    @property
    def hi(self) -> float | None: ...
    @property
    def ordered(self) -> bool: ...
    @property
    def within(self) -> float | None: ...
    @property
    def line(self) -> int: ...
    @property
    def unit(self) -> str: ...
    @property
    def scale(self) -> float: ...

@final
class OptimiseBlock:
    """The OPTIMISE block of a KIN OPT or DYN ANA deck."""

    def __eq__(self, other: object, /) -> bool: ...
    @property
    def vary(self) -> list[DeckVary]: ...
    @property
    def targets(self) -> list[DeckTarget]: ...
    @property
    def bounds(self) -> list[DeckBound]: ...
    @property
    def objective(self) -> DeckObjective | None: ...
    @property
    def steps(self) -> int: ...
    @property
    def tol(self) -> float | None: ...
    @property
    def ftol(self) -> tuple[float, float] | None:
        """OPTFTOL's (rtol, atol)."""
    @property
    def line(self) -> int:
        """Line of the OPTIMISE header."""
    @property
    def free_time(self) -> DeckSynthesis | None: ...
    @property
    def full_rotation(self) -> DeckSynthesis | None: ...
    @property
    def frame(self) -> DeckSynthesis | None: ...
    @property
    def mass_vary(self) -> list[DeckMassVary]: ...

@final
class DeckDescription:
    """What a deck declares, read and compiled without solving anything; numbers the deck's own, in its UNITS."""

    @property
    def coordinates(self) -> list[EchoCoordinate]:
        """Every co-ordinate, its value as the deck gives it in ``given`` (``adjusted`` NaN)."""
    @property
    def elements(self) -> list[EchoElement]: ...
    @property
    def prescribed(self) -> list[EchoRow]: ...
    @property
    def dependent(self) -> list[EchoRow]: ...
    @property
    def names(self) -> dict[str, Any]:
        """The NAMES block: ``points`` (x, y, name), ``coordinates``, ``elements``, ``prescribed``, ``dependent``
        (a name or None each)."""
    @property
    def dofs(self) -> list[int]: ...
    @property
    def tol(self) -> float:
        """ACCURACY, in the deck's length unit."""
    @property
    def max_iter(self) -> int: ...
    @property
    def motion(self) -> DeckMotion | None: ...
    @property
    def storage(self) -> EchoStorage: ...
    @property
    def inttol(self) -> tuple[float, float] | None:
        """INTTOL's ``(rtol, atol)``; None for a deck without INTTOL."""
    @property
    def integrator(self) -> str | None:
        """The method of INTEGRATOR (``auto``, ``dop853``, ``dopri5`` or ``radau5``); None without it."""
    @property
    def stop_when(self) -> tuple[int, float] | None:
        """``(buffer, value)`` of STOPWHEN; None for a deck without it."""
    @property
    def mode(self) -> str:
        """``KIN ANA``, ``KIN OPT``, ``DYN ANA`` or ``DYN SIM``."""
    @property
    def dynamics(self) -> EchoDynamics | None:
        """The masses and loads, LOADFUNC tables with their files (None for a KIN deck)."""
    @property
    def optimise(self) -> OptimiseBlock | None:
        """The OPTIMISE block of a KIN OPT or DYN ANA deck."""
    @property
    def units(self) -> dict[str, str | None]:
        """The deck's UNITS (length, angle, mass, force, time to a symbol or None)."""

# The compiled signatures show a default other than None or a bool as "...": order is 2 (first- and second-order
# transfer functions), memory_limit unlimited.
def run_deck_text(
    text: str,
    path: str | os.PathLike[str],
    base_dir: str | os.PathLike[str],
    motion: bool = True,
    progress: Callable[[int, int], object] | None = None,
    order: int | None = ...,
    memory_limit: int = ...,
) -> Run: ...
def describe_deck_text(
    text: str, path: str | os.PathLike[str], base_dir: str | os.PathLike[str]
) -> DeckDescription: ...

@final
class Model:
    """A deck compiled once, run many times with other numbers (no text written or parsed again)."""

    def __new__(cls, text: str, path: str | os.PathLike[str], base_dir: str | os.PathLike[str]) -> Model: ...
    @staticmethod
    def from_path(path: str | os.PathLike[str]) -> Model: ...
    @property
    def n_coords(self) -> int: ...
    @property
    def n_prescribed(self) -> int: ...
    def fingerprint(self) -> str:
        """The compiled model in full: equal for models that compute the same numbers."""
    def run(
        self,
        changes: list[tuple[int, int, float]] = ...,
        motion: bool = True,
        progress: Callable[[int, int], object] | None = None,
        order: int | None = ...,
        memory_limit: int = ...,
    ) -> Run: ...

@final
class ModelBuilder:
    """A model built item by item in the order of a deck's blocks, compiled by the deck reader's compiler."""

    def __new__(cls, path: str | os.PathLike[str], mode: str) -> ModelBuilder: ...
    design_in_model_units: bool
    """Whether the design models it makes (:meth:`design`, :meth:`dynamic_design`) take and give their numbers in
    the model's units (its UNITS) rather than the core's."""
    @property
    def item(self) -> int: ...
    def units(
        self,
        length: str | None = None,
        angle: str | None = None,
        mass: str | None = None,
        force: str | None = None,
        time: str | None = None,
    ) -> None: ...
    def name(self, kind: str, numbers: list[int], name: str) -> None: ...
    def element(self, ty: str, coords: list[int], name: str | None = None) -> None: ...
    def form(self, form: str, element: int, dest: int, factor: float, name: str | None = None) -> None: ...
    def nrdof(self, n: int) -> None: ...
    def coordinate(self, number: int, value: float, moving: bool, name: str | None = None) -> None: ...
    def para(self, row: int, value: float, name: str | None = None) -> None: ...
    def dynamics(self) -> None: ...
    def mass(self, element: int, mass: float, u: float, v: float, inertia: float, what: str) -> None: ...
    def point_mass(self, x: int, y: int, mass: float, what: str) -> None: ...
    def inertia(self, coord: int, inertia: float, what: str) -> None: ...
    def gravity(self, gx: float, gy: float) -> None: ...
    def force(self, x: int, y: int, fx: float, fy: float, what: str) -> None: ...
    def load(self, row: int, value: float, what: str) -> None: ...
    def load_table(self, row: int, file: str, what: str) -> None: ...
    def spring(self, row: int, k: float, e0: float, c: float, what: str) -> None: ...
    def motor(self, row: int, t0: float, w0: float, what: str) -> None: ...
    def movement(self, steps: int, dt: float) -> None: ...
    def motion(self, dof: int, kind: str, value: float, what: str) -> None: ...
    def motion_table(self, dof: int, file: str, what: str) -> None: ...
    def tolerances(
        self, accuracy: float | None = None, max_iter: int | None = None, inttol: tuple[float, float] | None = None
    ) -> None: ...
    def simulation(self, integrator: str | None = None, stop_when: tuple[int, float] | None = None) -> None: ...
    def storage(self) -> None: ...
    def buffer(self, keyword: str, args: list[int], number: int) -> None: ...
    def printbuf(self, buffers: list[int]) -> None: ...
    def savedata(self, buffers: list[int]) -> None: ...
    def animate(self, name: str) -> None: ...
    def picture(self, title: str, plots: list[tuple[str, int, int]]) -> None: ...
    def build(self, base_dir: str | os.PathLike[str]) -> Model: ...
    def design(
        self,
        base_dir: str | os.PathLike[str],
        variables: list[tuple[int, int]],
        buffers: list[int],
        extrema: list[tuple[int, int]],
    ) -> DesignModel: ...
    def dynamic_design(
        self,
        base_dir: str | os.PathLike[str],
        variables: list[tuple[int, int]],
        buffers: list[int],
        extrema: list[tuple[int, int]],
    ) -> DynamicDesignModel: ...

def run_deck_variants(
    texts: Sequence[str | ModelBuilder],
    variants: list[tuple[int, list[tuple[int, int, float]]]],
    path: str | os.PathLike[str],
    base_dir: str | os.PathLike[str],
    workers: int | None = None,
    progress: Callable[[int, int], object] | None = None,
    on_result: Callable[[int, Run | MechfemError], object] | None = None,
    order: int | None = ...,
    memory_limit: int = ...,
) -> list[Run | MechfemError]:
    """A variant is (index into ``texts``: deck text or a built model, changes); a change is (0, co-ordinate,
    value) or (1, row, value)."""

@final
class Evaluation:
    """One evaluation of a design: ``feasible``; ``reason`` (None when feasible) and ``reason_kind`` (None,
    ``"start"``, ``"position_one"``, ``"other_branch"``, ``"left_branch"`` or ``"stopped"``); ``positions`` computed;
    ``position_one`` (the co-ordinates at position 1, None without); ``report`` (None without positions); ``values``
    (positions x buffers); ``gradient`` (positions x buffers x variables); ``extrema``."""

    def __new__(
        cls,
        feasible: bool,
        reason: str | None,
        reason_kind: str | None,
        positions: int,
        position_one: list[float] | None,
        report: Report | None,
        values: npt.ArrayLike,
        gradient: npt.ArrayLike,
        extrema: list[Extremum],
    ) -> Evaluation: ...
    def __getnewargs__(
        self,
    ) -> tuple[bool, str | None, str | None, int, list[float] | None, Report | None, _F64, _F64, list[Extremum]]: ...
    @property
    def feasible(self) -> bool: ...
    @property
    def reason(self) -> str | None: ...
    @property
    def reason_kind(self) -> str | None: ...
    @property
    def positions(self) -> int: ...
    @property
    def position_one(self) -> list[float] | None: ...
    @property
    def report(self) -> Report | None: ...
    @property
    def values(self) -> _F64: ...
    @property
    def gradient(self) -> _F64: ...
    @property
    def extrema(self) -> list[Extremum]: ...

@final
class Extremum:
    """A buffer's value at an extremum of its reference: ``spec`` (which pair of buffers), ``after`` (the position,
    0-based, it lies after), ``input``, ``reference`` and ``value`` there, and ``gradient`` (by variable)."""

    def __new__(
        cls, spec: int, after: int, input: float, reference: float, value: float, gradient: list[float]
    ) -> Extremum: ...
    def __getnewargs__(self) -> tuple[int, int, float, float, float, list[float]]: ...
    @property
    def spec(self) -> int: ...
    @property
    def after(self) -> int: ...
    @property
    def input(self) -> float: ...
    @property
    def reference(self) -> float: ...
    @property
    def value(self) -> float: ...
    @property
    def gradient(self) -> list[float]: ...

@final
class DesignModel:
    """A compiled deck kept for an optimiser: designs evaluated in turn, each on the assembly branch of the start
    design (the deck's own unless ``start_at`` chose another), whatever was evaluated before."""

    def __new__(
        cls,
        text: str,
        path: str | os.PathLike[str],
        base_dir: str | os.PathLike[str],
        variables: list[tuple[int, int]],
        buffers: list[int],
        extrema: list[tuple[int, int]],
    ) -> DesignModel: ...
    @property
    def runs(self) -> int: ...
    def start(self) -> list[float]: ...
    def start_at(self, values: list[float]) -> Evaluation: ...
    def evaluate(self, values: list[float]) -> Evaluation: ...

@final
class DynamicDesignModel:
    """A compiled DYN ANA deck kept for an optimiser: an ``Evaluation`` as ``DesignModel``'s, the dynamic buffers with
    their sensitivities to dimensions and to the mass model. Variable kinds 0 (fixed co-ordinate), 1 (prescribed row),
    10..15 (MASS, U, V, J of an element's MASS line, the PMASS at a co-ordinate, the INERTIA on one)."""

    def __new__(
        cls,
        text: str,
        path: str | os.PathLike[str],
        base_dir: str | os.PathLike[str],
        variables: list[tuple[int, int]],
        buffers: list[int],
        extrema: list[tuple[int, int]],
    ) -> DynamicDesignModel: ...
    @property
    def runs(self) -> int: ...
    def start(self) -> list[float]: ...
    def start_at(self, values: list[float]) -> Evaluation: ...
    def evaluate(self, values: list[float]) -> Evaluation: ...

def deck_with_masses(text: str, path: str | os.PathLike[str], masses: list[tuple[int, int, float]]) -> str:
    """The DYN ANA deck with the numbers of its mass model replaced: ``(kind, number, value)``, kind 10..15 as for
    ``DynamicDesignModel``, values in the core's units (written in the deck's UNITS)."""

def optimised_deck_text(
    text: str,
    path: str | os.PathLike[str],
    rows: list[tuple[int, float]],
    coords: list[tuple[int, float]],
    file_dir: str | os.PathLike[str] | None = None,
) -> str:
    """The deck with the PARA values of ``rows`` and the XFIX/XMOV values of ``coords`` (number, value; the core's
    numbers, written in the deck's UNITS where it has them) replaced, in mode KIN ANA without OPTIMISE; MOV_FUNC
    files named from ``file_dir`` (the old deck's folder) when given."""

@final
class ToleranceBands:
    """Tolerance bands the core computed, every number in the model's units (``mechfem_core::run::tolerance``)."""

    @property
    def positions(self) -> int: ...
    @property
    def tolerances(self) -> _F64: ...
    @property
    def inputs(self) -> _F64:
        """Positions x inputs."""
    @property
    def values(self) -> _F64:
        """Positions x bands: the nominal values."""
    @property
    def worst(self) -> _F64:
        """Positions x bands: sum_k |s_k| t_k."""
    @property
    def rss(self) -> _F64:
        """Positions x bands: sqrt(sum_k (s_k t_k)^2)."""
    @property
    def sensitivity(self) -> _F64:
        """Positions x bands x dimensions: s_k."""
    @property
    def widest(self) -> list[int | None]:
        """Per band, the position of its largest worst case."""
    @property
    def shares(self) -> list[list[tuple[int, float, float, float, float]]]:
        """Per band, at its widest position: (dimension, sensitivity, deviation, of_worst, of_variance), largest
        first."""
    @property
    def dims(self) -> list[tuple[int, int, float, int]]:
        """(kind, number, t, line): kind 0 a fixed co-ordinate, 1 a prescribed row."""
    @property
    def bands(self) -> list[tuple[int, int, int]]:
        """(source, b, line)."""
    @property
    def labels(self) -> list[tuple[str, str]]: ...
    @property
    def dim_units(self) -> list[str]: ...
    @property
    def input_units(self) -> list[str]: ...

def deck_tolerance(text: str, path: str | os.PathLike[str], base_dir: str | os.PathLike[str]) -> ToleranceBands | None:
    """The TOLERANCE block of the deck evaluated (None without one)."""

def built_tolerance(
    builder: ModelBuilder,
    path: str | os.PathLike[str],
    base_dir: str | os.PathLike[str],
    dims: list[tuple[int, int, float]],
    sources: list[int],
) -> ToleranceBands:
    """The bands of buffers ``sources`` of the built model when each of ``dims`` (kind, number, t) is within +-t."""

_Dims = Sequence[int]
"""Exponents of length, angle, mass, force and time."""
_Named = tuple[str, str, str, _Dims]
"""A name, the unit the model states ("" without UNITS), the unit an axis shows, the exponents."""

@final
class Labels:
    """The names and units of a compiled model's things (crates/mechfem-py/src/labels.rs)."""

    def __eq__(self, other: object, /) -> bool: ...
    def coordinate(self, i: int) -> _Named: ...
    def row(self, r: int) -> _Named: ...
    def input(self, j: int) -> tuple[str, str, int, str, str, _Dims]: ...
    def buffer(self, number: int) -> _Named: ...
    def det(self) -> _Named: ...
    def unit(self, dim: _Dims) -> tuple[str, str]: ...
    def scale(self, dim: _Dims) -> float: ...
    def renamed(self, coordinates: list[str], prescribed: list[str], dependent: list[str]) -> Labels: ...
