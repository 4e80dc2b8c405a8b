"""The documentation site: mkdocs builds docs/ with --strict (no warning, no broken link), and the links to the
repository's files outside docs/ lead to copies of those files in the site."""

from __future__ import annotations

import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

pytestmark = pytest.mark.skipif(
    importlib.util.find_spec("mkdocs") is None,
    reason="mkdocs is not installed (it comes with the dev extra: pip install -e '.[dev]', or make install)",
)

HOOKS = ROOT / "scripts" / "mkdocs_hooks.py"


def build(config: Path, site: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file", str(config), "--site-dir", str(site)],
        capture_output=True,
        text=True,
        timeout=300,
        stdin=subprocess.DEVNULL,
    )


@pytest.fixture(scope="module")
def site(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The repository's site, built once with --strict."""
    out = tmp_path_factory.mktemp("docs") / "site"
    proc = build(ROOT / "mkdocs.yml", out)
    assert proc.returncode == 0, proc.stderr
    assert "WARNING" not in proc.stderr
    return out


def test_the_site_builds_strictly_with_every_page(site: Path) -> None:
    # Every page of docs/ is in the navigation and in the site; README.md is the home page.
    pages = sorted(p.stem for p in (ROOT / "docs").glob("*.md"))
    nav = (ROOT / "mkdocs.yml").read_text()
    for page in pages:
        assert f" {page}.md" in nav, f"docs/{page}.md is missing from the nav of mkdocs.yml"
        if page != "README":
            assert (site / page / "index.html").is_file()
    home = (site / "index.html").read_text()
    assert "mechfem documentation" in home
    # A link to an example deck leads to that deck, copied into the site.
    assert 'href="repository/examples/supply/supply.mec"' in home
    copied = site / "repository" / "examples" / "supply" / "supply.mec"
    assert copied.read_bytes() == (ROOT / "examples" / "supply" / "supply.mec").read_bytes()
    # A link to a folder leads to a page listing its files.
    listing = (site / "repository" / "examples" / "gears" / "index.html").read_text()
    assert 'href="step_dwell.mec"' in listing


def test_every_link_out_of_docs_is_kept_in_the_site(site: Path) -> None:
    for page in (ROOT / "docs").glob("*.md"):
        for target in re.findall(r"\]\(\.\./([^)\s#]+)", page.read_text()):
            # A file is copied as it is, a Markdown file becomes a page, a folder a page listing its files.
            kept = site / "repository" / target
            page_of = kept.with_suffix("") / "index.html" if kept.suffix == ".md" else kept / "index.html"
            assert kept.is_file() or page_of.is_file(), f"docs/{page.name} links to ../{target}"


def small_site(tmp_path: Path, page: str) -> Path:
    """A site of one page that links to the repository around it."""
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "index.md").write_text(page)
    (tmp_path / "deck.mec").write_text("KIN ANA\n")
    config = tmp_path / "mkdocs.yml"
    config.write_text(f"site_name: t\ndocs_dir: docs\nhooks:\n  - {HOOKS}\n")
    return config


def test_a_broken_link_fails_the_strict_build(tmp_path: Path) -> None:
    config = small_site(tmp_path, "# Home\n\n[a deck](../deck.mec) and [a lost deck](../missing.mec)\n")
    proc = build(config, tmp_path / "site")
    assert proc.returncode != 0
    assert "missing.mec" in proc.stderr
    assert "deck.mec" not in proc.stderr.replace("missing.mec", "")


def test_a_link_out_of_docs_is_pointed_at_its_copy(tmp_path: Path) -> None:
    config = small_site(tmp_path, "# Home\n\n[a deck](../deck.mec#top)\n")
    proc = build(config, tmp_path / "site")
    assert proc.returncode == 0, proc.stderr
    assert 'href="repository/deck.mec#top"' in (tmp_path / "site" / "index.html").read_text()
    assert (tmp_path / "site" / "repository" / "deck.mec").read_text() == "KIN ANA\n"


def test_the_docs_python_examples_still_run_as_tests() -> None:
    # The site shows the pages as they are; their code is run by tests/model/test_model_api.py.
    text = (ROOT / "tests" / "model" / "test_model_api.py").read_text()
    for page in ("tutorial.md", "python-api.md"):
        assert f'"{page}"' in text
