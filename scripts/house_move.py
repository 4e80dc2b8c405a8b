"""Moves python/mechfem into sub-packages by stage and tests/ into folders that mirror them, in one deterministic step.

Run at the root of a clean checkout of any descendant of main:

    python scripts/house_move.py && git add -A && git commit -m "..."

It ``git mv``s every module per MODULES (and the report's assets per RESOURCES), writes each sub-package's
``__init__.py`` (PACKAGES: what it holds and what it may import), ``git mv``s every test file per TESTS, and
rewrites every import and every mention of a moved module or file in the repository's code, docs and
configuration (see SCOPE): ``from mechfem import x``, ``mechfem.x`` (imports, attribute paths, ``-m`` commands,
reST roles, strings such as monkeypatch targets), ``python/mechfem/x.py``, ``tests/test_x.py``, the imports of one
test file from another and the depth of ``Path(__file__)`` in a moved test. It then sorts the imports it touched
with the project's ruff (``ruff check --select I --fix``).

It stops before changing anything, naming what to add, when the tree holds a module or a test file that the tables
do not place, and it refuses to run on a tree it has already moved. Only the standard library (and ruff, a dev
dependency of the project) is used.
"""

from __future__ import annotations

import ast
import re
import shutil
import subprocess
import sys
import tokenize
from pathlib import Path

# Sub-packages, lowest first: a module of one may import at module level only from those listed before it
# (tests/test_layers.py checks it). The docstring of each one's __init__.py says so.
PACKAGES: dict[str, str] = {
    "_util": (
        "Private helpers without a model: atomic file writes, optional imports (pandas, ezdxf, pyarrow), the "
        "progress bar and console, the memory limit, argument checks and name suggestions. Imports nothing of "
        "mechfem but ``mechfem.errors`` and the compiled module."
    ),
    "model": (
        "A mechanism with its names: the element catalogue, units, parts, the builder methods, storage requests, "
        "motions, stop conditions, masses and loads, the compiled model's echo, and :class:`Mechanism` itself. "
        "Imports ``_util``; the run result only for type checking (``Mechanism.run`` imports the run when called). "
        "Re-exports the names a script imports from ``mechfem.model`` (docs/python-api.md)."
    ),
    "results": (
        "What a run gives: the run result (:class:`RunResult` over the core's named columns), its tables, the run "
        "report and its words, inverse dynamics, the designer's outputs and the labels (names and units) of every "
        "column. Imports ``_util`` and ``model``."
    ),
    "deck": (
        "Reading and writing decks for a Mechanism: numbering, the NAMES and UNITS of a deck, the deck writer and "
        "reader, errors in the model's words. Imports ``_util``, ``model`` and ``results``."
    ),
    "run": (
        "Running: the core model built through the typed builder, compiled models kept per topology, the named "
        "result of a run. Imports ``_util``, ``model``, ``results`` and ``deck``."
    ),
    "studies": (
        "Many runs: sweeps and ``run_many``, tolerance studies and bands, the cluster executor. Imports the "
        "packages up to ``run``."
    ),
    "design": (
        "Design sensitivities and optimisation: the engine, its stopping rules, multi-start, free timing, frame "
        "angle, full rotation, dynamic design, the optimum and its view, the synthesis statements and a KIN OPT "
        "deck's optimisation. Imports the packages up to ``studies``."
    ),
    "viz": (
        "Pictures of a run: the mechanism's drawing, plots, animation, figures, DXF/SVG export and notebook views. "
        "Imports ``_util``, ``model`` and ``results``."
    ),
    "report": (
        "The interactive HTML report, its charts, its DYN and KIN OPT sections, and its page (``template.html``, "
        "``assets/``, the vendored uPlot in ``vendor/``). Imports the packages up to ``viz``."
    ),
    "output": (
        "The output files of a command: the print file and data set, their formats, the media and the output "
        "folder. Imports the packages up to ``report``."
    ),
    "cli": (
        "The ``mechfem`` command (``command.py``). Imports every package below it; ``mechfem.cli.main`` is the "
        "entry point of the installed command and imports the command when called."
    ),
}

