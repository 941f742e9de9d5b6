"""``python -m sunwind``: the ``sunwind`` command line."""

from sunwind.forces.cli import main

main()
