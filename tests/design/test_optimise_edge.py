"""An optimum on the edge of the feasible designs is found whatever the rounding of the linear algebra under SLSQP.

The supply mechanism's output swing grows with its crank until, past a crank of about 0.5416, the motion can no longer
be completed in its branch. SLSQP meets many infeasible designs on the way; the bowl they get around the best design
(mechfem.design.engine.solve) must lead it to the edge with every kernel OpenBLAS may pick on the machine at hand, not
only with the one of the machine the test was written on: each is forced in a process of its own.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

SCRIPT = """
import numpy as np, mechfem
m = mechfem.Mechanism.from_deck({deck!r}).variant(kappa=-5.25)

def swing(e):
    v, g = e.value("delta"), e.gradient("delta")
    i, k = int(np.argmax(v)), int(np.argmin(v))
    return -(v[i] - v[k]), -(g[i] - g[k])

opt = mechfem.optimize(m, {{"crank.length": (0.1, 5.0)}}, objective=swing, quantities=["delta"], steps=40)
print(opt.values["crank.length"], opt.infeasible, opt.runs)
"""


# The instruction set each forced kernel needs: a kernel the processor lacks would stop its process with SIGILL,
# which says nothing about mechfem.
NEEDS = {"Haswell": "avx2", "SkylakeX": "avx512f", "Zen": "avx2"}


def cpu_flags() -> set[str]:
    try:
        text = Path("/proc/cpuinfo").read_text()
    except OSError:
        return set()
    return {flag for line in text.splitlines() if line.startswith("flags") for flag in line.split(":", 1)[1].split()}


@pytest.mark.parametrize("kernel", ["", "Haswell", "SkylakeX", "Zen"])
def test_the_largest_swing_is_found_at_the_edge_with_every_blas_kernel(kernel: str) -> None:
    if kernel and NEEDS[kernel] not in cpu_flags():
        pytest.skip(f"this processor has no {NEEDS[kernel]}, which OpenBLAS's {kernel} kernel needs")
    env = dict(os.environ)
    if kernel:
        env["OPENBLAS_CORETYPE"] = kernel
    code = SCRIPT.format(deck=str(ROOT / "examples" / "supply" / "supply.mec"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    crank, infeasible, runs = out.stdout.split()
    assert 0.535 < float(crank) < 0.5417
    assert int(infeasible) > 0 and int(runs) > int(infeasible)