# Module of python/mechfem -> its place: "package.module".
MODULES: dict[str, str] = {
    "atomic": "_util.atomic",
    "checks": "_util.checks",
    "limits": "_util.limits",
    "names": "_util.names",
    "optional": "_util.optional",
    "progress": "_util.progress",
    "builders": "model.builders",
    "catalogue": "model.catalogue",
    "echo": "model.echo",
    "loads": "model.loads",
    "masses": "model.masses",
    "model": "model.mechanism",
    "motion": "model.motion",
    "parts": "model.parts",
    "stopping": "model.stopping",
    "storage": "model.storage",
    "units": "model.units",
    "converted": "results.converted",
    "designer": "results.designer",
    "inverse_dynamics": "results.inverse_dynamics",
    "labels": "results.labels",
    "result": "results.result",
    "result_tables": "results.result_tables",
    "table_columns": "results.table_columns",
    "run_report": "results.run_report",
    "words": "results.words",
    "deck_names": "deck.deck_names",
    "deckio": "deck.deckio",
    "explain": "deck.explain",
    "numbering": "deck.numbering",
    "building": "run.building",
    "compiled": "run.compiled",
    "namespace": "run.namespace",
    "running": "run.running",
    "bands": "studies.bands",
    "batch": "studies.batch",
    "cluster": "studies.cluster",
    "tolerance": "studies.tolerance",
    "tolerance_print": "studies.tolerance_print",
    "deck_synthesis": "design.deck_synthesis",
    "design": "design.engine",
    "design_rules": "design.rules",
    "dynamic_design": "design.dynamic_design",
    "dynamic_optimise": "design.dynamic_optimise",
    "fourbar_starts": "design.fourbar_starts",
    "frame_angle": "design.frame_angle",
    "full_rotation": "design.full_rotation",
    "multistart": "design.multistart",
    "optimise": "design.optimise",
    "angle_units": "design.angle_units",
    "optimise_deck": "design.optimise_deck",
    "optimum": "design.optimum",
    "optimum_view": "design.optimum_view",
    "timing": "design.timing",
    "animation": "viz.animation",
    "drawing": "viz.drawing",
    "export": "viz.export",
    "figures": "viz.figures",
    "mpl_drawing": "viz.mpl_drawing",
    "notebook": "viz.notebook",
    "plots": "viz.plots",
    "optimum_report": "report.optimum_report",
    "report": "report.html",
    "report_charts": "report.charts",
    "report_dynamics": "report.dynamics",
    "datasets": "output.datasets",
    "media": "output.media",
    "output": "output.files",
    "output_folder": "output.output_folder",
    "cli": "cli.command",
}

# What stays at the top of the package.
KEEP_MODULES = {"__init__", "__main__", "errors", "_version"}
KEEP_ENTRIES = {"_core.pyi", "py.typed", "studio_app"}

# Data files of the package: old path -> new path, relative to python/mechfem (read with importlib.resources).
RESOURCES: dict[str, str] = {
    "report_template.html": "report/template.html",
    "report_assets": "report/assets",
    "vendor": "report/vendor",
}

