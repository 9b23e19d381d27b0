"""Parametric panel meshes of the floater geometries (capytaine 3 meshes).

Only the wetted hull (z <= 0) is meshed; normals point into the fluid.

* Cylinder: a profile (bottom disk, side) revolved ``n`` times about z, kept as a capytaine
  :class:`~capytaine.RotationSymmetricMesh` (cost 1/n of the unsymmetric problem).
* Semisubmersible: columns (with optional heave plates) and tubular members (pontoons,
  braces). Members end exactly on the surface they join: each generator line of a tube is cut
  where it leaves the union of the other solids (bisection), and at the still water line. The
  panels of a column or member whose centre lies inside another solid (the member's footprint)
  are removed. When the geometry is invariant under an n-fold rotation about z and the
  mirror y -> -y, the mesh is rebuilt from one half-sector (0 <= angle <= pi/n) as a
  ``RotationSymmetricMesh(ReflectionSymmetricMesh(half, "xOz"), n)``; all panel edges are laid
  on the sector planes, so the half-sector is an exact subset of the full mesh (checked).

Drift meshes (``waterline_panel_size``): the walls reaching the still water line (columns,
the cylinder's side, members crossing it, along their axis) are graded, panel height
``waterline_panel_size`` at z = 0 growing by at most :data:`GRADING_RATIO` per row to
``panel_size`` (:func:`graded_levels`; docs/theory/hydrodynamics.md#mean-wave-drift): the mean
drift's waterline and velocity terms and the Kochin functions' e^{kz} are resolved where the
wave's pressure varies fastest, without refining the whole hull.

Lids (interior waterplane panels at ``z = -lid_depth`` against irregular frequencies) follow
the same symmetry. A ``mesh`` geometry meshes nothing: its file is read, placed, clipped and
given a lid by :mod:`floatmoor.hydro.mesh_file`, into the same :class:`HullMesh`
(:mod:`floatmoor.hydro.hull_mesh`). :func:`geometry_properties` gives the analytic volume,
waterplane area and centre of buoyancy of the geometry for the checks.

Size: the parametric hulls' meshing (cylinder, semisubmersible with its members and symmetry
detection, the drift's grading) and their analytic properties, one family of helpers.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import (
    Column, CylinderGeometry, FloaterGeometry, Member, MeshGeometry, SemisubmersibleGeometry,
)
from floatmoor.hydro.hull_mesh import HullMesh

__all__ = [
    "HullMesh", "build_mesh", "cylinder_mesh", "semisubmersible_mesh", "hemisphere_mesh",
    "geometry_properties", "GeometryProperties", "mesh_hash", "SYMMETRY_TOLERANCE",
    "GRADING_RATIO", "graded_levels",
]

#: Relative tolerance on total panel area when a symmetric mesh is compared with the full mesh
#: it replaces: the geometry is symmetric to GEOMETRY_SYMMETRY_TOLERANCE, so the areas agree
#: to ~1e-7; a missing or duplicated sector panel changes the area by more than 1e-5.
SYMMETRY_TOLERANCE = 1e-6
#: Distance within which two columns or members count as images of each other under a
#: symmetry [m]: case coordinates are written to 1e-6 m.
GEOMETRY_SYMMETRY_TOLERANCE = 1e-5
#: Bisection steps for the end of a member's generator on another solid: 2^-60 of the search
#: interval, i.e. exact to round-off.
_BISECTION_STEPS = 60
#: Largest ratio of adjacent panel heights in a graded wall (:func:`graded_levels`): 1.25
#: keeps neighbouring panels' source strengths and the surface gradient's least-squares
#: stencils (floatmoor.hydro.drift.surface_gradient) close to the uniform mesh's.
GRADING_RATIO = 1.25


@dataclass(frozen=True)
class GeometryProperties:
    """Analytic properties of the submerged geometry (z <= 0)."""

    volume: float  #: [m^3]
    waterplane_area: float  #: [m^2]
    centre_of_buoyancy: tuple[float, float, float]  #: [m]
    waterplane_inertia: tuple[float, float]  #: integral of y^2 and x^2 over the waterplane [m^4]


# -- helpers ----------------------------------------------------------------------------------

class _Builder:
    """Collects vertices and faces (lists of 3 or 4 vertex indices)."""

    def __init__(self) -> None:
        self.vertices: list[NDArray[np.float64]] = []
        self.faces: list[list[int]] = []
        self.owner: list[int] = []

    def add_grid(self, points: NDArray[np.float64], owner: int, *, closed: bool) -> None:
        """Quads over a (m, n, 3) grid of points; ``closed`` joins the last column to the
        first. Faces collapsing to triangles (a repeated point) are written as triangles."""
        m, n = points.shape[:2]
        base = len(self.vertices)
        self.vertices.extend(points.reshape(-1, 3))
        ncol = n if closed else n - 1
        for i in range(m - 1):
            for j in range(ncol):
                jj = (j + 1) % n
                quad = [base + i * n + j, base + (i + 1) * n + j, base + (i + 1) * n + jj,
                        base + i * n + jj]
                pts = [self.vertices[k] for k in quad]
                keep = [quad[k] for k in range(4)
                        if np.linalg.norm(pts[k] - pts[(k + 1) % 4]) > 1e-12]
                if len(keep) >= 3:
                    self.faces.append(keep)
                    self.owner.append(owner)

    def arrays(self) -> tuple[NDArray[np.float64], list[list[int]], NDArray[np.int64]]:
        return np.array(self.vertices), self.faces, np.array(self.owner)


def _mesh(vertices: NDArray[np.float64], faces: list[list[int]], name: str):
    import capytaine as cpt

    # no auto_clean: the builder already drops collapsed panels, and capytaine's per-face
    # cleaning costs seconds on a semisubmersible; shared edges need no merged vertices in BEM
    return cpt.Mesh(vertices=vertices, faces=faces, name=name, auto_check=False,
                    auto_clean=False)


def _disk(builder: _Builder, centre: tuple[float, float], z: float, r_in: float, r_out: float,
          angles: NDArray[np.float64], size: float, owner: int, *, down: bool) -> None:
    """Annulus (or disk when r_in = 0) at height z; normal down (bottom) or up (top)."""
    nr = max(1, math.ceil((r_out - r_in) / size))
    radii = np.linspace(r_in, r_out, nr + 1)
    if down:  # rows outward x columns counter-clockwise gives an upward normal
        radii = radii[::-1]
    pts = np.empty((len(radii), len(angles), 3))
    pts[..., 0] = centre[0] + radii[:, None] * np.cos(angles)[None, :]
    pts[..., 1] = centre[1] + radii[:, None] * np.sin(angles)[None, :]
    pts[..., 2] = z
    builder.add_grid(pts, owner, closed=True)


def graded_levels(z_lo: float, z_hi: float, size: float, top_size: float | None = None
                  ) -> NDArray[np.float64]:
    """Increasing z levels from ``z_lo`` to ``z_hi``: uniform at about ``size``, or (with
    ``top_size`` < ``size``) rows of height ``top_size`` at ``z_hi`` growing by
    :data:`GRADING_RATIO` per row until they reach ``size``, uniform below (the nearest
    whole number of rows: heights within a factor 1.5 of ``size``)."""
    length = z_hi - z_lo
    if top_size is None or top_size >= size:
        return np.linspace(z_lo, z_hi, max(1, math.ceil(length / size)) + 1)
    heights: list[float] = []
    h = top_size
    while h < size and sum(heights) + h < length:
        heights.append(h)
        h *= GRADING_RATIO
    rest = length - sum(heights)
    if heights and rest < heights[-1]:  # a thin remainder: stretch the graded rows to fill
        heights = [v * length / sum(heights) for v in heights]
    else:
        n_rest = max(1, round(rest / size))
        heights += [rest / n_rest] * n_rest
    return z_hi - np.concatenate([[0.0], np.cumsum(heights)])[::-1]


def _wall(builder: _Builder, centre: tuple[float, float], radius: float, z_lo: float,
          z_hi: float, angles: NDArray[np.float64], size: float, owner: int,
          top_size: float | None = None) -> None:
    """Vertical cylindrical wall, normal outward (graded towards a top at the still water
    line by ``top_size``: :func:`graded_levels`)."""
    zs = graded_levels(z_lo, z_hi, size, top_size if z_hi >= 0.0 else None)
    zs[0], zs[-1] = z_lo, z_hi
    pts = np.empty((len(zs), len(angles), 3))
    pts[..., 0] = centre[0] + radius * np.cos(angles)[None, :]
    pts[..., 1] = centre[1] + radius * np.sin(angles)[None, :]
    pts[..., 2] = zs[:, None]
    # rows go up, columns go counter-clockwise: (up) x (ccw tangent) points inward; reverse.
    builder.add_grid(pts[:, ::-1], owner, closed=True)


#: Fewest panels around a column: a 36-gon has 0.5 % less area than its circle, a 60-gon 0.18 %.
MIN_COLUMN_PANELS = 36


def _angular_count(radius: float, size: float, multiple: int, minimum: int = 4) -> int:
    n = max(multiple, minimum, math.ceil(2.0 * math.pi * radius / size))
    return int(multiple * math.ceil(n / multiple))


# -- cylinder ---------------------------------------------------------------------------------

def cylinder_mesh(geometry: CylinderGeometry, *, panel_size: float, centre=(0.0, 0.0),
                  lid_depth: float | None = None, symmetry: bool = True,
                  radial_panels: int | None = None,
                  waterline_panel_size: float | None = None) -> HullMesh:
    """Mesh of the wetted part of a vertical cylinder.

    Parameters
    ----------
    geometry
        Diameter and draft.
    panel_size
        Target panel edge [m].
    centre
        (x, y) of the axis [m].
    lid_depth
        Depth of the lid below the still water line [m], or None for no lid.
    symmetry
        Keep the rotation symmetry (a capytaine ``RotationSymmetricMesh``).
    radial_panels
        Panels across the bottom radius (default from ``panel_size``).
    waterline_panel_size
        Side panels' height at the still water line, graded to ``panel_size`` below
        (:func:`graded_levels`); None: uniform.
    """
    import capytaine as cpt

    radius, draft = geometry.radius, geometry.draft
    n_theta = _angular_count(radius, panel_size, 4)
    nr = radial_panels or max(1, math.ceil(radius / panel_size))
    levels = graded_levels(-draft, 0.0, panel_size, waterline_panel_size)
    levels[0], levels[-1] = -draft, 0.0
    profile = [(r, 0.0, -draft) for r in np.linspace(0.0, radius, nr + 1)]
    profile += [(radius, 0.0, z) for z in levels[1:]]
    hull = cpt.RotationSymmetricMesh.from_profile_points(np.array(profile), n=n_theta,
                                                        name="hull")
    lid = None
    if lid_depth is not None:
        lid_profile = np.array([(r, 0.0, -lid_depth) for r in np.linspace(0.0, radius, nr + 1)])
        lid = cpt.RotationSymmetricMesh.from_profile_points(lid_profile, n=n_theta, name="lid")
    shift = (centre[0], centre[1], 0.0)
    if centre != (0.0, 0.0):
        hull = hull.translated(shift)
        lid = lid.translated(shift) if lid is not None else None
    full = hull.merged()
    if not symmetry or centre != (0.0, 0.0):
        return HullMesh(full, lid.merged() if lid is not None else None, full, "none")
    return HullMesh(hull, lid, full, f"rotation-{n_theta}")


def hemisphere_mesh(radius: float, *, n_theta: int, n_phi: int) -> HullMesh:
    """A floating hemisphere (centre at the still water line), rotation-symmetric, no lid."""
    import capytaine as cpt

    phi = np.linspace(0.0, 0.5 * math.pi, n_phi + 1)
    profile = np.array([(radius * math.sin(p), 0.0, -radius * math.cos(p)) for p in phi])
    hull = cpt.RotationSymmetricMesh.from_profile_points(profile, n=n_theta, name="hemisphere")
    return HullMesh(hull, None, hull.merged(), f"rotation-{n_theta}")


# -- semisubmersible --------------------------------------------------------------------------

def _inside_column(points: NDArray[np.float64], column: Column) -> NDArray[np.bool_]:
    """Strictly inside the solid of ``column`` (upper part and heave plate)."""
    dx = points[..., 0] - column.x
    dy = points[..., 1] - column.y
    r2 = dx * dx + dy * dy
    z = points[..., 2]
    plate_top = column.z_bottom + (column.heave_plate_height if column.heave_plate_diameter
                                   else 0.0)
    upper = (r2 < (0.5 * column.diameter) ** 2) & (z > column.z_bottom) & (z < column.z_top)
    if column.heave_plate_diameter:
        plate = ((r2 < (0.5 * column.heave_plate_diameter) ** 2) & (z > column.z_bottom)
                 & (z < plate_top))
        return upper | plate
    return upper


def _inside_member(points: NDArray[np.float64], member: Member) -> NDArray[np.bool_]:
    a = np.asarray(member.start, dtype=float)
    d = np.asarray(member.end, dtype=float) - a
    length = float(np.linalg.norm(d))
    d = d / length
    rel = points - a
    s = rel @ d
    perp = rel - s[..., None] * d
    return ((np.einsum("...i,...i->...", perp, perp) < (0.5 * member.diameter) ** 2)
            & (s > 0.0) & (s < length))


def _member_frame(member: Member) -> tuple[NDArray, NDArray, NDArray, float]:
    a = np.asarray(member.start, dtype=float)
    d = np.asarray(member.end, dtype=float) - a
    length = float(np.linalg.norm(d))
    d /= length
    ez = np.array([0.0, 0.0, 1.0])
    e_a = ez - (ez @ d) * d
    if np.linalg.norm(e_a) < 1e-9:  # vertical member
        e_a = np.array([1.0, 0.0, 0.0]) - d[0] * d
    e_a /= np.linalg.norm(e_a)
    e_b = np.cross(d, e_a)
    return a, d, e_a, e_b


def _member_surface(member: Member, others, size: float, n_theta: int, n_axial_even: bool,
                    top_size: float | None = None) -> NDArray[np.float64] | None:
    """(m, n_theta, 3) grid of a member's wetted surface between the solids it joins (rows
    graded to ``top_size`` along the axis at a still water line crossing it)."""
    a, d, e_a, e_b = _member_frame(member)
    length = float(np.linalg.norm(np.subtract(member.end, member.start)))
    radius = 0.5 * member.diameter
    theta = np.linspace(0.0, 2.0 * math.pi, n_theta, endpoint=False)
    offsets = radius * (np.cos(theta)[:, None] * e_a + np.sin(theta)[:, None] * e_b)

    def inside(p: NDArray[np.float64]) -> NDArray[np.bool_]:
        out = np.zeros(len(p), dtype=bool)
        for f in others:
            out |= f(p)
        return out

    def exit_distance(origins: NDArray[np.float64], direction: NDArray[np.float64]
                      ) -> NDArray[np.float64]:
        """Per generator: distance along ``direction`` from ``origins`` to where the line
        leaves the other solids (0 where the origin's neighbourhood is outside them)."""
        step = radius / 8.0
        lo = np.full(len(origins), -2.0 * radius)
        start_inside = inside(origins + lo[:, None] * direction)
        hi = lo.copy()
        active = start_inside.copy()
        while np.any(active):
            hi[active] += step
            active &= inside(origins + hi[:, None] * direction)
            if np.any(hi[active] > length):
                raise ValueError("a member lies inside another solid")
        lo = hi - step
        for _ in range(_BISECTION_STEPS):
            mid = 0.5 * (lo + hi)
            now = inside(origins + mid[:, None] * direction)
            lo = np.where(now, mid, lo)
            hi = np.where(now, hi, mid)
        return np.where(start_inside, hi, 0.0)

    s_start = exit_distance(a + offsets, d)
    s_end = length - exit_distance(a + d * length + offsets, -d)
    # cut at the still water line
    z0 = (a + offsets)[:, 2]
    at_water = 0  # the end cut by the still water line: 1 at s_end, -1 at s_start
    if abs(d[2]) > 1e-12:
        s_zero = -z0 / d[2]
        if d[2] > 0:
            at_water = 1 if np.any(s_zero < s_end) else 0
            s_end = np.minimum(s_end, s_zero)
        else:
            at_water = -1 if np.any(s_zero > s_start) else 0
            s_start = np.maximum(s_start, s_zero)
    elif np.any(z0 > 0):
        return None
    if np.any(s_end <= s_start):
        return None
    longest = float(np.max(s_end - s_start))
    if at_water and top_size is not None and top_size < size:
        frac = graded_levels(0.0, 1.0, size / longest, top_size / longest)
        frac[0], frac[-1] = 0.0, 1.0
        if at_water < 0:
            frac = 1.0 - frac[::-1]
    else:
        n_axial = max(1, math.ceil(longest / size))
        if n_axial_even and n_axial % 2:
            n_axial += 1
        frac = np.linspace(0.0, 1.0, n_axial + 1)
    s = s_start[None, :] + frac[:, None] * (s_end - s_start)[None, :]
    pts = a[None, None, :] + s[..., None] * d[None, None, :] + offsets[None, :, :]
    # rows along d, columns counter-clockwise about d: (d) x (tangent) points inward; reverse
    return pts[:, ::-1]


def _detect_symmetry(geometry: SemisubmersibleGeometry) -> int:
    """Largest n in (3, 2) such that the geometry is invariant under rotation by 2 pi / n about
    z and under the mirror y -> -y (within :data:`GEOMETRY_SYMMETRY_TOLERANCE`); 0 if none."""
    tol = GEOMETRY_SYMMETRY_TOLERANCE

    def column_rows(rot: NDArray) -> NDArray:
        return np.array([list(rot @ np.array([c.x, c.y, 0.0]))[:2]
                         + [c.diameter, c.z_top, c.z_bottom, c.heave_plate_diameter or 0.0,
                            c.heave_plate_height] for c in geometry.columns])

    def member_rows(rot: NDArray) -> NDArray:
        return np.array([list(rot @ np.asarray(m.start)) + list(rot @ np.asarray(m.end))
                         + [m.diameter] for m in geometry.members]).reshape(-1, 7)

    def matched(a: NDArray, b: NDArray, swap: bool) -> bool:
        used = np.zeros(len(b), dtype=bool)
        for row in a:
            candidates = [row]
            if swap:
                candidates.append(np.concatenate([row[3:6], row[0:3], row[6:]]))
            hit = -1
            for cand in candidates:
                diff = np.abs(b - cand).max(axis=1) if len(b) else np.array([])
                ok = np.nonzero((diff < tol) & ~used)[0]
                if len(ok):
                    hit = int(ok[0])
                    break
            if hit < 0:
                return False
            used[hit] = True
        return True

    def invariant(rot: NDArray) -> bool:
        eye = np.eye(3)
        return (matched(column_rows(rot), column_rows(eye), swap=False)
                and matched(member_rows(rot), member_rows(eye), swap=True))

    if not invariant(np.diag([1.0, -1.0, 1.0])):
        return 0
    for n in (3, 2):
        c, s = math.cos(2 * math.pi / n), math.sin(2 * math.pi / n)
        if invariant(np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])):
            return n
    return 0


