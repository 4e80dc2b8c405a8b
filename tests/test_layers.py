"""The package's layers: hooks a lower layer declares and an upper one fills, and the public names."""

from __future__ import annotations

import types
from collections.abc import Callable

import pytest

import mechfem
from mechfem import model, result
from mechfem.hooks import Hook


def test_an_unfilled_hook_names_the_module_to_import() -> None:
    hook: Hook[Callable[[int], int]] = Hook("Thing.method", "mechfem.somewhere")
    with pytest.raises(mechfem.MechfemError, match=r"Thing\.method needs mechfem\.somewhere.*import mechfem"):
        hook.call(1)
    hook.register(lambda x: x + 1)
    assert hook.call(1) == 2


def test_import_mechfem_fills_every_hook_of_the_lower_layers() -> None:
    hooks = [v for mod in (model, result) for v in vars(mod).values() if isinstance(v, Hook)]
    assert len(hooks) >= 14
    for hook in hooks:
        assert callable(hook.call), hook.what


def test_all_lists_public_names_only() -> None:
    for name in mechfem.__all__:
        assert hasattr(mechfem, name), name
        value = getattr(mechfem, name)
        assert not isinstance(value, types.ModuleType), name
        assert name == "__version__" or not name.startswith("_"), name
    for leaked in ("os", "Path", "Callable", "version", "PackageNotFoundError"):
        assert leaked not in mechfem.__all__
        assert leaked not in dir(mechfem), leaked