# Test file of tests/ -> "folder/test_name": the folder mirrors the sub-package, the name says the behaviour.
TESTS: dict[str, str] = {
    "test_resources": "_util/test_memory_limit",
    "test_catalogue": "model/test_catalogue",
    "test_dynamics_api": "model/test_dynamics_api",
    "test_gears": "model/test_gears",
    "test_model_api": "model/test_model_api",
    "test_python_units": "model/test_python_units",
    "test_shared_names": "model/test_shared_names",
    "test_typed_storage": "model/test_typed_storage",
    "test_designer_outputs": "results/test_designer_outputs",
    "test_dynamics_deck": "results/test_dynamics_deck",
    "test_error_parts": "results/test_error_parts",
    "test_labels": "results/test_labels",
    "test_layout": "results/test_layout",
    "test_named_errors": "results/test_named_errors",
    "test_one_result": "results/test_a_run_has_one_result_type",
    "test_typed_errors": "results/test_typed_errors",
    "test_units_power": "results/test_units_power",
    "test_pandas_units": "results/test_pandas_columns_carry_units",
    "test_roundtrip_units": "deck/test_round_trips_keep_given_values",
    "test_typed_report": "results/test_run_report_is_typed",
    "test_deck_echo": "deck/test_deck_echo",
    "test_deck_files": "deck/test_deck_files",
    "test_declared_names": "deck/test_declared_names",
    "test_names_units": "deck/test_names_units",
    "test_python_words": "deck/test_python_words",
    "test_roundtrip": "deck/test_roundtrip",
    "test_units_messages": "deck/test_units_messages",
    "test_api": "run/test_run_deck",
    "test_builder": "run/test_builder",
    "test_changed_coordinates": "run/test_changed_coordinates",
    "test_fast_runs": "run/test_runs_compute_only_what_is_asked",
    "test_hostile": "run/test_hostile",
    "test_interrupt": "run/test_interrupt",
    "test_kept_models": "run/test_a_topology_is_compiled_once",
    "test_limits": "run/test_limits",
    "test_no_deck_text": "run/test_no_deck_text",
    "test_simulate_api": "run/test_simulate_api",
    "test_simulate_deck": "run/test_simulate_deck",
    "test_simulate_settings": "run/test_simulate_settings",
    "test_batch": "studies/test_batch",
    "test_cluster": "studies/test_cluster",
    "test_tolerance_bands": "studies/test_tolerance_bands",
    "test_tolerance_columns": "studies/test_tolerance_columns",
    "test_tolerance_dynamic": "studies/test_tolerance_dynamic",
    "test_fourbar_starts": "design/test_fourbar_starts",
    "test_full_rotation_degrees": "design/test_full_rotation_degrees",
    "test_multistart": "design/test_multistart",
    "test_multistart_straight_line": "design/test_multistart_reaches_the_exact_straight_line",
    "test_optimise_timing_degrees": "design/test_free_timing_in_degrees",
    "test_published_benchmarks": "design/test_published_benchmarks",
    "test_optimise_api": "design/test_optimise_api",
    "test_optimise_branch": "design/test_optimise_branch",
    "test_optimise_deck": "design/test_optimise_deck",
    "test_optimise_deck_synthesis": "design/test_optimise_deck_synthesis",
    "test_optimise_dynamic": "design/test_optimise_dynamic",
    "test_optimise_edge": "design/test_optimise_edge",
    "test_optimise_frame_angle": "design/test_optimise_frame_angle",
    "test_optimise_full_rotation": "design/test_optimise_full_rotation",
    "test_optimise_periodic": "design/test_optimise_periodic",
    "test_optimise_stop": "design/test_optimise_stop",
    "test_optimise_timing": "design/test_optimise_timing",
    "test_export": "viz/test_export",
    "test_notebook": "viz/test_notebook",
    "test_pictures": "viz/test_pictures",
    "test_plot_and_drawings": "viz/test_plot_and_drawings",
    "test_optimum_report": "report/test_optimum_report",
    "test_report_browser": "report/test_report_browser",
    "test_report_dynamics": "report/test_report_dynamics",
    "test_report_page": "report/test_report_page",
    "test_report_screenshots": "report/test_report_screenshots",
    "test_confinement": "output/test_confinement",
    "test_named_outputs": "output/test_named_outputs",
    "test_output": "output/test_print_file_and_data_set",
    "test_output_folder": "output/test_output_folder",
    "test_units_outputs": "output/test_units_outputs",
    "test_cli": "cli/test_cli",
    "test_cli_progress": "cli/test_cli_progress",
    "test_hostile_modes": "cli/test_hostile_modes",
    "test_mutation": "cli/test_mutation",
    "test_progress": "cli/test_progress",
    "test_studio": "studio/test_studio",
    "test_studio_browser": "studio/test_studio_browser",
    "test_studio_jupyter": "studio/test_studio_in_jupyterlab",
    "test_bench_simulation": "docs/test_bench_simulation",
    "test_docs_site": "docs/test_docs_site",
    "test_elements_doc": "docs/test_elements_doc",
    "test_errors_doc": "docs/test_errors_doc",
    "test_examples": "docs/test_examples",
    "test_examples_speak_names": "docs/test_examples_speak_names",
    "test_readme": "docs/test_readme",
    "test_stub": "docs/test_stub",
}

# What stays at the top of tests/: the shared fixtures, a helper module, the package-wide layer test, the decks.
KEEP_TESTS = {"conftest.py", "bare_examples.py", "test_layers.py", "decks"}