def semisubmersible_mesh(geometry: SemisubmersibleGeometry, *, panel_size: float,
                         lid_depth: float | None = None, symmetry: bool = True,
                         waterline_panel_size: float | None = None) -> HullMesh:
    """Mesh of the wetted part of a semisubmersible (see the module docstring; columns'
    walls graded to ``waterline_panel_size`` at the still water line when given)."""
    n_sym = _detect_symmetry(geometry) if symmetry else 0
    multiple = 4 * max(n_sym, 1) if n_sym else 4
    builder = _Builder()
    lid_builder = _Builder()
    solids = [lambda p, c=c: _inside_column(p, c) for c in geometry.columns]
    solids += [lambda p, m=m: _inside_member(p, m) for m in geometry.members]
    n_cols = len(geometry.columns)
    for i, col in enumerate(geometry.columns):
        centre = (col.x, col.y)
        phase = math.atan2(col.y, col.x) if math.hypot(col.x, col.y) > 1e-9 else 0.0
        radius = 0.5 * col.diameter
        plate = col.heave_plate_diameter if col.heave_plate_diameter else None
        n_theta = _angular_count(plate / 2 if plate else radius, panel_size, multiple,
                                 MIN_COLUMN_PANELS)
        angles = phase + np.linspace(0.0, 2 * math.pi, n_theta, endpoint=False)
        z_top_wet = min(col.z_top, 0.0)
        plate_top = col.z_bottom + (col.heave_plate_height if plate else 0.0)
        if plate:
            _wall(builder, centre, plate / 2, col.z_bottom, min(plate_top, z_top_wet), angles,
                  panel_size, i, waterline_panel_size)
            if plate_top < z_top_wet:
                _disk(builder, centre, plate_top, radius, plate / 2, angles, panel_size, i,
                      down=False)
            _disk(builder, centre, col.z_bottom, 0.0, plate / 2, angles, panel_size, i, down=True)
        else:
            _disk(builder, centre, col.z_bottom, 0.0, radius, angles, panel_size, i, down=True)
        if plate_top < z_top_wet:
            _wall(builder, centre, radius, plate_top, z_top_wet, angles, panel_size, i,
                  waterline_panel_size)
        if col.z_top < 0.0:
            _disk(builder, centre, col.z_top, 0.0, radius, angles, panel_size, i, down=False)
        elif lid_depth is not None:
            _disk(lid_builder, centre, -lid_depth, 0.0, radius, angles, panel_size, i,
                  down=True)
    for k, member in enumerate(geometry.members):
        others = [f for j, f in enumerate(solids) if j != n_cols + k]
        n_theta = _angular_count(0.5 * member.diameter, panel_size, 4)
        n_theta = max(n_theta, 12)
        grid = _member_surface(member, others, panel_size, n_theta, n_axial_even=True,
                               top_size=waterline_panel_size)
        if grid is not None:
            builder.add_grid(grid, n_cols + k, closed=True)

    vertices, faces, owner = builder.arrays()
    centres = np.array([vertices[f].mean(axis=0) for f in faces])
    keep = np.ones(len(faces), dtype=bool)
    for j, inside in enumerate(solids):
        keep &= ~((owner != j) & inside(centres))
    faces = [f for f, k in zip(faces, keep) if k]
    full = _mesh(vertices, faces, "hull")
    lid_full = lid = None
    if lid_builder.faces:
        lv, lf, _ = lid_builder.arrays()
        lid_full = _mesh(lv, lf, "lid")
    if not n_sym:
        return HullMesh(full, lid_full, full, "none")
    hull = _symmetric(vertices, faces, n_sym, "hull")
    if lid_full is not None:
        lid = _symmetric(lv, lf, n_sym, "lid")
    if hull is None or (lid_full is not None and lid is None):
        return HullMesh(full, lid_full, full, "none")
    return HullMesh(hull, lid, full, f"rotation-{n_sym}+mirror-xOz")


