"""The ``sunwind`` command line."""

from sunwind.forces.cli.app import main

__all__ = ["main"]
