"""A mechanism with its names: the element catalogue, units, parts, the builder methods, storage requests, motions,
stop conditions, masses and loads, the compiled model's echo, and :class:`Mechanism` itself. Imports ``_util``; the
run result only for type checking (``Mechanism.run`` imports the run when called). Re-exports the names a script
imports from ``mechfem.model`` (docs/python-api.md)."""

from mechfem.model.mechanism import By, Driven, Dynamic, Keep, Mechanism, Motion, Output, Storage, Table, To

__all__ = ["By", "Driven", "Dynamic", "Keep", "Mechanism", "Motion", "Output", "Storage", "Table", "To"]
