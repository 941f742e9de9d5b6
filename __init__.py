"""sunwind: solar-radiation-pressure and free-molecular forces and torques on a spacecraft mesh.

Subpackages, each importing only those before it:

- :mod:`sunwind.geometry`: the spacecraft model, mesh and material files, ray casting, view factors.
- :mod:`sunwind.meshes`: parametric meshes and the sample spacecraft.
- :mod:`sunwind.forces`: the force laws and solvers, attitude tables, their file formats, the CLI.
- :mod:`sunwind.validation`: closed forms, brute-force tracers and the validation runner.

The method, frames and signs are in METHOD.md; ``python -m sunwind`` runs the command line.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("sunwind")
except PackageNotFoundError:  # imported from a checkout that was never installed
    __version__ = "unknown"