# Where mentions are rewritten (tracked files only; the history in CHANGELOG.md is left as it was).
SCOPE = [
    "python",
    "tests",
    "benches",
    "scripts",
    "examples",
    "docs",
    ".ci",
    "crates/mechfem-py/src",
    "pyproject.toml",
    "Makefile",
    "mkdocs.yml",
    "README.md",
    "CONTRIBUTING.md",
]
TEXT_SUFFIXES = {".py", ".pyi", ".md", ".toml", ".yml", ".yaml", ".cfg", ".txt", ".rs", ".js", ".html", ".css", ""}

# Names that scripts and docs import from ``mechfem.model`` (docs/python-api.md): the sub-package re-exports them.
MODEL_EXPORTS = ["By", "Driven", "Dynamic", "Keep", "Mechanism", "Motion", "Output", "Storage", "Table", "To"]

# One name, one class: internal classes that share a name with another class of the package get a name of their own
# (module of today, class, new name). In the defining module every mention is renamed; elsewhere where the class is
# imported by name, or reached as ``module.Class``. The public names (mechfem.__all__) keep theirs.
CLASS_RENAMES: list[tuple[str, str, str]] = [
    ("output_folder", "Plan", "OutputPlan"),  # timing.Plan is a free timing made ready for the engine
    ("export", "Label", "PointLabel"),  # labels.Label is a column's name and unit
    ("design_rules", "Stop", "FTol"),  # the stopping tolerance on f (OPTFTOL); mechfem.Stop is why a run stopped
    ("result_tables", "Target", "NameTarget"),  # mechfem.Target is an optimisation target
    ("studio_app.session", "Outcome", "EditOutcome"),  # optimise_deck.Outcome is a deck's optimisation
]
# The protocols of what a lower module needs of a Mechanism (which sits above it): (module, new name); only the
# class line and the annotations ``mech: Mechanism`` are renamed, the prose names the real Mechanism.
PROTOCOL_RENAMES: dict[str, str] = {"motion": "MechanismInputs", "loads": "MechanismLoads"}

# Text that keeps its spelling: the installed command's entry point (mechfem.cli.main, see PACKAGES["cli"]).
PRESERVE = ["mechfem.cli:main"]

PKG = Path("python/mechfem")
SELF = "scripts/house_move.py"


def fail(lines: list[str]) -> None:
    print("house_move: nothing was changed.", file=sys.stderr)
    for line in lines:
        print("  " + line, file=sys.stderr)
    sys.exit(1)


def git(*args: str) -> str:
    return subprocess.run(["git", *args], check=True, capture_output=True, text=True).stdout


def ruff() -> str:
    for candidate in (Path(".venv/bin/ruff"), shutil.which("ruff")):
        if candidate and Path(candidate).exists():
            return str(candidate)
    fail(["ruff is needed to sort the rewritten imports: `make install` (it installs the dev tools into .venv)"])
    raise AssertionError


def check_tree() -> None:
    """Refuses a tree already moved, a dirty tree, and a module or test file that the tables do not place."""
    if not (PKG / "__init__.py").exists():
        fail(["run this at the root of the repository (python/mechfem/__init__.py not found)"])
    moved = [p for p in PACKAGES if (PKG / p / "__init__.py").exists()]
    if moved:
        fail([f"the package is already moved (python/mechfem/{moved[0]}/ exists): the script runs once"])
    if git("status", "--porcelain", "--untracked-files=no").strip():
        fail(["the work tree has uncommitted changes: commit or stash them first"])
    problems: list[str] = []
    tracked = git("ls-files", "python/mechfem", "tests").splitlines()
    top = sorted({Path(t).relative_to(PKG).parts[0] for t in tracked if t.startswith(f"{PKG}/")})
    for entry in top:
        stem = entry[:-3] if entry.endswith(".py") else None
        if stem is not None and (stem in MODULES or stem in KEEP_MODULES):
            continue
        if entry in KEEP_ENTRIES or entry in RESOURCES:
            continue
        if stem is not None:
            problems.append(f'python/mechfem/{entry}: add a line to MODULES, e.g.  "{stem}": "<package>.{stem}",')
        else:
            problems.append(f"python/mechfem/{entry}: add it to RESOURCES (data) or KEEP_ENTRIES (stays on top)")
    tests = sorted({Path(t).parts[1] for t in tracked if t.startswith("tests/") and len(Path(t).parts) > 1})
    for entry in tests:
        if entry in KEEP_TESTS or (entry.endswith(".py") and entry[:-3] in TESTS):
            continue
        if entry.endswith(".py"):
            problems.append(f'tests/{entry}: add a line to TESTS, e.g.  "{entry[:-3]}": "<folder>/<behaviour>",')
        else:
            problems.append(f"tests/{entry}: add it to KEEP_TESTS or move it by hand first")
    new_tests = [t.split("/")[-1] for t in TESTS.values()]
    doubles = sorted({n for n in new_tests if new_tests.count(n) > 1})
    if doubles:
        problems.append(f"TESTS gives two files one name (pytest imports them by name): {', '.join(doubles)}")
    if problems:
        fail(["the tables do not place everything:", *problems])
    stale = [m for m in MODULES if not (PKG / f"{m}.py").exists()]
    stale += [t for t in TESTS if not Path(f"tests/{t}.py").exists()]
    for s in stale:
        print(f"house_move: {s} is in the tables but not in the tree: skipped", file=sys.stderr)


