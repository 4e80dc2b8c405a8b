"""Running: the core model built through the typed builder, compiled models kept per topology, the named result of a
run. Imports ``_util``, ``model``, ``results`` and ``deck``."""
