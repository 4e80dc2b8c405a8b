"""The benches' own environment, ``.venv-bench``: the peers a bench compares mechfem with are installed there,
never into mechfem's ``.venv``, and the bench re-runs itself with that interpreter (mechfem is imported from the
source tree, its compiled module built by ``make install``)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
VENV = ROOT / ".venv-bench"
# What mechfem itself needs at import and to optimise (see pyproject.toml).
MECHFEM_DEPS = ["numpy", "scipy", "matplotlib", "pillow"]


def venv_python() -> Path:
    return VENV / ("Scripts/python.exe" if os.name == "nt" else "bin/python")


def ensure_venv(peers: list[str], stamp_name: str) -> None:
    """Installs ``peers`` into .venv-bench (once; ``stamp_name`` records what this bench installed), then re-runs
    the calling script with that interpreter. Returns only when already running there."""
    python = venv_python()
    if Path(sys.prefix).resolve() == VENV.resolve():
        return
    stamp = VENV / stamp_name
    wanted = "\n".join(peers + MECHFEM_DEPS)
    if not python.exists() or not stamp.exists() or stamp.read_text() != wanted:
        print(f"installing into {VENV.name}: {' '.join(peers)}", flush=True)
        if not python.exists():
            subprocess.run([sys.executable, "-m", "venv", str(VENV)], check=True)
        pip = [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check"]
        subprocess.run(pip + peers + MECHFEM_DEPS, check=True)
        stamp.write_text(wanted)
    os.execv(str(python), [str(python), *sys.argv])