def _face_areas(vertices: NDArray[np.float64], faces: list[list[int]]) -> NDArray[np.float64]:
    """Areas of triangles and planar quads (two triangles), vectorised."""
    quads = np.array([f if len(f) == 4 else f + [f[-1]] for f in faces])
    p = vertices[quads]
    a1 = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1)
    a2 = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]), axis=1)
    return a1 + a2


def _symmetric(vertices: NDArray[np.float64], faces: list[list[int]], n: int, name: str):
    """The half-sector 0 < angle < pi/n of a mesh as a dihedral-symmetric capytaine mesh, or
    None when its images do not tile the whole mesh (panels across the sector planes)."""
    import capytaine as cpt

    centres = np.array([vertices[f].mean(axis=0) for f in faces])
    areas = _face_areas(vertices, faces)
    angle = np.arctan2(centres[:, 1], centres[:, 0])
    in_half = (angle > 0.0) & (angle < math.pi / n)
    # the 2 n images of the half-sector tile the whole mesh when their panel count and area add
    # up to the full mesh's (a panel across a sector plane would be missing from every image)
    if (2 * n * int(in_half.sum()) != len(faces)
            or abs(2 * n * areas[in_half].sum() - areas.sum()) > SYMMETRY_TOLERANCE * areas.sum()):
        return None
    half = _mesh(vertices, [f for f, k in zip(faces, in_half) if k], name)
    return cpt.RotationSymmetricMesh(cpt.ReflectionSymmetricMesh(half, plane="xOz"), n=n)


