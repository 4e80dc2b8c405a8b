"""Design sensitivities and optimisation: the engine, its stopping rules, multi-start, free timing, frame angle,
full rotation, dynamic design, the optimum and its view, the synthesis statements and a KIN OPT deck's optimisation.
Imports the packages up to ``studies``."""