def rewrite_dotted(text: str, markdown: bool) -> str:
    """``mechfem.x`` -> ``mechfem.pkg.y`` (not ``mechfem.x_y``, not ``other.mechfem.x``)."""
    names = dict(MODULES)
    if markdown:
        # A doc keeps ``from mechfem.model import By, Storage, To``: the sub-package re-exports those names.
        names.pop("model")
    alternation = "|".join(sorted(map(re.escape, names), key=len, reverse=True))
    pattern = re.compile(rf"(?<![\w.])mechfem\.({alternation})(?![\w])")
    return pattern.sub(lambda m: f"mechfem.{names[m.group(1)]}", text)


PATH_RE = re.compile(
    r"(?<![\w.])(python/mechfem/|mechfem/)("
    + "|".join(sorted(map(re.escape, MODULES), key=len, reverse=True))
    + r")\.py\b"
)
TEST_PATH_RE = re.compile(
    r"(?<![\w.])tests/(" + "|".join(sorted(map(re.escape, TESTS), key=len, reverse=True)) + r")\.py\b"
)
TEST_JOIN_RE = re.compile(
    r'("tests" / )"(' + "|".join(sorted(map(re.escape, TESTS), key=len, reverse=True)) + r')\.py"'
)
RENAMED_TESTS = {old: new.split("/")[1] for old, new in TESTS.items() if old != new.split("/")[1]}
BARE_TEST_RE = (
    re.compile(r"(?<![\w./])(" + "|".join(map(re.escape, RENAMED_TESTS)) + r")\.py\b") if RENAMED_TESTS else None
)


def rewrite_paths(text: str) -> str:
    text = PATH_RE.sub(lambda m: f"{m.group(1)}{MODULES[m.group(2)].replace('.', '/')}.py", text)
    text = TEST_PATH_RE.sub(lambda m: f"tests/{TESTS[m.group(1)]}.py", text)
    # ROOT / "tests" / "test_x.py" in a test
    text = TEST_JOIN_RE.sub(
        lambda m: m.group(1) + " / ".join(f'"{part}"' for part in f"{TESTS[m.group(2)]}.py".split("/")), text
    )
    if BARE_TEST_RE is not None:
        text = BARE_TEST_RE.sub(lambda m: f"{RENAMED_TESTS[m.group(1)]}.py", text)
    for old, new in RESOURCES.items():
        # python/mechfem/vendor/uplot, "vendor/uplot/LICENSE", report_assets/page.js, report_template.html
        text = re.sub(rf"(?<![\w.-]){re.escape(old)}(?=[/\"'`) ]|$)", new, text, flags=re.M)
        text = text.replace(f"python/mechfem/{new.split('/')[0]}/{old}", f"python/mechfem/{new}")
    return text


