"""What a run gives: the run result (:class:`RunResult` over the core's named columns), its tables, the run report
and its words, inverse dynamics, the designer's outputs and the labels (names and units) of every column. Imports
``_util`` and ``model``."""
