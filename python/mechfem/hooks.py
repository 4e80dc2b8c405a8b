"""Hooks: how a lower layer offers a convenience method whose work an upper layer does.

:meth:`Mechanism.run <mechfem.Mechanism.run>` needs the deck writer and the run, :meth:`RunResult.plot
<mechfem.RunResult.plot>` needs matplotlib's figures; both classes sit below those modules, and a lower module never
imports an upper one (docs/architecture.md). So the lower module declares a :class:`Hook` with the signature it
needs, and the upper module registers its function when it is imported. ``import mechfem`` imports every layer, so
every hook is filled before a user can call one; a hook called before that says which module to import.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar

from mechfem.errors import MechfemError

F = TypeVar("F", bound=Callable[..., Any])


class Hook(Generic[F]):
    """One function a lower layer needs (of type ``F``), filled in by the upper module ``provider``."""

    def __init__(self, what: str, provider: str) -> None:
        self.what = what
        self.provider = provider
        self._fn: F | None = None

    def register(self, fn: F) -> F:
        """Fills the hook with ``fn`` (usable as a decorator); returns ``fn``."""
        self._fn = fn
        return fn

    @property
    def call(self) -> F:
        """The registered function; a MechfemError naming the module to import when none is registered yet."""
        if self._fn is None:
            raise MechfemError(
                f"{self.what} needs {self.provider}, which is not imported yet: import mechfem (or {self.provider})"
            )
        return self._fn
