"""The package's layers: module-level imports point one way (no circle), each sub-package imports only the
sub-packages below it, convenience methods reach the module that does their work when called, and the public names."""

from __future__ import annotations

import ast
import subprocess
import sys
import types
from pathlib import Path

import mechfem

PACKAGE = Path(mechfem.__file__).parent

# The sub-packages, lowest first (docs/architecture.md): a module of one imports at module level only from the
# sub-packages before it, from its own, and from the top-level modules (errors, _version, the compiled module).
LAYERS = ["_util", "model", "results", "deck", "run", "studies", "design", "viz", "report", "output", "studio_app"]
LAYERS += ["cli"]


def _name(path: Path) -> str:
    parts = path.relative_to(PACKAGE).with_suffix("").parts
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(("mechfem", *parts))


MODULES = {_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


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
            if node.module == "mechfem" or node.module.startswith("mechfem."):
                # ``from mechfem.deck import deckio`` imports a module of the sub-package; ``from mechfem.deck
                # import DeckNames`` imports the sub-package's __init__.
                for a in node.names:
                    out.add(f"{node.module}.{a.name}" if f"{node.module}.{a.name}" in MODULES else node.module)
    return out


def _graph() -> dict[str, set[str]]:
    modules = {m: p for m, p in MODULES.items() if m != "mechfem"}
    return {m: {d for d in _module_imports(p) if d in modules and d != m} for m, p in modules.items()}


def _layer(module: str) -> int:
    """The place of ``module``'s sub-package in LAYERS; -1 for a top-level module, which any module may import."""
    parts = module.split(".")
    return LAYERS.index(parts[1]) if len(parts) > 1 and parts[1] in LAYERS else -1


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


def test_sub_packages_import_only_the_sub_packages_below_them() -> None:
    upward = [f"{m} -> {d}" for m, deps in sorted(_graph().items()) for d in sorted(deps) if _layer(d) > _layer(m) >= 0]
    assert not upward, "module-level imports that point up: " + ", ".join(upward)


def test_the_layer_check_finds_an_upward_import() -> None:
    assert _layer("mechfem.deck.deckio") == 3
    assert _layer("mechfem.errors") == -1
    assert _layer("mechfem.viz.plots") > _layer("mechfem.results.result") > 0


def test_the_circle_finder_finds_a_circle() -> None:
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


def test_convenience_methods_work_with_only_their_own_module_imported() -> None:
    # Mechanism.run, to_deck and RunResult.to_html import the modules that do their work when called, so a script
    # that imports mechfem.model.mechanism alone still gets them.
    code = (
        "import math\n"
        "from mechfem.model.mechanism import Mechanism\n"
        "from mechfem.model.motion import Motion\n"
        "from mechfem.model.parts import Driven, Output\n"
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


def test_the_top_level_holds_only_the_public_api_and_what_every_layer_needs() -> None:
    # Every other module lives in the sub-package of its stage (docs/architecture.md, "The Python package").
    top = sorted(p.stem for p in PACKAGE.glob("*.py"))
    assert top == ["__init__", "__main__", "_version", "errors"]
    subpackages = sorted(p.parent.name for p in PACKAGE.glob("*/__init__.py"))
    assert subpackages == sorted(LAYERS)


def test_every_sub_package_says_what_it_holds_and_may_import() -> None:
    for name in LAYERS:
        doc = ast.get_docstring(ast.parse((PACKAGE / name / "__init__.py").read_text(encoding="utf-8")))
        assert doc and "import" in doc.lower(), name


def test_no_module_is_over_600_lines() -> None:
    long = {m: n for m, p in MODULES.items() if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert not long, long


def test_no_two_classes_of_the_package_share_a_name() -> None:
    where: dict[str, list[str]] = {}
    for module, path in MODULES.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in tree.body:
            if isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
                where.setdefault(node.name, []).append(module)
            elif isinstance(node, ast.ImportFrom) and node.module == "mechfem._core":
                # ``from mechfem._core import Storage as Storage`` hands the compiled class on under its name.
                for a in node.names:
                    if a.asname == a.name:
                        where.setdefault(a.name, []).append(f"{module} (mechfem._core)")
    twice = {name: modules for name, modules in where.items() if len(modules) > 1}
    assert not twice, twice
