"""The Markdown tables of docs/simulation-benchmarks.md from a run of ``bench_work_precision.py --json FILE``:

    python benches/work_precision_tables.py FILE

For each problem: every run (tolerance or step count, evaluations, time compiled once and per call, error), and
each solver's time and evaluations at equal errors (log-log between the runs that bracket them).
"""

from __future__ import annotations

import json
import sys
from typing import Any

from sim_solvers import interpolate

TARGETS = [1e-4, 1e-6, 1e-8, 1e-10]


def ms(seconds: float | None) -> str:
    if seconds is None:
        return ""
    value = seconds * 1e3
    return f"{value:.3g}" if value < 1000 else f"{value:,.0f}".replace(",", " ")


def count(n: float | None) -> str:
    return "" if n is None else f"{n:,.0f}".replace(",", " ")


def runs_table(rows: list[dict[str, Any]]) -> list[str]:
    out = [
        "| solver | tolerance or steps | evaluations | time | compiled per call | error |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for r in rows:
        at = f"{r['tol']:g}" if "tol" in r else f"{r['steps']} steps"
        ev = count(r["evaluations"]) + (f" ({r['jacobians']} J)" if r.get("jacobians") else "")
        once = (
            "not timed"
            if r["seconds"] is None
            else ms(r["seconds"]) + " ms" + (" (1 run)" if r.get("timed") == "once" else "")
        )
        fresh = "" if "seconds_fresh" not in r else ms(r["seconds_fresh"]) + " ms"
        err = "did not finish" if r["error"] is None else f"{r['error']:.1e}"
        note = f" ({r['note']})" if r["note"] and r["error"] is None else ""
        out.append(f"| {r['solver']} | {at} | {ev} | {once} | {fresh} | {err}{note} |")
    return out


def equal_error_table(rows: list[dict[str, Any]]) -> list[str]:
    out = [
        "| solver | " + " | ".join(f"error {e:.0e}" for e in TARGETS) + " |",
        "|---|" + "---:|" * len(TARGETS),
    ]
    for name in dict.fromkeys(r["solver"] for r in rows):
        mine = [r for r in rows if r["solver"] == name and r["error"] is not None]
        cells = []
        for target in TARGETS:
            sec = interpolate([(r["error"], r["seconds"] or 0.0) for r in mine], target)
            ev = interpolate([(r["error"], r["evaluations"] or 0.0) for r in mine], target)
            cells.append("" if sec is None else f"{ms(sec)} ms" + ("" if ev is None else f" / {count(ev)}"))
        out.append(f"| {name} | " + " | ".join(cells) + " |")
    return out


def main() -> None:
    data = json.loads(open(sys.argv[1]).read())
    print(f"machine: {data['machine']}\n")
    for problem in dict.fromkeys(r["problem"] for r in data["rows"]):
        rows = [r for r in data["rows"] if r["problem"] == problem]
        print(f"### {problem}\n")
        print("\n".join(runs_table(rows)))
        print()
        print("\n".join(equal_error_table(rows)))
        print()


if __name__ == "__main__":
    main()
