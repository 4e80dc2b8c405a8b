"""Unknown names in the Python API: one message everywhere, with the closest names the model has.

Every lookup of a name the user typed (a point, element, form parameter, input, output, a study's variable)
that finds nothing says so in the same words, e.g.
``no point named 'Cc' in model 'fourbar'; did you mean 'C'? (points: A, B, C, D)``.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable

#: How many names a message lists before it says how many more there are.
LISTED = 12


class UnknownNameError(KeyError):
    """A name the model does not have. A ``KeyError`` whose ``str()`` is the message itself (a plain
    ``KeyError`` shows it quoted, as a key)."""

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


def plural(what: str) -> str:
    """``point`` -> ``points``; a phrase with ``or`` pluralises its last word only (``form parameter``)."""
    if what.endswith("s"):
        return what
    return what[:-1] + "ies" if what.endswith("y") and not what.endswith(("ay", "ey", "oy")) else what + "s"


def article(what: str) -> str:
    """``a point``, ``an element``."""
    return f"an {what}" if what[:1].lower() in "aeiou" else f"a {what}"


def suggestion(name: object, known: Iterable[str]) -> str | None:
    """The known name closest to ``name`` (case is ignored when it is the only difference), or None."""
    candidates = list(dict.fromkeys(known))
    if not isinstance(name, str) or not candidates:
        return None
    folded = [c for c in candidates if c.casefold() == name.casefold()]
    if folded:
        return folded[0]
    close = difflib.get_close_matches(name, candidates, n=1, cutoff=0.6)
    return close[0] if close else None


def listing(known: Iterable[str], limit: int = LISTED) -> str:
    """``A, B, C`` — at most ``limit`` names, then how many more; ``none`` without any."""
    names = list(dict.fromkeys(known))
    if not names:
        return "none"
    shown = ", ".join(names[:limit])
    return shown if len(names) <= limit else f"{shown} and {len(names) - limit} more"


def unknown(what: str, name: object, known: Iterable[str], where: str = "", kinds: str | None = None) -> str:
    """The message for a ``name`` that is no ``what`` among ``known``: ``no {what} named {name!r}{where}; did you
    mean ...? ({kinds}: ...)``; ``kinds`` defaults to the plural of ``what``."""
    names = list(dict.fromkeys(known))
    close = suggestion(name, names)
    hint = f"; did you mean {close!r}?" if close is not None else ""
    return f"no {what} named {name!r}{where}{hint} ({kinds or plural(what)}: {listing(names)})"


def unknown_name(
    what: str, name: object, known: Iterable[str], where: str = "", kinds: str | None = None
) -> UnknownNameError:
    """:func:`unknown` as an :class:`UnknownNameError`, to raise."""
    return UnknownNameError(unknown(what, name, known, where, kinds))


__all__ = ["LISTED", "UnknownNameError", "article", "listing", "plural", "suggestion", "unknown", "unknown_name"]
