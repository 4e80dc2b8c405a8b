"""Reading and writing decks for a Mechanism: numbering, the NAMES and UNITS of a deck, the deck writer and reader,
errors in the model's words. Imports ``_util``, ``model`` and ``results``."""
