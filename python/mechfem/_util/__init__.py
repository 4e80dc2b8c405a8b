"""Private helpers without a model: atomic file writes, optional imports (pandas, ezdxf, pyarrow), the progress bar
and console, the memory limit, argument checks and name suggestions. Imports nothing of mechfem but
``mechfem.errors`` and the compiled module."""