def from_mechfem_import(names: list[tuple[str, str | None]], indent: str) -> list[str]:
    """The statements of ``from mechfem import <names>``, each moved module from its sub-package."""
    stay = [(n, a) for n, a in names if n not in MODULES]
    groups: dict[str, list[str]] = {}
    for n, a in names:
        if n in MODULES:
            package, leaf = MODULES[n].split(".")
            alias = a or (n if leaf != n else None)
            groups.setdefault(package, []).append(f"{leaf} as {alias}" if alias else leaf)
    out = []
    if stay:
        out.append(f"{indent}from mechfem import " + ", ".join(f"{n} as {a}" if a else n for n, a in stay))
    for package in sorted(groups):
        out.append(f"{indent}from mechfem.{package} import " + ", ".join(groups[package]))
    return out


def rewrite_python_imports(text: str, path: str) -> str:
    """``from mechfem import x`` (x a moved module) and ``from test_x import`` of a moved test file."""
    try:
        tree = ast.parse(text)
    except SyntaxError:
        return text
    lines = text.splitlines(keepends=True)
    edits: list[tuple[int, int, list[str]]] = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom) or node.level != 0 or node.module is None:
            continue
        indent = " " * node.col_offset
        names = [(a.name, a.asname) for a in node.names]
        if node.module == "mechfem" and any(n in MODULES for n, _ in names):
            new = from_mechfem_import(names, indent)
        elif path.startswith("tests/") and node.module in TESTS:
            new = [
                f"{indent}from {TESTS[node.module].replace('/', '.')} import "
                + ", ".join(f"{n} as {a}" if a else n for n, a in names)
            ]
        else:
            continue
        first, last = node.lineno - 1, (node.end_lineno or node.lineno) - 1
        after = lines[last].rstrip("\n")[node.end_col_offset :].strip()
        if lines[first][: node.col_offset].strip() or (after and not after.startswith("#")):
            raise SystemExit(f"house_move: {path}:{node.lineno}: an import shares its line; split it and run again")
        if after:
            new = [f"{line}  {after}" for line in new]
        edits.append((first, last, [line + "\n" for line in new]))
    for first, last, new in sorted(edits, reverse=True):
        lines[first : last + 1] = new
    return "".join(lines)


FILE_DEPTH_RE = re.compile(r"Path\(__file__\)(\.resolve\(\))?(\.parents\[(\d+)\]|(?:\.parent(?!s))+)")


def deeper(text: str) -> str:
    """A test moved one folder down: ``Path(__file__).parent`` -> ``.parents[1]``, ``.parents[1]`` -> ``[2]``."""

    def one_more(m: re.Match[str]) -> str:
        depth = int(m.group(3)) + 1 if m.group(3) is not None else m.group(2).count(".parent")
        return f"Path(__file__){m.group(1) or ''}.parents[{depth}]"

    return FILE_DEPTH_RE.sub(one_more, text)


def rename_name(text: str, old: str, new: str) -> str:
    """``old`` -> ``new`` where it is code (a name token), and in strings and comments where it names the class
    (``:class:`old```, ``old.attr``, ``old's``, ``old(``), not where it is a word (``Stop when ...``)."""
    word = re.compile(rf"(?<!\w){old}(?!\w)")

    def names_the_class(part: str, m: re.Match[str]) -> bool:
        before, after = part[m.start() - 1 : m.start()], part[m.end() : m.end() + 1]
        return before in ("`", "~", ".") or after in ("`", ".", "(", "'")

    lines = text.splitlines(keepends=True)
    spans: list[tuple[int, int, int]] = []
    for tok in tokenize.generate_tokens(iter(lines).__next__):
        if tok.type == tokenize.NAME and tok.string == old:
            spans.append((tok.start[0], tok.start[1], tok.end[1]))
        elif tok.type == tokenize.STRING and tok.string[1:-1] == old:  # __all__'s entry
            spans.append((tok.start[0], tok.start[1] + 1, tok.end[1] - 1))
        elif tok.type in (tokenize.STRING, tokenize.COMMENT) and old in tok.string:
            row, col = tok.start
            for k, part in enumerate(tok.string.split("\n")):
                offset = col if k == 0 else 0
                for m in word.finditer(part):
                    if names_the_class(part, m):
                        spans.append((row + k, offset + m.start(), offset + m.end()))
    for row, start, end in sorted(spans, reverse=True):
        line = lines[row - 1]
        lines[row - 1] = line[:start] + new + line[end:]
    return "".join(lines)


