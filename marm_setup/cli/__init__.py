"""The command line: the Typer app (`app`), shared options (`common`), one module per command."""
