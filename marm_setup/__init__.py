"""marm-setup: a headless MoveIt Setup Assistant."""

__version__ = "0.1.0"
