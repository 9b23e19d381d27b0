"""The floater's surface for the views: closed panels of the case's geometry at rest (global
coordinates), and the same panels placed by a 6-DOF displacement.

A cylinder is a tube with its two end caps; a semisubmersible the tubes of its columns, their
heave plates and its pontoons and braces (each tube whole, overlapping where they join: a
picture, not a BEM mesh); a mesh hull the panels of its file, mirrored over its declared
symmetry planes, scaled and moved as the case says (the whole hull, above and below the
water line). Placement uses the rotation of the floater's kinematics
(:func:`floatmoor.rotations.rotation_matrix`, R = Rz(yaw) Ry(pitch) Rx(roll)):
p = c0 + x[:3] + R (p0 - c0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.case.schema import (
    CylinderGeometry, Floater, MeshGeometry, SemisubmersibleGeometry,
)
from floatmoor.rotations import rotation_matrix

__all__ = ["BodySurface", "body_surface", "tube_surface", "N_AROUND"]

#: Panels around a circular section: the drawn circle's chord sits within
#: 1 - cos(pi / 36) = 0.4 % of the radius of the true circle.
N_AROUND = 36


@dataclass(frozen=True)
class BodySurface:
    """Panels of a rigid body at rest.

    Attributes
    ----------
    vertices
        (n, 3) global positions at rest [m].
    faces
        (m, 4) vertex indices; a triangle repeats its third vertex (capytaine's convention).
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64]

    def placed(self, displacement: ArrayLike, centre: ArrayLike) -> NDArray[np.float64]:
        """The vertices (n, 3) [m] moved by ``displacement`` (Surge, Sway, Heave [m], Roll,
        Pitch, Yaw [rad]) about the rotation centre at rest ``centre`` [m]."""
        x = np.asarray(displacement, dtype=float)
        c = np.asarray(centre, dtype=float)
        R = rotation_matrix(float(x[3]), float(x[4]), float(x[5]))
        return c + x[:3] + (self.vertices - c) @ R.T


def _join(parts: list[BodySurface]) -> BodySurface:
    offsets = np.cumsum([0] + [len(p.vertices) for p in parts[:-1]])
    return BodySurface(np.concatenate([p.vertices for p in parts]),
                       np.concatenate([p.faces + k for p, k in zip(parts, offsets)]))


def tube_surface(start: ArrayLike, end: ArrayLike, radius: float,
                 around: int = N_AROUND) -> BodySurface:
    """A closed circular tube from ``start`` to ``end`` [m] of ``radius`` [m]: ``around``
    wall quads and a fan of triangles on each end."""
    a, b = np.asarray(start, dtype=float), np.asarray(end, dtype=float)
    axis = (b - a) / np.linalg.norm(b - a)
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)
    phi = 2.0 * np.pi * np.arange(around) / around
    ring = radius * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * w)
    vertices = np.concatenate([a + ring, b + ring, [a, b]])
    i = np.arange(around)
    j = (i + 1) % around
    wall = np.column_stack([i, j, around + j, around + i])
    ca, cb = 2 * around, 2 * around + 1
    cap_a = np.column_stack([j, i, np.full(around, ca), np.full(around, ca)])
    cap_b = np.column_stack([around + i, around + j, np.full(around, cb), np.full(around, cb)])
    return BodySurface(vertices, np.concatenate([wall, cap_a, cap_b]).astype(np.int64))


def _cylinder(geometry: CylinderGeometry, reference_point) -> BodySurface:
    x, y = float(reference_point[0]), float(reference_point[1])
    return tube_surface((x, y, -geometry.draft), (x, y, geometry.height - geometry.draft),
                        geometry.radius)


def _semisubmersible(geometry: SemisubmersibleGeometry) -> BodySurface:
    parts = []
    for c in geometry.columns:
        parts.append(tube_surface((c.x, c.y, c.z_bottom), (c.x, c.y, c.z_top), 0.5 * c.diameter))
        if c.heave_plate_diameter is not None:
            parts.append(tube_surface((c.x, c.y, c.z_bottom),
                                      (c.x, c.y, c.z_bottom + c.heave_plate_height),
                                      0.5 * c.heave_plate_diameter))
    for m in geometry.members:
        parts.append(tube_surface(m.start, m.end, 0.5 * m.diameter))
    return _join(parts)


def _mirrored(surface: BodySurface, axis: int) -> BodySurface:
    """``surface`` joined with its mirror image over the plane where coordinate ``axis`` is 0
    (the mirror's faces reversed, so both keep their orientation)."""
    flip = surface.vertices.copy()
    flip[:, axis] *= -1.0
    triangle = surface.faces[:, 3] == surface.faces[:, 2]
    reversed_ = np.where(triangle[:, None], surface.faces[:, [2, 1, 0, 0]],
                         surface.faces[:, ::-1])
    return _join([surface, BodySurface(flip, reversed_)])


def _mesh(geometry: MeshGeometry) -> BodySurface:
    """The hull of a mesh file, whole (see :mod:`floatmoor.hydro.mesh_file` for the reading).

    Raises
    ------
    BemFileError
        When the file cannot be read or has changed since the case was read (SHA-256; the
        run file keeps no hash of it, so a change between the run and its views goes
        unseen).
    """
    from floatmoor.file_hash import file_sha256
    from floatmoor.hydro.mesh_file import read_mesh_file
    from floatmoor.io.bem_data import BemFileError

    path = str(geometry.path)
    try:
        digest = file_sha256(path)
    except OSError as err:
        raise BemFileError(path, "", "a readable mesh file", err.strerror or str(err)) from None
    if digest != geometry.sha256:
        raise BemFileError(path, "", "the mesh file read with the case (SHA-256 "
                           f"{geometry.sha256[:12]}...)", f"a file changed since (SHA-256 "
                           f"{digest[:12]}...)")
    mesh, _ = read_mesh_file(path, geometry.format)
    while hasattr(mesh, "half"):  # a file flagging symmetry: its stored part
        mesh = mesh.half
    surface = BodySurface(np.asarray(mesh.vertices, dtype=float) * geometry.scale,
                          np.asarray(mesh.faces, dtype=np.int64))
    for plane in geometry.symmetry:
        surface = _mirrored(surface, 1 if plane == "xz" else 0)
    return BodySurface(surface.vertices + np.asarray(geometry.position, dtype=float),
                       surface.faces)


def body_surface(floater: Floater) -> BodySurface:
    """The surface of a case's floater at rest, from its ``[floater.geometry]``.

    Raises
    ------
    BemFileError
        For a mesh hull whose file cannot be read or changed since the case was read.
    """
    geometry = floater.geometry
    if geometry is None:
        raise ValueError(f"floater {floater.name}: no [floater.geometry], no surface to draw")
    if isinstance(geometry, CylinderGeometry):
        return _cylinder(geometry, floater.reference_point)
    if isinstance(geometry, SemisubmersibleGeometry):
        return _semisubmersible(geometry)
    return _mesh(geometry)
