"""The data set in a binary format, for runs too big to read back from text comfortably.

``<stem>.npz`` (numpy) holds one array per SAVEDATA buffer, named by the buffer's header cell in the CSV
(``101 dANGB(8)/dinput1``), and the array ``position`` (1, 2, ...). ``<stem>.parquet`` (Apache Parquet,
needs the optional dependency pyarrow: ``pip install 'mechfem[parquet]'``) holds the same as columns, ``position``
first. Both store the doubles as computed, so each column equals the CSV's to the last bit, and both are
written under a temporary name and renamed when complete, like every output.
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

import numpy as np
import numpy.typing as npt

from mechfem._util import optional
from mechfem._util.atomic import atomic_binary
from mechfem.errors import MechfemError
from mechfem.results.labels import buffer_labels
from mechfem.results.result import RunResult

#: The formats of the data set, the default first.
FORMATS = ("csv", "npz", "parquet")

#: The name of the column (array) of position numbers.
POSITION = "position"


class MissingDependency(MechfemError):
    """An output asked for needs an optional dependency that is not installed."""


def suffix(fmt: str) -> str:
    """The file suffix of the data set in format ``fmt``."""
    if fmt not in FORMATS:
        raise ValueError(f"unknown data set format {fmt!r}: use one of {', '.join(FORMATS)}")
    return f".{fmt}"


def columns(result: RunResult) -> dict[str, npt.NDArray[np.float64]]:
    """The SAVEDATA buffers by their header cell in the CSV, in deck order."""
    labels = buffer_labels(result)
    return {
        labels[n].header(): np.ascontiguousarray(result.buffers[n], dtype=np.float64) for n in result.storage.savedata
    }


def positions(result: RunResult) -> npt.NDArray[np.int64]:
    """The position numbers 1 to ``result.positions``."""
    return np.arange(1, result.positions + 1, dtype=np.int64)


def write_npz(result: RunResult, path: Path) -> Path:
    """The data set as ``.npz``: the array ``position`` and one array per SAVEDATA buffer (uncompressed: doubles
    hardly compress, and a big run's file is then written as fast as the disk takes it)."""
    arrays = {POSITION: positions(result), **columns(result)}
    with atomic_binary(path) as f:
        # mypy matches a **dict against every keyword of savez, its allow_pickle: bool among them, though the
        # arrays go to **kwds.
        np.savez(f, **arrays)  # type: ignore[arg-type]
    return path


def pyarrow() -> ModuleType:
    """The pyarrow module, or a :class:`MissingDependency` saying how to install it."""
    missing = (
        "the Parquet data set needs pyarrow, which is not installed: install it with "
        "`pip install 'mechfem[parquet]'`, or write the data set as csv or npz (--format)"
    )
    optional.module("pyarrow.parquet", missing, MissingDependency)  # the writer is a submodule
    return optional.module("pyarrow", missing, MissingDependency)


def write_parquet(result: RunResult, path: Path) -> Path:
    """The data set as ``.parquet``: the column ``position``, then one column of doubles per SAVEDATA buffer."""
    pa = pyarrow()
    data = {POSITION: positions(result), **columns(result)}
    # NaN stays NaN (not a missing value): pa.array takes numpy's doubles as they are.
    table = pa.table({name: pa.array(values) for name, values in data.items()})
    with atomic_binary(path) as f:
        pa.parquet.write_table(table, f)
    return path


def write_binary(result: RunResult, path: Path, fmt: str) -> Path:
    """The data set in the binary format ``fmt`` (npz or parquet)."""
    if fmt == "npz":
        return write_npz(result, path)
    if fmt == "parquet":
        return write_parquet(result, path)
    raise ValueError(f"not a binary data set format: {fmt!r}")
