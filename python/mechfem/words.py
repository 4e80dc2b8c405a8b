"""How a run's stop reason, its limit positions and its warnings name things.

:class:`Words` speaks the deck's language (an input by its DOF and row, the keywords MOV_FREE, TSTEPE and
INTTOL), as ``mechfem run`` and :func:`mechfem.run_deck` say it; :class:`mechfem.explain.PythonWords` speaks
that of the Python API for a named model.
"""

from __future__ import annotations

from collections.abc import Sequence

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


def input_name(j: int, names: Sequence[str] = ()) -> str:
    """``the input of DOF j``, with its row and form parameters when ``names`` has them."""
    return f"the input of DOF {j} ({names[j - 1]})" if len(names) >= j else f"the input of DOF {j}"


def free_motion_line(j: int, ds: float) -> str:
    """The deck line ``MOV_FREE j ds``, with ds rounded to two significant digits."""
    return f"MOV_FREE {j} {float(f'{ds:.2g}'):g}"


class Words:
    """How a stop reason, a limit or a warning names things. This class speaks the deck's language (an input by
    its DOF, the keywords MOV_FREE, TSTEPE, INTTOL); :class:`mechfem.explain.PythonWords` speaks that of the
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

    def at(self, j: int, value: float, digits: int) -> str:
        """The input of DOF ``j`` at ``value``, e.g. ``input 1 = 2.5``."""
        return f"input {j} = {value:.{digits}g}"

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
        """A thing a message names (see :data:`Part`), in the deck's words: ``element 3 (TR2)``,
        ``co-ordinates 5, 6``."""
        return deck


def words_of(names: Sequence[str] | Words) -> Words:
    """``names`` when they are :class:`Words`, else the deck's words with those input names."""
    return names if isinstance(names, Words) else Words(names)


__all__ = ["Part", "Words", "free_motion_line", "input_name", "words_of"]
