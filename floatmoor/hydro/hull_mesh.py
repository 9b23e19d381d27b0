"""The hull mesh every geometry kind gives: capytaine meshes of the hull and lid, and how they
were built.

The parametric kinds (:mod:`floatmoor.hydro.geometry`) and mesh files
(:mod:`floatmoor.hydro.mesh_file`) both build one, so it lives below both.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

__all__ = ["HullMesh"]


@dataclass
class HullMesh:
    """A hull mesh, its lid and how they were built.

    Attributes
    ----------
    hull
        capytaine mesh of the wetted hull (possibly symmetric).
    lid
        capytaine mesh of the lid, or None.
    full_hull
        the same hull without symmetry (for hydrostatics and checks).
    symmetry
        ``"none"``, ``"rotation-n"``, ``"rotation-n+mirror-xOz"``, ``"mirror-xOz"``,
        ``"mirror-yOz"`` or ``"mirror-xOz+mirror-yOz"``.
    source
        For a hull read from a file, what was read
        (:class:`floatmoor.hydro.mesh_file.MeshFileInfo`); None for the parametric kinds.
    """

    hull: object
    lid: object | None
    full_hull: object
    symmetry: str
    source: Any = None

    @property
    def hull_panels(self) -> int:
        """Number of hull panels (whole body)."""
        return int(self.full_hull.nb_faces)

    @property
    def lid_panels(self) -> int:
        """Number of lid panels (whole body)."""
        return 0 if self.lid is None else int(self.lid.nb_faces)