def build_mesh(geometry: FloaterGeometry, *, panel_size: float, reference_xy=(0.0, 0.0),
               lid_depth: float | None = None, symmetry: bool = True,
               radial_panels: int | None = None, water_depth: float = math.inf,
               waterline_panel_size: float | None = None) -> HullMesh:
    """The hull (and lid) mesh of a floater geometry.

    Parameters
    ----------
    geometry
        Cylinder, semisubmersible or mesh file (read by
        :func:`floatmoor.hydro.mesh_file.mesh_from_file`, which may raise
        :class:`floatmoor.io.bem_data.BemFileError`).
    panel_size
        Target panel edge [m] (of the lid only, for a mesh file).
    reference_xy
        (x, y) of the cylinder's axis [m] (semisubmersible coordinates are global).
    lid_depth
        Lid depth below the still water line [m], or None for no lid.
    symmetry
        Use the geometry's symmetries when capytaine can.
    radial_panels
        Cylinder only: panels across the bottom radius.
    water_depth
        Mesh file only: the seabed's depth [m], which the hull must stay above.
    waterline_panel_size
        Parametric hulls: walls graded to this panel height at the still water line
        (the drift's mesh; :func:`graded_levels`); None: uniform. A mesh file is used as is.
    """
    if isinstance(geometry, MeshGeometry):
        from floatmoor.hydro.mesh_file import mesh_from_file

        return mesh_from_file(geometry, lid_depth=lid_depth, lid_panel_size=panel_size,
                              symmetry=symmetry, water_depth=water_depth)
    if isinstance(geometry, CylinderGeometry):
        return cylinder_mesh(geometry, panel_size=panel_size, centre=tuple(reference_xy),
                             lid_depth=lid_depth, symmetry=symmetry, radial_panels=radial_panels,
                             waterline_panel_size=waterline_panel_size)
    return semisubmersible_mesh(geometry, panel_size=panel_size, lid_depth=lid_depth,
                                symmetry=symmetry, waterline_panel_size=waterline_panel_size)


