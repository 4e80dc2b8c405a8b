"""The package's layers: module-level imports point one way (no circle), convenience methods reach the module that
does their work when called, and the public names."""

from __future__ import annotations

import ast
import subprocess
import sys
import types
from pathlib import Path

import mechfem

PACKAGE = Path(mechfem.__file__).parent


def _module_imports(path: Path) -> set[str]:
    """The package modules ``path`` imports when it is imported: at module level, not inside functions or methods
    (a lazy import in a method is not a dependency of the module) nor under ``if TYPE_CHECKING:``."""
    out: set[str] = set()
    body = list(ast.parse(path.read_text(encoding="utf-8")).body)
    while body:
        node = body.pop()
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            body.extend(node.orelse)
        elif isinstance(node, ast.If | ast.Try):
            body.extend(node.body + node.orelse + getattr(node, "finalbody", []))
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names if a.name.startswith("mechfem."))
        elif isinstance(node, ast.ImportFrom) and node.module is not None and node.level == 0:
            if node.module == "mechfem":
                out.update(f"mechfem.{a.name}" for a in node.names)
            elif node.module.startswith("mechfem."):
                out.add(node.module)
    return out


def _graph() -> dict[str, set[str]]:
    modules = {f"mechfem.{p.stem}": p for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    return {m: {d for d in _module_imports(p) if d in modules and d != m} for m, p in modules.items()}


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One circle of imports in ``graph``, or None (depth-first search, colouring the modules on the path)."""
    on_path: list[str] = []
    done: set[str] = set()

    def visit(m: str) -> list[str] | None:
        if m in on_path:
            return on_path[on_path.index(m) :] + [m]
        if m in done:
            return None
        on_path.append(m)
        for d in sorted(graph[m]):
            found = visit(d)
            if found:
                return found
        on_path.pop()
        done.add(m)
        return None

    for m in sorted(graph):
        found = visit(m)
        if found:
            return found
    return None


def test_module_level_imports_form_no_circle() -> None:
    graph = _graph()
    assert len(graph) > 40
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_the_circle_finder_finds_a_circle() -> None:
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_convenience_methods_work_with_only_their_own_module_imported() -> None:
    # Mechanism.run, to_deck and RunResult.to_html import the modules that do their work when called, so a script
    # that imports mechfem.model alone still gets them.
    code = (
        "import math\n"
        "from mechfem.model import Mechanism\n"
        "from mechfem.motion import Motion\n"
        "from mechfem.parts import Driven, Output\n"
        "m = Mechanism('fourbar')\n"
        "A0, B0 = m.fixed('A0', 0, 0), m.fixed('B0', 4, 0)\n"
        "A, B = m.point('A', 1, 0), m.point('B', 3.5, 2.5)\n"
        "m.bar('crank', A0, A, length=1.0, angle=Driven())\n"
        "m.bar('coupler', A, B, length=3.5)\n"
        "m.bar('rocker', B0, B, length=3.0, angle=Output('psi'))\n"
        "r = m.run(Motion.by(4, math.pi / 2))\n"
        "assert r.output('psi').shape == (5,)\n"
        "assert m.to_deck().strip()\n"
        "assert r.to_html().lstrip().lower().startswith('<!doctype html>')\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_all_lists_public_names_only() -> None:
    for name in mechfem.__all__:
        assert hasattr(mechfem, name), name
        value = getattr(mechfem, name)
        assert not isinstance(value, types.ModuleType), name
        assert name == "__version__" or not name.startswith("_"), name
    for leaked in ("os", "Path", "Callable", "version", "PackageNotFoundError"):
        assert leaked not in mechfem.__all__
        assert leaked not in dir(mechfem), leaked
