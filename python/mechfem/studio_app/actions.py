"""What the page asks of the studio, one JSON message at a time, and the answers: open a deck or the template, edit,
undo, redo, save, optimise. No web here: the server (:mod:`.server`) and the notebook widget (:mod:`.widget`) both
hand their messages to :meth:`Actions.handle`.

Every answer is a dict with ``type``: ``design`` (the new view, with ``branch`` words when the assembly branch
changed), ``refused`` (the words why; the design on screen is still the last good one), ``saved`` (the files
written), ``optimised``, or ``error`` (a message the page could not act on).
"""

from __future__ import annotations

import math
import os
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

import mechfem
from mechfem.errors import MechfemError
from mechfem.model.mechanism import Mechanism
from mechfem.studio_app.session import EditOutcome, EditRefused, Session
from mechfem.studio_app.template import four_bar
from mechfem.studio_app.view import view

Push = Callable[[dict[str, Any]], object]

#: The repository's example decks, when mechfem runs from a checkout (an installed wheel has none).
EXAMPLES = Path(mechfem.__file__).resolve().parents[2] / "examples"


def examples(folder: Path = EXAMPLES) -> list[str]:
    """The example decks under ``folder``, as paths relative to it."""
    return decks(folder)


#: Folders a listing of decks does not look into: the tools' own (a virtual environment, build output).
SKIPPED = {"node_modules", "target", "__pycache__", "site-packages"}

#: The most decks a listing gives, how deep it looks below its folder and how many folders it looks into (a
#: listing of a home folder stays quick).
MOST_DECKS, DEEPEST, MOST_FOLDERS = 2000, 6, 5000


def decks(folder: Path) -> list[str]:
    """The decks (``*.mec``) in ``folder`` and the folders below it, as paths relative to it (hidden folders and
    :data:`SKIPPED` left out; at most :data:`MOST_DECKS`, :data:`DEEPEST` folders down, :data:`MOST_FOLDERS`
    folders)."""
    if not folder.is_dir():
        return []
    out = []
    for seen, (top, dirs, files) in enumerate(os.walk(folder)):
        if seen >= MOST_FOLDERS:
            break
        depth = len(Path(top).relative_to(folder).parts)
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIPPED and depth < DEEPEST)
        out += [(Path(top) / f).relative_to(folder).as_posix() for f in files if f.lower().endswith(".mec")]
        if len(out) >= MOST_DECKS:
            break
    return sorted(out)[:MOST_DECKS]


def inside(folder: Path, name: str) -> Path:
    """The deck ``name`` (relative) of ``folder``; refuses a name that leads out of it or is not a deck there."""
    root = folder.resolve()
    path = (root / name).resolve()
    if not path.is_relative_to(root) or path.suffix.lower() != ".mec" or not path.is_file():
        raise ValueError(f"{name!r} is not a deck of {folder}")
    return path


