"""MkDocs hooks for the documentation site (mkdocs.yml): links from docs/ to the rest of the repository.

The pages link to example decks, test decks and sources with paths relative to the repository
(``../examples/fourbar/fourbar.mec``), so that they work where the Markdown is read in the repository
itself. The site has only docs/ in it, and a strict build refuses such links. These hooks copy every file
a page links to outside docs/ into the site under ``repository/`` (a linked folder gets a page that
lists its files) and point the links there, so the site keeps the decks the pages talk about. A link to
something that does not exist is left as it is, and the strict build reports it.
"""

from __future__ import annotations

import posixpath
import re
from pathlib import Path
from typing import Any

from mkdocs.structure.files import File, Files

PREFIX = "repository"
"""The folder of the site that holds the repository's files the pages link to."""

# An inline Markdown link or image target that leaves docs/: ](../path) or ](../path#anchor).
LINK = re.compile(r"\]\((\.\./[^)\s#]*)(#[^)\s]*)?\)")

# What the hooks found in on_files, for on_page_markdown: repository path -> the site's source URI.
_targets: dict[str, str] = {}


def _root(config: Any) -> Path:
    return Path(config["docs_dir"]).resolve().parent


def _outside(page_dir: Path, link: str, root: Path) -> Path | None:
    """The file or folder a link from ``page_dir`` names when it is outside docs/ but inside the repository."""
    target = (page_dir / link).resolve()
    try:
        target.relative_to(root)
    except ValueError:
        return None
    return target if target.exists() else None


def _contents(folder: Path) -> list[Path]:
    """The files in a folder and its sub-folders, without hidden files and caches."""

    def shown(p: Path) -> bool:
        return not any(part.startswith(".") or part == "__pycache__" for part in p.relative_to(folder).parts)

    return sorted(p for p in folder.rglob("*") if p.is_file() and shown(p))


def _listing(rel: str, folder: Path) -> str:
    """The page of a linked folder: its files, each linked."""
    names = [p.relative_to(folder).as_posix() for p in _contents(folder)]
    lines = [f"# {rel}/", "", f"The files of `{rel}/` in the repository:", ""]
    lines += [f"* [{name}]({name})" for name in names]
    return "\n".join(lines) + "\n"


def on_files(files: Files, config: Any) -> Files:
    root = _root(config)
    docs = Path(config["docs_dir"]).resolve()
    _targets.clear()
    for page in docs.rglob("*.md"):
        for match in LINK.finditer(page.read_text(encoding="utf-8")):
            target = _outside(page.parent, match.group(1), root)
            if target is None or target.is_relative_to(docs):
                continue
            rel = target.relative_to(root).as_posix()
            if rel in _targets:
                continue
            if target.is_dir():
                uri = f"{PREFIX}/{rel}/index.md"
                files.append(File.generated(config, uri, content=_listing(rel, target)))
                for f in _contents(target):
                    frel = f.relative_to(root).as_posix()
                    if frel not in _targets:
                        _targets[frel] = f"{PREFIX}/{frel}"
                        files.append(File.generated(config, _targets[frel], abs_src_path=str(f)))
            else:
                uri = f"{PREFIX}/{rel}"
                files.append(File.generated(config, uri, abs_src_path=str(target)))
            _targets[rel] = uri
    return files


def on_page_markdown(markdown: str, page: Any, config: Any, files: Files) -> str:
    root = _root(config)
    docs = Path(config["docs_dir"]).resolve()
    src = Path(page.file.abs_src_path) if page.file.abs_src_path else docs / page.file.src_uri
    page_dir = posixpath.dirname(page.file.src_uri)

    def point(match: re.Match[str]) -> str:
        target = _outside(src.parent, match.group(1), root)
        if target is None:
            return match.group(0)
        uri = _targets.get(target.relative_to(root).as_posix())
        if uri is None:
            return match.group(0)
        return f"]({posixpath.relpath(uri, page_dir or '.')}{match.group(2) or ''})"

    return LINK.sub(point, markdown)