def rename_classes(text: str, path: str) -> str:
    """CLASS_RENAMES and PROTOCOL_RENAMES in one file of today's tree."""
    for module, old, new in CLASS_RENAMES:
        defining = path == f"{PKG}/{module.replace('.', '/')}.py"
        imported = re.search(rf"from mechfem\.{re.escape(module)} import [^\n]*\b{old}\b", text) or re.search(
            rf"from mechfem\.{re.escape(module)} import \([^)]*\b{old}\b", text
        )
        if defining or imported:
            text = rename_name(text, old, new)
        leaf = module.split(".")[-1]
        text = re.sub(rf"\b{re.escape(leaf)}\.{old}\b", f"{leaf}.{new}", text)
    for module, new in PROTOCOL_RENAMES.items():
        if path == f"{PKG}/{module}.py":
            text = text.replace("class Mechanism(Protocol):", f"class {new}(Protocol):")
            text = re.sub(r"\bmech: Mechanism\b", f"mech: {new}", text)
    return text


def rewrite(text: str, path: str) -> str:
    markdown = not path.endswith((".py", ".pyi"))
    held = {f"\0{i}\0": p for i, p in enumerate(PRESERVE)}
    for key, p in held.items():
        text = text.replace(p, key)
    if path.endswith(".py"):
        text = rename_classes(text, path)
    # Dotted paths first: the imports written next name sub-packages (``from mechfem.model import loads``) that
    # share a name with a module of today (``mechfem.model``).
    text = rewrite_paths(rewrite_dotted(text, markdown))
    if path.endswith(".py"):
        text = rewrite_python_imports(text, path)
    # ``from mechfem import x`` on one line of a doc's code block, or of code in a string (a test's subprocess).
    text = re.sub(
        r"^([ \t]*)from mechfem import ([\w, ]+)$",
        lambda m: "\n".join(
            from_mechfem_import(
                [
                    (n.split(" as ")[0].strip(), (n.split(" as ")[1].strip() if " as " in n else None))
                    for n in m.group(2).split(",")
                ],
                m.group(1),
            )
        ),
        text,
        flags=re.M,
    )
    for key, p in held.items():
        text = text.replace(key, p)
    return text


def init_text(package: str) -> str:
    words = PACKAGES[package]
    paragraph: list[str] = []
    line = '"""'
    for word in words.split():
        if len(line) + 1 + len(word) > 116:
            paragraph.append(line)
            line = word
        else:
            line = f"{line} {word}" if line != '"""' else line + word
    paragraph.append(line + '"""')
    out = "\n".join(paragraph) + "\n"
    if package == "model":
        out += f"\nfrom mechfem.model.mechanism import {', '.join(MODEL_EXPORTS)}\n\n"
        out += "__all__ = [" + ", ".join(f'"{n}"' for n in MODEL_EXPORTS) + "]\n"
    if package == "cli":
        out += (
            "\n\ndef main(argv: list[str] | None = None) -> int:\n"
            '    """Runs the command line; returns the exit status (:func:`mechfem.cli.command.main`)."""\n'
            "    from mechfem.cli.command import main as command\n\n"
            "    return command(argv)\n"
        )
    return out


LINE_LENGTH = 120  # pyproject.toml, [tool.ruff]


def prose_lines(text: str) -> set[int]:
    """The 0-based numbers of the lines that hold only prose: comment lines and the lines of docstrings."""
    out: set[int] = set()
    tree = ast.parse(text)
    for node in ast.walk(tree):
        # A string standing as a statement: a docstring, or the docstring of an attribute or a constant.
        if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str):
            out.update(range(node.lineno - 1, node.end_lineno or node.lineno))
    lines = text.splitlines()
    for tok in tokenize.generate_tokens(iter(text.splitlines(keepends=True)).__next__):
        if tok.type == tokenize.COMMENT and not lines[tok.start[0] - 1][: tok.start[1]].strip():
            out.add(tok.start[0] - 1)
    return out


