"""``mechfem studio [DECK] [--folder DIR] [--port N] [--no-browser]``: serves the studio on 127.0.0.1 and opens it in
the browser."""

from __future__ import annotations

import argparse
import sys
import webbrowser
from pathlib import Path

from mechfem.studio_app import INSTALL, missing


def add_studio(commands: argparse._SubParsersAction[argparse.ArgumentParser]) -> None:
    """The ``studio`` command of the command line."""
    studio = commands.add_parser(
        "studio", help="edit a mechanism in the browser and see it move, live (needs mechfem[studio])"
    )
    studio.add_argument("deck", type=Path, nargs="?", metavar="DECK", help="the deck to open (default: none yet)")
    studio.add_argument(
        "--folder",
        type=Path,
        metavar="DIR",
        help="offer the decks of DIR and the folders below it (default: the deck's folder, else the current one)",
    )
    studio.add_argument("--port", type=port_number, default=0, metavar="N", help="the port (default: a free one)")
    studio.add_argument("--no-browser", action="store_true", help="print the address only, open no browser")
    studio.set_defaults(func=cmd_studio)


def port_number(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"a port is a whole number, not {text!r}") from None
    if not 1 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"a port is between 1 and 65535, not {value}")
    return value


def cmd_studio(args: argparse.Namespace) -> int:
    absent = missing()
    if absent:
        print(
            f"error: mechfem studio needs {', '.join(absent)}, which mechfem does not install by itself: {INSTALL}",
            file=sys.stderr,
        )
        return 1
    from mechfem.model.mechanism import Mechanism
    from mechfem.studio_app.server import serve
    from mechfem.studio_app.session import Session

    session = None
    if args.deck is not None:
        session = Session(Mechanism.from_deck(args.deck), args.deck)
    folder = args.folder or (args.deck.parent if args.deck is not None else Path.cwd())
    if not folder.is_dir():
        print(f"error: --folder {folder}: no such folder", file=sys.stderr)
        return 1

    def started(url: str) -> None:
        print(f"mechfem studio: {url}", flush=True)
        print("(this address, with its token, is the only way in; Ctrl-C stops the studio)", flush=True)
        if not args.no_browser:
            webbrowser.open(url)

    try:
        serve(session, args.port, on_start=started, folder=folder)
    except OSError as e:
        print(f"error: cannot serve on 127.0.0.1:{args.port}: {e.strerror or e}", file=sys.stderr)
        return 1
    return 0


__all__ = ["add_studio", "cmd_studio"]
