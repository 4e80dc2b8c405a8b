"""The README's quick start: exactly two commands, both Makefile targets, and the demo's deck runs."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from conftest import ROOT, Cli

QUICK_START = re.compile(r"## Quick start\n(.*?)\n## ", re.S)


def readme_commands() -> list[str]:
    section = QUICK_START.search((ROOT / "README.md").read_text())
    assert section, "README.md has no '## Quick start' section"
    blocks = re.findall(r"```(?:sh|bash|console)?\n(.*?)```", section.group(1), re.S)
    return [line.strip() for block in blocks for line in block.splitlines() if line.strip()]


def makefile_recipe(target: str) -> list[str]:
    text = (ROOT / "Makefile").read_text()
    match = re.search(rf"^{target}:.*\n((?:\t.*\n)*)", text, re.M)
    assert match, f"the Makefile has no target {target}"
    return [line.strip() for line in match.group(1).splitlines()]


def test_readme_quick_start_is_make_demo_and_make_test() -> None:
    assert readme_commands() == ["make demo", "make test"]
    for command in readme_commands():
        makefile_recipe(command.split()[1])


def test_ci_runs_the_readmes_test_command() -> None:
    ci = (ROOT / ".ci" / "run").read_text()
    assert "make test" in ci


def test_demo_runs(cli: Cli, tmp_path: Path) -> None:
    run = next(line for line in makefile_recipe("demo") if " run " in line)
    args = shlex.split(run)[1:]
    assert args[0] == "run"
    deck = ROOT / args[1]
    assert deck.is_file()
    proc = cli("run", deck, "-o", tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / f"{deck.stem}.prt").is_file()
    # The README says where the demo's outputs go.
    out = args[args.index("-o") + 1]
    assert out in (ROOT / "README.md").read_text()


def test_readme_python_example_runs(monkeypatch: pytest.MonkeyPatch) -> None:
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert blocks
    monkeypatch.chdir(ROOT)
    for block in blocks:
        exec(compile(block, "README.md", "exec"), {})


def test_readme_links_exist() -> None:
    text = (ROOT / "README.md").read_text()
    for target in re.findall(r"\]\(([^)#:]+)\)", text):
        assert (ROOT / target).exists(), target
