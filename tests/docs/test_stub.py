"""The stub python/mechfem/_core.pyi describes the compiled module: mypy's stubtest imports ``mechfem._core`` and
compares every name, signature, class and attribute it has with the stub (names missing on either side, parameters
that differ in name, kind or default, a class that cannot be subclassed yet is not @final)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def test_stub_matches_the_compiled_module() -> None:
    pytest.importorskip("mypy.stubtest", reason="mypy is a dev dependency: pip install -e '.[dev]'")
    proc = subprocess.run(
        [sys.executable, "-m", "mypy.stubtest", "--concise", "mechfem._core"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, f"_core.pyi differs from the compiled module:\n{proc.stdout}{proc.stderr}"
