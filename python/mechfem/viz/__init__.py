"""Pictures of a run: the mechanism's drawing, plots, animation, figures, DXF/SVG export and notebook views. Imports
``_util``, ``model`` and ``results``."""
