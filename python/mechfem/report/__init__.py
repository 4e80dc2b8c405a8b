"""The interactive HTML report, its charts, its DYN and KIN OPT sections, and its page (``template.html``,
``assets/``, the vendored uPlot in ``vendor/``). Imports the packages up to ``viz``."""
