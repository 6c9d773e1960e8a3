"""Subcommands of the ``shaketable`` command line, one module each."""