def wrap_prose(text: str) -> str:
    """Breaks a comment or docstring line that a longer path made too long, at its last space that fits, and carries
    the rest over to the start of the paragraph's next line (a line of its own where the paragraph ends)."""
    lines = [line.rstrip("\n") for line in text.splitlines()]
    prose = prose_lines(text)
    i = 0
    while i < len(lines):
        body = lines[i]
        stripped = body.lstrip()
        indent = body[: len(body) - len(stripped)]
        lead = "# " if stripped.startswith("#") else ""
        cut = body.rfind(" ", len(indent) + 10, LINE_LENGTH + 1)
        if i not in prose or len(body) <= LINE_LENGTH or cut < 0:
            i += 1
            continue
        lines[i], rest = body[:cut], body[cut + 1 :]
        after = lines[i + 1] if i + 1 < len(lines) else ""
        after_text = after.strip()[len(lead) :] if after.strip().startswith(lead.strip()) else ""
        same_paragraph = (
            i + 1 in prose
            and after.startswith(indent)
            and after_text
            and not after_text.startswith(("* ", "- ", '"""'))
            and (lead == "") == (not after.strip().startswith("#"))
            and not rest.endswith('"""')
        )
        if same_paragraph:
            lines[i + 1] = f"{after[: len(after) - len(after.lstrip())]}{lead}{rest} {after_text}"
        else:
            lines.insert(i + 1, f"{indent}{lead}{rest}")
            prose = {k + 1 if k > i else k for k in prose} | {i + 1}
        i += 1
    return "\n".join(lines) + ("\n" if text.endswith("\n") else "")


def long_lines(paths: list[str]) -> list[str]:
    return [
        f"{path}:{n}"
        for path in paths
        for n, line in enumerate(Path(path).read_text(encoding="utf-8").splitlines(), 1)
        # ruff lets a line that ends with a pragma comment be longer
        if len(line) > LINE_LENGTH and not re.search(r"#\s*(type:|noqa)", line)
    ]


def destination(path: str, moves: dict[str, str]) -> str:
    """Where ``path`` is after the moves (a file of a moved folder moves with it)."""
    for old, new in moves.items():
        if path == old or path.startswith(old + "/"):
            return new + path[len(old) :]
    return path


def main() -> None:
    check_tree()
    ruff_exe = ruff()
    moves: dict[str, str] = {}
    for old, new in MODULES.items():
        if (PKG / f"{old}.py").exists():
            moves[f"{PKG}/{old}.py"] = f"{PKG}/{new.replace('.', '/')}.py"
    for old, new in RESOURCES.items():
        if (PKG / old).exists():
            moves[f"{PKG}/{old}"] = f"{PKG}/{new}"
    for old, new in TESTS.items():
        if Path(f"tests/{old}.py").exists():
            moves[f"tests/{old}.py"] = f"tests/{new}.py"

    # Every rewrite is made in memory first, so that a file the script cannot rewrite stops it before any change.
    texts: dict[str, str] = {}
    for path in sorted(git("ls-files", *SCOPE).splitlines()):
        p = Path(path)
        if path == SELF or "/vendor/" in path or p.suffix not in TEXT_SUFFIXES or not p.is_file():
            continue
        try:
            text = p.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        new = rewrite(text, path)
        if path.startswith("tests/") and path in moves:
            new = deeper(new)
        if new != text:
            texts[destination(path, moves)] = new

    for package in PACKAGES:
        (PKG / package).mkdir(exist_ok=True)
    for new in moves.values():
        Path(new).parent.mkdir(parents=True, exist_ok=True)
    for old, new in moves.items():
        git("mv", old, new)
    for path, text in texts.items():
        Path(path).write_text(text, encoding="utf-8")
    for package in PACKAGES:
        (PKG / package / "__init__.py").write_text(init_text(package), encoding="utf-8")
    py = [t for t in texts if t.endswith(".py")] + [str(PKG / p / "__init__.py") for p in PACKAGES]
    subprocess.run([ruff_exe, "check", "--quiet", "--select", "I", "--fix", *py], check=False)
    subprocess.run([ruff_exe, "format", "--quiet", *py], check=False)
    for path in py:
        text = Path(path).read_text(encoding="utf-8")
        Path(path).write_text(wrap_prose(text), encoding="utf-8")
    for where in long_lines(py):
        print(f"house_move: {where}: longer than {LINE_LENGTH} characters, to wrap by hand", file=sys.stderr)
    git("add", "-A", *[s for s in SCOPE if Path(s).exists()])
    print(f"house_move: moved {len(moves)} files, rewrote {len(texts)}; now: git add -A && git commit")


if __name__ == "__main__":
    main()