def mesh_hash(mesh) -> str:
    """SHA-256 of the panels' vertex coordinates, face by face (rounded to 1e-9 m), of a
    (merged) mesh: independent of how vertices are shared between panels."""
    merged = mesh.merged() if hasattr(mesh, "merged") else mesh
    faces = np.asarray(merged.as_array_of_faces(), dtype=float)
    return hashlib.sha256(np.round(faces, 9).tobytes()).hexdigest()


# -- analytic properties ----------------------------------------------------------------------

def geometry_properties(geometry: FloaterGeometry, reference_xy=(0.0, 0.0)) -> GeometryProperties:
    """Analytic submerged volume, waterplane area and moments, and centre of buoyancy.

    For a semisubmersible the columns are exact; members are counted as straight tubes
    between their end points (cut at z = 0), minus nothing for their ends: an end joining a
    column curved with radius R overlaps it by about r^2 L_end / R, below 0.1 % of the volume
    for the OC4 platform. Inclined members crossing the water line add an ellipse
    pi r^2 / sin(elevation) to the waterplane.

    Raises
    ------
    ValueError
        For a mesh geometry, which has no analytic properties (see
        :func:`floatmoor.hydro.mesh_checks.reference_hydrostatics`).
    """
    if isinstance(geometry, MeshGeometry):
        raise ValueError("a mesh hull has no analytic geometry properties")
    if isinstance(geometry, CylinderGeometry):
        r, t = geometry.radius, geometry.draft
        area = math.pi * r * r
        x0, y0 = reference_xy
        return GeometryProperties(volume=area * t, waterplane_area=area,
                                  centre_of_buoyancy=(x0, y0, -0.5 * t),
                                  waterplane_inertia=(math.pi * r ** 4 / 4 + area * y0 * y0,
                                                      math.pi * r ** 4 / 4 + area * x0 * x0))
    vol = 0.0
    moment = np.zeros(3)
    awp = 0.0
    iyy = ixx = 0.0  # integral of x^2 (pitch) and y^2 (roll)
    for c in geometry.columns:
        r = 0.5 * c.diameter
        top = min(c.z_top, 0.0)
        sections = []
        if c.heave_plate_diameter:
            plate_top = c.z_bottom + c.heave_plate_height
            sections.append((0.5 * c.heave_plate_diameter, c.z_bottom, min(plate_top, top)))
            sections.append((r, plate_top, top))
        else:
            sections.append((r, c.z_bottom, top))
        for rad, lo, hi in sections:
            if hi > lo:
                v = math.pi * rad * rad * (hi - lo)
                vol += v
                moment += v * np.array([c.x, c.y, 0.5 * (lo + hi)])
        if c.z_top >= 0.0 > c.z_bottom:
            a = math.pi * r * r
            awp += a
            ixx += math.pi * r ** 4 / 4 + a * c.y * c.y
            iyy += math.pi * r ** 4 / 4 + a * c.x * c.x
    for m in geometry.members:
        p0, p1 = np.asarray(m.start, float), np.asarray(m.end, float)
        if p0[2] > p1[2]:
            p0, p1 = p1, p0
        if p0[2] >= 0.0:
            continue
        if p1[2] > 0.0:
            frac = -p0[2] / (p1[2] - p0[2])
            p_wl = p0 + frac * (p1 - p0)
            elev = math.asin((p1[2] - p0[2]) / float(np.linalg.norm(p1 - p0)))
            a = math.pi * (0.5 * m.diameter) ** 2 / math.sin(elev)
            awp += a
            ixx += a * p_wl[1] ** 2
            iyy += a * p_wl[0] ** 2
            p1 = p_wl
        v = math.pi * (0.5 * m.diameter) ** 2 * float(np.linalg.norm(p1 - p0))
        vol += v
        moment += v * 0.5 * (p0 + p1)
    cob = moment / vol
    return GeometryProperties(volume=vol, waterplane_area=awp,
                              centre_of_buoyancy=(float(cob[0]), float(cob[1]), float(cob[2])),
                              waterplane_inertia=(ixx, iyy))
