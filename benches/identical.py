"""Checks that a change of the code leaves every result the same to the last bit: runs every example deck and
every deck under tests/ along every path a user runs one, keeps every number, and compares two such records.

    .venv/bin/python benches/identical.py record BEFORE.pkl     # with the code before the change built
    .venv/bin/python benches/identical.py record AFTER.pkl      # with the code after it built
    .venv/bin/python benches/identical.py compare BEFORE.pkl AFTER.pkl

The paths: ``mechfem.run_deck`` (with and without det), the compiled handle ``_core.Model.from_path(deck).run``
(positions only, first and second order), ``Mechanism.from_deck(deck).run`` (order 2, 1 and positions only, each
twice: built through the typed builder, then on its kept compiled model), and the command line
``mechfem run --no-media --format npz`` (its data set's every column and its print file). Of each run every
column of the core's table, the co-ordinates, buffers, time, det(D^c) and the run report are kept; a deck that
fails is kept as its error's type and words. Numbers are compared by their bytes; texts as they are, but for the
wall-clock times a print file states ("11 mechanism runs in 0.165 s"). The compare exits 1 on any difference.
A record of the shipped decks takes about two minutes and a few GB of memory (the long runs' tables).
"""

from __future__ import annotations

import pickle
import re
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent

# Wall-clock times in print files, which no two runs share.
TIMES = re.compile(r"runs? in [0-9.e+-]+ s")

RAW = ("table", "coords", "buffers", "time", "det")
TEXTS = ("positions", "report", "layout", "stop")


def raw_values(raw: Any) -> dict[str, Any]:
    """Every array of the binding's run, copied, and the reprs of its other results."""
    import numpy as np

    out: dict[str, Any] = {}
    for name in RAW:
        try:
            out[name] = np.array(getattr(raw, name), copy=True)
        except Exception as e:  # noqa: BLE001  (a run without that array: its absence is compared)
            out[name] = "no " + type(e).__name__
    for name in TEXTS:
        try:
            out[name] = repr(getattr(raw, name))
        except Exception as e:  # noqa: BLE001
            out[name] = "no " + type(e).__name__
    return out


def result_values(result: Any) -> dict[str, Any]:
    """``raw_values`` of a RunResult's run, and what the RunResult itself gives."""
    import numpy as np

    out = raw_values(result._raw)
    for name in ("coords", "det", "time"):
        try:
            out["result." + name] = np.array(getattr(result, name), copy=True)
        except Exception as e:  # noqa: BLE001
            out["result." + name] = "no " + type(e).__name__
    out["result.report"] = repr(result.report)
    return out


def command_line(deck: Path, outdir: Path) -> dict[str, Any]:
    """``mechfem run --no-media --format npz``: its exit status, its words and every file it wrote."""
    import numpy as np

    p = subprocess.run(
        [sys.executable, "-m", "mechfem", "run", str(deck), "--no-media", "--format", "npz", "-o", str(outdir), "-q"],
        capture_output=True,
        text=True,
        check=False,
    )
    out: dict[str, Any] = {"status": str(p.returncode), "stderr": p.stderr.replace(str(outdir), "OUT")}
    for f in sorted(outdir.glob("*")) if outdir.exists() else []:
        if f.suffix == ".npz":
            with np.load(f, allow_pickle=False) as z:
                out.update({f"{f.name}:{k}": np.array(z[k]) for k in z.files})
        else:
            out[f.name] = f.read_text(errors="replace").replace(str(outdir), "OUT").replace(str(ROOT), "ROOT")
    return out


def record(path: Path) -> None:
    sys.path.insert(0, str(ROOT / "python"))
    import mechfem
    from mechfem import _core

    warnings.simplefilter("ignore")
    decks = sorted(ROOT.glob("examples/**/*.mec")) + sorted(ROOT.glob("tests/**/*.mec"))
    cli = Path(tempfile.mkdtemp(prefix="mechfem-identical-"))
    runs: dict[tuple[str, str], Any] = {}
    for deck in decks:
        key = str(deck.relative_to(ROOT))
        for how in (
            "run_deck",
            "run_deck det=False",
            "model 0",
            "model 1",
            "model 2",
            "mech 2",
            "mech 1",
            "mech 0",
            "cli",
        ):
            try:
                if how == "run_deck":
                    v = result_values(mechfem.run_deck(deck))
                elif how == "run_deck det=False":
                    v = result_values(mechfem.run_deck(deck, det=False))
                elif how.startswith("model"):
                    order = int(how[-1]) or None
                    v = raw_values(_core.Model.from_path(deck).run(order=order))
                elif how.startswith("mech"):
                    mech, order = mechfem.Mechanism.from_deck(str(deck)), int(how[-1]) or None
                    v = result_values(mech.run(order=order, progress=False))
                    again = result_values(mech.run(order=order, progress=False))
                    v.update({"kept " + k: x for k, x in again.items()})
                else:
                    v = command_line(deck, cli / deck.stem)
            except Exception as e:  # noqa: BLE001  (a deck that fails is compared by its error)
                v = f"error: {type(e).__name__}: {e}"
            runs[key, how] = v
    with path.open("wb") as f:
        pickle.dump(runs, f)
    print(f"{len(decks)} decks, {len(runs)} runs, {sum(isinstance(v, str) for v in runs.values())} of them errors")


def compare(before: Path, after: Path) -> int:
    import numpy as np

    with before.open("rb") as f:
        a = pickle.load(f)
    with after.open("rb") as f:
        b = pickle.load(f)
    if a.keys() != b.keys():
        print("the records are of different decks or paths:", sorted(set(a) ^ set(b)))
        return 1
    bad = numbers = 0

    def differ(key: object, what: str, x: object, y: object) -> None:
        nonlocal bad
        bad += 1
        print("DIFFERENT", key, what, str(x)[:150], "|", str(y)[:150])

    for key, x in a.items():
        y = b[key]
        if isinstance(x, str) or isinstance(y, str):
            if not (isinstance(x, str) and isinstance(y, str) and TIMES.sub("", x) == TIMES.sub("", y)):
                differ(key, "", x, y)
            continue
        if x.keys() != y.keys():
            differ(key, "values kept", sorted(x), sorted(y))
            continue
        for what, u in x.items():
            v = y[what]
            if isinstance(u, np.ndarray) and isinstance(v, np.ndarray):
                numbers += u.size
                if u.shape != v.shape or u.dtype != v.dtype or u.tobytes() != v.tobytes():
                    differ(key, what, u.shape, v.shape)
            elif isinstance(u, str) and isinstance(v, str):
                if TIMES.sub("", u) != TIMES.sub("", v):
                    differ(key, what, u, v)
            elif type(u) is not type(v) or u != v:
                differ(key, what, u, v)
    print(f"{len(a)} runs, {numbers} numbers compared bit for bit, {bad} differences")
    return 1 if bad else 0


def main() -> None:
    if len(sys.argv) == 3 and sys.argv[1] == "record":
        record(Path(sys.argv[2]))
    elif len(sys.argv) == 4 and sys.argv[1] == "compare":
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
