"""The TOLERANCE BANDS section of a deck run's print file: for every BUFTOL, the largest band over the motion,
where it occurs (the inputs there, in the deck's names and units) and every toleranced dimension's share of it
at that position, largest first (:mod:`mechfem.studies.bands`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from mechfem.studies.bands import ToleranceBands, bands_of

if TYPE_CHECKING:
    from mechfem.results.result import RunResult


def _with(value: float, unit: str) -> str:
    return f"{value:.6g} {unit}".rstrip() if unit and unit != "-" else f"{value:.6g}"


def band_lines(bands: ToleranceBands) -> list[str]:
    """The section's lines for ``bands``."""
    out = ["TOLERANCE BANDS", "  first order, from the exact design sensitivities; tolerances (value +- t):"]
    width = max(len(n) for n in bands.tolerances)
    for name, t in bands.tolerances.items():
        out.append(f"    {name:<{width}}  +-{_with(t, bands.units.get(name, ''))}")
    for b in bands.bands.values():
        k = b.at
        where = ", ".join(
            f"{n} = {_with(float(bands.inputs[k, j]), bands.input_units[j])}" for j, n in enumerate(bands.input_names)
        )
        into = "" if b.buffer is None else f" (BUFTOL {b.source} {b.buffer}: worst case {b.buffer}, RSS {b.buffer + 1})"
        out += [
            "",
            f"  {b.name}{into}",
            f"    largest band: +-{_with(float(b.worst[k]), b.unit)} worst case, +-{_with(float(b.rss[k]), b.unit)} "
            f"RSS, at position {k + 1} ({where}), where {b.name} = {_with(float(b.value[k]), b.unit)}",
            "    shares there, largest first:",
        ]
        shares = b.shares(k)
        w = max(width, len("dimension"))
        out.append(f"      {'dimension':<{w}}  {'d/dp':>14}  {'|d/dp| t':>14}  {'of worst':>9}  {'of RSS^2':>9}")
        for s in shares:
            out.append(
                f"      {s.dimension:<{w}}  {s.sensitivity:14.6g}  {s.deviation:14.6g}  {100 * s.of_worst:8.2f}%  "
                f"{100 * s.of_variance:8.2f}%"
            )
    out.append("")
    return out


def tolerance_lines(result: RunResult) -> list[str]:
    """The section for a deck run with a TOLERANCE block; nothing for any other run. The bands take one more run
    of the motion; when it fails, the section says why and the rest of the print file stands."""
    from mechfem.errors import MechfemError

    try:
        bands = bands_of(result)
    except MechfemError as e:
        return ["TOLERANCE BANDS", "  not computed: the run with the design sensitivities failed:", f"  {e}", ""]
    return [] if bands is None or not bands.bands else band_lines(bands)


__all__ = ["band_lines", "tolerance_lines"]
