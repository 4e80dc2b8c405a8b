"""Checks of the values the model API is given: finite numbers, names, and the file names a run writes."""

from __future__ import annotations

import math
import unicodedata


def finite(value: float, what: str) -> float:
    """``value`` as a float; a ValueError naming ``what`` when it is NaN or infinite."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number, not {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{what} must be a finite number, not {value!r}")
    return v


def check_name(name: str) -> str:
    """``name`` when it can name a part of a mechanism (it is written into deck comments); else a ValueError."""
    if not isinstance(name, str) or not name or name != name.strip() or any(c in name for c in "\r\n\t"):
        raise ValueError(f"a name must be a non-empty string without surrounding blanks or line breaks: {name!r}")
    return name


#: The longest output name (bytes of UTF-8) a deck or the Python API may give: with its extension it stays well
#: below the 255 bytes a file name may have.
MAX_OUTPUT_NAME = 200


def name_problem(name: str) -> str | None:
    """Why ``name`` is not a plain file name that stays inside the output folder, or None when it is one.

    The deck reader refuses the same names in a deck (an ANIMATE name), with the same words."""
    trimmed = name.strip()
    if not trimmed:
        return "is empty"
    if trimmed.startswith(("/", "\\")) or (
        len(trimmed) >= 2 and trimmed[1] == ":" and trimmed[0].isascii() and trimmed[0].isalpha()
    ):
        return "is an absolute path"
    parts = trimmed.replace("\\", "/").split("/")
    if ".." in parts or trimmed == ".":
        return "leads out of the output folder (`..`)"
    if len(parts) > 1:
        return "has a folder part (`/` or `\\`)"
    if "\0" in name:
        return "holds a NUL character"
    if any(c < " " or "\x7f" <= c <= "\x9f" for c in name):
        return "holds a control character"
    # Format characters (a direction override, a zero-width space) and line or paragraph separators: invisible, or
    # shown as a break, so that the name reads as another.
    invisible = [c for c in name if unicodedata.category(c) in ("Cf", "Zl", "Zp")]
    if invisible:
        return (
            f"holds the character U+{ord(invisible[0]):04X}, which does not show as itself (a format character or "
            "separator)"
        )
    size = len(name.encode("utf-8", errors="surrogatepass"))
    if size > MAX_OUTPUT_NAME:
        return f"is {size} bytes long, more than {MAX_OUTPUT_NAME}"
    return None
