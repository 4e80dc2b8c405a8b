"""The optional dependencies, imported when a feature asks for one: a module missing is an error saying how to
install it. They are imported by name: pandas, ezdxf and pyarrow ship no annotations, and callers need only the
module."""

from __future__ import annotations

import importlib
from types import ModuleType


def module(name: str, missing: str, error: type[Exception] = ImportError) -> ModuleType:
    """The module ``name``; ``error(missing)`` when it is not installed."""
    try:
        return importlib.import_module(name)
    except ImportError:
        raise error(missing) from None


def pandas() -> ModuleType:
    """pandas, for ``to_pandas()`` of a result or a study."""
    return module(
        "pandas",
        "to_pandas() needs pandas, which mechfem does not install by itself: pip install 'mechfem[pandas]' "
        "(or pip install pandas)",
    )


__all__ = ["module", "pandas"]
