"""An optimum on the edge of the feasible designs is found whatever the rounding of the linear algebra under SLSQP.

The supply mechanism's output swing grows with its crank until, past a crank of about 0.5416, the motion can no longer
be completed in its branch. SLSQP meets many infeasible designs on the way; the bowl they get around the best design
(mechfem.design.solve) must lead it to the edge with every kernel OpenBLAS may pick on the machine at hand, not only
with the one of the machine the test was written on: each is forced in a process of its own.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

SCRIPT = """
import numpy as np, mechfem
m = mechfem.Mechanism.from_deck({deck!r}).variant(row5=-5.25)

def swing(e):
    v, g = e.value("out1"), e.gradient("out1")
    i, k = int(np.argmax(v)), int(np.argmin(v))
    return -(v[i] - v[k]), -(g[i] - g[k])

opt = mechfem.optimize(m, {{"E1.length": (0.1, 5.0)}}, objective=swing, quantities=["out1"], steps=40)
print(opt.values["E1.length"], opt.infeasible, opt.runs)
"""


@pytest.mark.parametrize("kernel", ["", "Haswell", "SkylakeX", "Zen"])
def test_the_largest_swing_is_found_at_the_edge_with_every_blas_kernel(kernel: str) -> None:
    env = dict(os.environ)
    if kernel:
        env["OPENBLAS_CORETYPE"] = kernel
    code = SCRIPT.format(deck=str(ROOT / "examples" / "supply" / "supply.mec"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    crank, infeasible, runs = out.stdout.split()
    assert 0.535 < float(crank) < 0.5417
    assert int(infeasible) > 0 and int(runs) > int(infeasible)