class Actions:
    """The studio's state, one :class:`Session` at a time (None before a deck is opened)."""

    def __init__(self, session: Session | None, examples_folder: Path = EXAMPLES, folder: Path | None = None) -> None:
        self.session = session
        self.examples_folder = examples_folder
        #: The folder the user pointed the studio at (``mechfem studio --folder DIR``; the deck's, or the current
        #: one): its decks are offered and opened by path, with the files beside them (MOV_FUNC tables, targets).
        self.folder = folder
        self.optimising = False

    def hello(self) -> dict[str, Any]:
        """The first message: the examples and the folder's decks to offer and, when a design is open, its view."""
        out: dict[str, Any] = {"type": "hello", "examples": examples(self.examples_folder), **self._listing()}
        if self.session is not None:
            out["design"] = view(self.session)
        return out

    def _listing(self) -> dict[str, Any]:
        if self.folder is None:
            return {"folder": None, "files": []}
        return {"folder": str(self.folder), "files": decks(self.folder)}

    def op_files(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        """The folder's decks as they are now."""
        return {"type": "files", **self._listing()}

    def handle(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        op = message.get("op")
        handler = getattr(self, f"op_{op}", None) if isinstance(op, str) else None
        if handler is None:
            return {"type": "error", "message": f"unknown request {op!r}"}
        try:
            return dict(handler(message, push))
        except EditRefused as e:
            return {"type": "refused", "message": str(e)}
        except (MechfemError, OSError, ValueError, TypeError, KeyError) as e:
            text = e.args[0] if isinstance(e, KeyError) and e.args else str(e)
            return {"type": "refused", "message": text}

    # -- opening

    def _open(self, mech: Mechanism, deck: Path | None, source: str | None = None) -> dict[str, Any]:
        self.session = Session(mech, deck, source)
        return self._design(EditOutcome(), opened=True)

    def op_template(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        return self._open(four_bar(), None)

    def op_example(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        name = str(message["name"])
        if name not in examples(self.examples_folder):
            raise ValueError(f"{name!r} is not one of the examples")
        deck = self.examples_folder / name
        return self._open(Mechanism.from_deck(deck), deck)

    def op_open_path(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        # A deck of the folder the user pointed at, read by its path: the files beside it are read too.
        if self.folder is None:
            raise ValueError("the studio was started without a folder: `mechfem studio --folder DIR` offers its decks")
        deck = inside(self.folder, str(message["name"]))
        return self._open(Mechanism.from_deck(deck), deck)

    def op_open_text(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        # A file the browser read (file picker, drag and drop): no folder, so a deck that reads files beside it
        # says which one it misses.
        name = Path(str(message.get("name") or "deck.mec")).stem
        text = str(message["text"])
        return self._open(Mechanism.from_deck_text(text, name), None, text)

    # -- editing

    def _need(self) -> Session:
        if self.session is None:
            raise ValueError("open a deck or the four-bar template first")
        return self.session

    def _design(self, outcome: EditOutcome, **more: Any) -> dict[str, Any]:
        session = self._need()
        return {"type": "design", "design": view(session), "branch": outcome.branch, **more}

    def op_edit(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        changes = message["changes"]
        if not isinstance(changes, dict):
            raise TypeError("an edit's changes are a mapping of names to values")
        started = time.perf_counter()
        outcome = self._need().edit(changes, message.get("group"))
        run_ms = 1000 * (time.perf_counter() - started)
        return self._design(outcome, run_ms=round(run_ms, 2))

    def op_undo(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        return self._design(self._need().undo())

    def op_redo(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        return self._design(self._need().redo())

    def op_save(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        path = Path(str(message["path"])).expanduser()
        if path.suffix.lower() != ".mec":
            raise ValueError(f"save as a deck: give a file name ending in .mec, not {path.name!r}")
        files = self._need().save(path)
        listing = self._listing()
        written = [str(p) for p in files]
        return {
            "type": "saved",
            "files": written,
            "deck": written[0],
            "folder": listing["folder"],
            "decks": listing["files"],
        }

    # -- optimising

    def op_optimise(self, message: dict[str, Any], push: Push) -> dict[str, Any]:
        from mechfem.studio_app import optimising

        session = self._need()
        vary = [str(v) for v in message["vary"]]
        target = str(message.get("target") or "path")
        lo = message.get("transmission")
        least = None if lo is None or lo == "" else float(lo)
        self.optimising = True
        try:
            if target == "path":
                points = [(float(x), float(y)) for x, y in message["points"]]
                found = optimising.path_through(session, str(message["point"]), points, vary, push)
            elif target == "extremum":
                quantity, which = str(message["quantity"]), str(message["which"])
                before = self._extremum(quantity, which)
                value = message.get("value")
                wanted = None if value is None or value == "" else float(value)
                found = optimising.extremum(session, quantity, which, str(message["goal"]), wanted, vary, push, least)
            elif target == "transmission":
                if least is None:
                    raise ValueError("give the least transmission angle")
                found = optimising.transmission(session, least, vary, push)
            else:
                raise ValueError(f"unknown target {target!r}: a path, an extremum or a transmission angle")
        finally:
            self.optimising = False
        outcome = session.edit(found["values"])
        found["target"] = target
        if target == "path":
            found["distances"] = distances(session, str(message["point"]), points)
        said = []
        if target == "extremum":
            unit = self._unit(quantity)
            now = self._extremum(quantity, which)
            said.append(
                f"The {which} of {quantity} over the motion is {now:.6g}{unit} (it was {before:.6g}{unit}"
                + (f"; wanted {wanted:.6g}{unit})." if wanted is not None and message["goal"] == "value" else ").")
            )
        if least is not None and target != "path":
            reached = optimising.transmission_range(session)
            unit = f" {session.mechanism.units.angle or 'rad'}"
            if reached is not None:
                half = 180.0 if unit == " deg" else math.pi
                said.append(
                    f"The transmission angle stays within {reached[0]:.4g} to {reached[1]:.4g}{unit} "
                    f"(wanted {least:.4g} to {half - least:.4g}{unit})."
                )
        found["said"] = " ".join(said)
        return self._design(outcome, optimised=found)

    def _extremum(self, quantity: str, which: str) -> float:
        values = self._need().result.value(quantity)
        return float(np.nanmax(values) if which == "max" else np.nanmin(values))

    def _unit(self, quantity: str) -> str:
        from mechfem.model.parts import Row

        session = self._need()
        obj = session.mechanism.find(quantity)
        units = session.mechanism.units
        unit = (units.angle or "rad") if isinstance(obj, Row) and obj.is_angle else (units.length or "")
        return f" {unit}" if unit else ""


def distances(session: Session, point: str, points: list[tuple[float, float]]) -> list[float]:
    """How near the path of ``point`` in the last good run passes to each of ``points``."""
    result, p = session.result, session.mechanism.find(point)
    nb = result.numbering
    xs = result.coords[:, nb.coord_number[p.x] - 1]
    ys = result.coords[:, nb.coord_number[p.y] - 1]
    return [float(np.nanmin(np.hypot(xs - x, ys - y))) for x, y in points]


__all__ = ["Actions", "examples"]
