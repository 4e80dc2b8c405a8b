"""Makes the pictures of docs/pictures.md: the interactive report of one example deck of each mode (KIN ANA, KIN
OPT, DYN ANA, DYN SIM), written by ``mechfem report`` (for the KIN OPT deck by ``mechfem run --report``, which
optimises first, so that its report is of the optimisation) and photographed in headless Chromium.

    .venv/bin/python scripts/report_screenshots.py [--out docs/images] [--mode "DYN SIM" ...]

Chromium is Debian's ``chromium`` (``make browser`` installs it), driven from the command line as the report's
tests drive it: ``--screenshot`` of the page opened at a chosen position (``<stem>.html#position=N``), in a window
tall enough for the cards the picture is about. Every deck runs in a temporary folder; only the PNGs are written
to ``--out``. Exit status 0 when every picture was made, 1 otherwise (the reason on standard error).
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent


@dataclass(frozen=True)
class Shot:
    """One picture: the deck whose report it shows, the window's size and where the slider stands."""

    mode: str
    deck: str
    image: str
    window: tuple[int, int]
    position: str | None = None
    """A position number, ``largest-pin-force`` (where the DYN ANA report's pin-force card says the largest
    occurs) or None (the first position)."""
    cards: tuple[str, ...] = ()
    """The starts of the titles of the cards to show at the top of the column of charts, beside the mechanism."""


SHOTS = [
    Shot("KIN ANA", "examples/supply/supply.mec", "report_kin_ana.png", (1400, 1000), "20"),
    Shot("KIN OPT", "examples/supply/supply_opt.mec", "report_kin_opt.png", (1400, 1000)),
    Shot(
        "DYN ANA",
        "examples/supply/supply_forces.mec",
        "report_dyn_ana.png",
        (1400, 1500),
        "largest-pin-force",
        ("pin", "shaking"),
    ),
    Shot(
        "DYN SIM",
        "examples/supply/supply_sim.mec",
        "report_dyn_sim.png",
        (1400, 1500),
        "400",
        ("drive or motor", "power", "energy balance"),
    ),
]

# Headless, without a sandbox (root in a container) and without the browser's own traffic; the report itself
# loads nothing (its Content-Security-Policy forbids it to).
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--host-resolver-rules=MAP * ~NOTFOUND",
    "--hide-scrollbars",
]


class ShotError(Exception):
    """A picture could not be made: what failed, in words."""


def find_chromium() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        path = shutil.which(name)
        if path:
            return path
    raise ShotError("no Chromium on the PATH: `make browser` installs Debian's chromium (as root)")


def write_report(deck: Path, outdir: Path, optimise: bool) -> Path:
    """Writes the report of ``deck`` into ``outdir``: ``mechfem report`` (the report alone), or for a KIN OPT deck
    (``optimise``) ``mechfem run --report``, which optimises first; returns the report's path."""
    # Relative to the repository, so that the page names the deck as the docs do.
    name = str(deck.relative_to(ROOT))
    command = ["run", name, "-o", str(outdir), "--report"] if optimise else ["report", name, "-o", str(outdir)]
    proc = subprocess.run(
        [sys.executable, "-m", "mechfem.cli.command", *command],
        cwd=ROOT,
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        check=False,
    )
    page = outdir / f"{deck.stem}.html"
    if not page.is_file():
        raise ShotError(f"{deck}: `mechfem run --report` wrote no report (exit {proc.returncode}):\n{proc.stderr}")
    return page


def report_data(page: Path) -> dict[str, Any]:
    """The data the report's page shows (its JSON)."""
    found = re.search(r'<script type="application/json" id="data">(.*?)</script>', page.read_text(), re.S)
    if not found:
        raise ShotError(f"{page}: no data in the report")
    data: dict[str, Any] = json.loads(found.group(1))
    return data


def address(page: Path, shot: Shot) -> str:
    """The page's URL with the position (``#position=N``) and the card (``&card=K``) the picture shows."""
    data = report_data(page)
    position = shot.position
    if position == "largest-pin-force":
        jumps = [c["jump"]["frame"] for c in data["cards"] if c.get("jump")]
        if not jumps:
            raise ShotError(f"{page}: the report has no pin-force card (does the deck record BUFPIN?)")
        position = str(data["frames"][jumps[0]] + 1)
    shown = [k for start in shot.cards for k, c in enumerate(data["cards"]) if c["title"].startswith(start)]
    if len(shown) < len(shot.cards):
        raise ShotError(f"{page}: the report lacks a card titled {' or '.join(shot.cards)}...")
    hash_ = f"#position={position or 1}" + (f"&cards={','.join(map(str, shown))}" if shown else "")
    return page.as_uri() + (hash_ if position or shown else "")


def screenshot(chromium: str, page: Path, shot: Shot, image: Path, profile: Path) -> None:
    url = address(page, shot)
    proc = subprocess.run(
        [
            chromium,
            *FLAGS,
            f"--user-data-dir={profile}",
            f"--window-size={shot.window[0]},{shot.window[1]}",
            "--virtual-time-budget=4000",
            f"--screenshot={image}",
            url,
        ],
        capture_output=True,
        text=True,
        timeout=300,
        stdin=subprocess.DEVNULL,
        check=False,
    )
    if proc.returncode != 0 or not image.is_file():
        raise ShotError(f"{page}: Chromium made no screenshot (exit {proc.returncode}):\n{proc.stderr[-2000:]}")


def make(out: Path, modes: list[str] | None = None) -> list[Path]:
    """Makes the pictures of ``modes`` (default: all four) in ``out``; returns their paths."""
    chromium = find_chromium()
    out.mkdir(parents=True, exist_ok=True)
    made = []
    with tempfile.TemporaryDirectory(prefix="mechfem-shots-") as tmp:
        for k, shot in enumerate(s for s in SHOTS if modes is None or s.mode in modes):
            run = Path(tmp) / f"run{k}"
            page = write_report(ROOT / shot.deck, run, shot.mode == "KIN OPT")
            image = out / shot.image
            screenshot(chromium, page, shot, image, Path(tmp) / f"profile{k}")
            made.append(image)
    return made


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "images", help="folder of the PNGs")
    parser.add_argument(
        "--mode", action="append", choices=[s.mode for s in SHOTS], help="only this mode's picture (repeatable)"
    )
    args = parser.parse_args(argv)
    try:
        for path in make(args.out, args.mode):
            print(f"wrote {path}")
    except (ShotError, subprocess.TimeoutExpired) as e:
        print(f"report_screenshots: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
