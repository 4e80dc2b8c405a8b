"""The ``mechfem`` command (``command.py``). Imports every package below it; ``mechfem.cli.main`` is the entry point
of the installed command and imports the command when called."""


def main(argv: list[str] | None = None) -> int:
    """Runs the command line; returns the exit status (:func:`mechfem.cli.command.main`)."""
    from mechfem.cli.command import main as command

    return command(argv)
