"""The stop condition of a simulation (deck ``STOPWHEN b value``) by the names of a :class:`~mechfem.Mechanism`.

A :class:`~mechfem.Motion`'s ``stop_when = (buffer, value)`` names the buffer of the storage it watches by
its number or by the name of the one quantity it holds: ``"omega"`` is the buffer defined as
``Storage.buffer(11, "BUFVE", "omega")`` when no other buffer holds ``omega`` alone. The deck writer and the
typed builder both turn it into the buffer number here, so a deck and a run watch the same buffer.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from mechfem.model.motion import Motion
    from mechfem.model.storage import Ref, Storage


def _names(arg: Ref) -> str | None:
    """The name a buffer argument gives (a name, or a named object of the model), None for a deck number."""
    if isinstance(arg, str):
        return arg
    name = getattr(arg, "name", None)
    return name if isinstance(name, str) else None


def _described(b: int, kw: str, args: tuple[Ref, ...]) -> str:
    return " ".join([f"{b} ({kw}", *(str(_names(a) or a) for a in args)]) + ")"


def stop_buffer(motion: Motion | None, storage: Storage | None, mechanism: str) -> tuple[int, float] | None:
    """The buffer number and value of ``motion.stop_when`` in ``storage`` (None without a stop condition); a
    ValueError that names the mechanism's buffers when the storage has no such buffer, or several by that name."""
    if motion is None or motion.stop_when is None:
        return None
    buffer, value = motion.stop_when
    buffers = [] if storage is None else storage.buffers
    defined = ", ".join(_described(*b) for b in buffers) or "none"
    if isinstance(buffer, int):
        if all(b != buffer for b, _, _ in buffers):
            raise ValueError(
                f"stop_when watches buffer {buffer}, which the storage of mechanism {mechanism!r} does not define "
                f"(its buffers: {defined}): add it with Storage.buffer or watch a defined one"
            )
        return buffer, float(value)
    matches = [b for b in buffers if len(b[2]) == 1 and _names(b[2][0]) == buffer]
    if len(matches) == 1:
        return matches[0][0], float(value)
    if not matches:
        raise ValueError(
            f"stop_when watches {buffer!r}, but no buffer of the storage of mechanism {mechanism!r} holds {buffer!r} "
            f"alone (its buffers: {defined}): add one, e.g. Storage.buffer(n, 'BUFVE', {buffer!r}) for a row's speed, "
            "or give the buffer's number"
        )
    raise ValueError(
        f"stop_when watches {buffer!r}, which several buffers of mechanism {mechanism!r} hold "
        f"({', '.join(_described(*b) for b in matches)}): give the number of the one to watch"
    )


def stop_name(storage: Storage | None, number: int) -> int | str:
    """Buffer ``number`` by the name :func:`stop_buffer` finds it by, or by its number when no name does."""
    if storage is None:
        return number
    for b, _, args in storage.buffers:
        if b == number and len(args) == 1:
            name = _names(args[0])
            if name is not None and sum(len(a) == 1 and _names(a[0]) == name for _, _, a in storage.buffers) == 1:
                return name
    return number
