"""Shared fixtures: the repository's folders and a way to run the ``mechfem`` command."""

from __future__ import annotations

import shutil
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parent.parent

# A shell started without job control (`cmd &` in a script) starts its children with Ctrl-C ignored, and Python
# then never raises KeyboardInterrupt. The interrupt tests press Ctrl-C on purpose: give it back its usual meaning
# here, and to the processes the tests start (an ignored signal is inherited through exec, a handler is not).
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
SUPPLY = ROOT / "examples" / "supply" / "supply.mec"
# A crank-rocker four-bar (crank 1, coupler 3, rocker 2.5, frame 3.2) with a coupler point, recording positions:
# the same deck text for the tests that need one.
FOURBAR = """KIN ANA
TOPOLOGY
ELEM 1 BIN 1 2 5 6
     2 TR2 5 6 7 8 9 10
     3 BIN 3 4 7 8
FORM 1 LENL 1 1
     2 LENL 2 2
     3 LENL 3 3
     4 LENU 2 4
     5 LENV 2 5
     6 ANGB 1 6
NRDOF 1
GEOMETRY
XFIX 1 0.0
 2 0.0
 3 3.2
 4 0.0
XMOV 5 1.0
 6 0.0
 7 2.725
 8 2.4545
 9 1.02
 10 1.8
PARA 1 1.0
 2 3.0
 3 2.5
 4 1.4857
 5 1.0164
 6 0.0
MOVEMENT
TSTEPE 360 0.01
MOV_RELE 1 6.283185307179586
STORAGE
BUFX0 5 1
BUFX0 6 2
BUFX0 9 3
BUFX0 10 4
"""

STOP_MARK = "; expect: the motion stops at a limit position"


def stops_on_purpose(deck: Path) -> bool:
    """Whether an example deck demonstrates a driven motion stopping at a limit
    position (it says so in a comment line); such a run exits with status 3."""
    return STOP_MARK in deck.read_text()


Cli = Callable[..., subprocess.CompletedProcess[str]]


def mechfem_command() -> list[str]:
    """The installed console script, or the module when running from a tree without one."""
    script = Path(sys.executable).parent / "mechfem"
    if script.exists():
        return [str(script)]
    found = shutil.which("mechfem")
    return [found] if found else [sys.executable, "-m", "mechfem.cli.command"]


@pytest.fixture
def cli() -> Cli:
    """Runs ``mechfem ARGS...`` without stdin and returns the finished process (text output)."""

    def run(*args: str | Path, cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [*mechfem_command(), *map(str, args)],
            cwd=cwd,
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            timeout=300,
        )

    return run


@pytest.fixture
def supply_with_savedata(tmp_path: Path) -> Path:
    """A copy of the supply deck (it saves its four buffers) in a folder of its own."""
    deck = tmp_path / "deck" / "supply.mec"
    deck.parent.mkdir()
    deck.write_text(SUPPLY.read_text())
    return deck


# The slow families of tests (pyproject.toml's markers): `make test` runs them with the rest and shows their time
# apart, so that a change that makes one of them slower is seen. With pytest-xdist the reports reach these hooks in
# the controlling process, each with its test's markers among its keywords.
SLOW_FAMILIES = ("browser", "cluster", "large_run")
_family_time: dict[str, list[float]] = {}


def fourbar_mm_deg(units: dict[str, str | None] | None = None) -> Any:
    """A crank-rocker four-bar in mm and degrees (crank 10, coupler 35, rocker 30, frame 40), its crank the input
    ``phi`` and its rocker angle the output ``psi``: the model in other units than SI that several tests share."""
    from mechfem import Driven, Mechanism, Output

    m = Mechanism("fourbar", units=units or {"length": "mm"}, angle="deg")
    A0, B0 = m.fixed("A0", 0.0, 0.0), m.fixed("B0", 40.0, 0.0)
    A, B = m.point("A", 10.0, 0.0), m.point("B", 35.0, 25.0)
    m.bar("crank", A0, A, length=10.0, angle=Driven(start=0.0, name="phi"))
    m.bar("coupler", A, B, length=35.0)
    m.bar("rocker", B0, B, length=30.0, angle=Output("psi"))
    return m


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    family = next((f for f in SLOW_FAMILIES if f in report.keywords), "other")
    count_and_seconds = _family_time.setdefault(family, [0, 0.0])
    count_and_seconds[0] += report.when == "call"
    count_and_seconds[1] += report.duration


def pytest_terminal_summary(terminalreporter: pytest.TerminalReporter) -> None:
    if not _family_time:
        return
    total = sum(s for _, s in _family_time.values())
    terminalreporter.section("time by family (seconds of test time, all workers together)")
    for family in (*SLOW_FAMILIES, "other"):
        if family in _family_time:
            n, seconds = _family_time[family]
            terminalreporter.write_line(f"{family:>10}: {int(n):4d} tests {seconds:8.1f} s ({seconds / total:.0%})")
