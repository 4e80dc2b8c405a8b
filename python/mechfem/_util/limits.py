"""How much memory a run may use for its results.

A run keeps every recorded value of every position until its outputs are written, so a deck asking for
millions of positions of a large model could exhaust the machine hours into the run. Instead, each run
estimates its peak before it starts and is refused with :class:`~mechfem.ResourceError` when that exceeds
the limit: by default ``DEFAULT_MEMORY_LIMIT``, or the environment variable ``MECHFEM_MEMORY_LIMIT``, or
what the caller passes (``mechfem run --memory-limit``, ``run_deck(memory_limit=...)``).
"""

from __future__ import annotations

import operator
import os
import re
from fractions import Fraction

DEFAULT_MEMORY_LIMIT = 2 * 1024**3
"""2 GiB: about 9 million positions of a four-bar that records a dozen buffers."""

ENV = "MECHFEM_MEMORY_LIMIT"

MAX_MEMORY_LIMIT = 2**64 - 1
"""The largest limit a run takes (the core counts bytes in 64 bits): far beyond any machine, so no limit at all."""

MAX_TEXT = f"{MAX_MEMORY_LIMIT} bytes (16 EiB)"

_UNITS = {"": 1, "K": 1024, "M": 1024**2, "G": 1024**3, "T": 1024**4}
_SIZE = re.compile(r"^\s*(\d+(?:\.\d*)?|\.\d+)\s*([KMGT]?)(?:i?B)?\s*$", re.IGNORECASE)


def parse_size(text: str) -> int:
    """Bytes from ``text``: a number with an optional binary unit, ``500M``, ``4G``, ``1.5GiB``, ``1048576``.

    Raises ValueError with a message that shows the accepted forms.
    """
    m = _SIZE.match(text)
    if m is None:
        raise ValueError(f"not a size: {text!r} (write for example 512M, 4G or 1.5GiB)")
    # Exact arithmetic: a size of 20 digits is not rounded on its way to the bound.
    value = Fraction(m.group(1)) * _UNITS[m.group(2).upper()]
    if value < 1:
        raise ValueError(f"not a size: {text!r} (it must be at least one byte)")
    if value > MAX_MEMORY_LIMIT:
        raise ValueError(f"not a size: {text!r} (it must be at most {MAX_TEXT})")
    return int(value)


def memory_limit(value: int | str | None = None) -> int:
    """The limit in bytes: ``value`` when given (bytes, or a size as :func:`parse_size` reads it), else the
    environment variable ``MECHFEM_MEMORY_LIMIT``, else ``DEFAULT_MEMORY_LIMIT``."""
    if value is None:
        env = os.environ.get(ENV)
        if not env:
            return DEFAULT_MEMORY_LIMIT
        try:
            return parse_size(env)
        except ValueError as e:
            raise ValueError(f"{ENV}: {e}") from None
    if isinstance(value, str):
        return parse_size(value)
    try:
        value = operator.index(value)  # an int, or numpy's: not a float, which would be rounded
    except TypeError:
        raise ValueError(
            f"the memory limit must be a whole number of bytes or a size such as '4G', not {value!r}"
        ) from None
    if value < 1:
        raise ValueError(f"the memory limit must be at least one byte, not {value}")
    if value > MAX_MEMORY_LIMIT:
        raise ValueError(f"the memory limit must be at most {MAX_TEXT}, not {value}")
    return int(value)


RAISE_DECK_LIMIT = (
    "with `mechfem run --memory-limit SIZE` or the environment variable MECHFEM_MEMORY_LIMIT (for example 8G)"
)
"""How a deck's run raises its limit: the words that end the core's refusal (``... or raise the limit``) on the
deck path (``run_deck``, the command line)."""
