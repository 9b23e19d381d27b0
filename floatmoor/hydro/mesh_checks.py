"""Checks of a hull mesh read from a file, before the BEM solves on it (``hydro build``).

Each check gives a :class:`MeshCheck`: its figure, its limit, whether it passed, the rule's
source and how to fix a failure. They are made on the immersed hull (clipped at z = 0, the
declared symmetries expanded):

* ``watertight`` (fatal): every panel edge below the waterline is shared by exactly two
  panels. Edges on z = 0 are the waterline, closed by the waterplane. A T-junction of a
  non-conforming mesh (one long edge against two or more short ones along it) is closed too:
  edges used once are matched against the other once-used edges lying along them. What is
  left is a hole (or a crack) in the hull; an edge shared by three or more panels is
  reported as well. Floatmoor's hydrostatics and capytaine's integral equations both assume
  a closed hull.
* ``normals`` (fatal): the panel normals point out of the body into the water (capytaine's
  convention). The displaced volume by the divergence theorem from its three components,
  V = int x n_x dS = int y n_y dS = int z n_z dS (the waterplane closes the hull and adds
  nothing to any of them), must be positive and the three must agree; and neighbouring
  panels must run along their shared edge in opposite directions (a consistently oriented
  surface). Inward normals give negative volumes; a few flipped panels break the agreement
  and the orientation of their edges.
* ``panel_size`` (warning): the wavelength at the top BEM frequency is at least capytaine's
  ``FloatingBody.minimal_computable_wavelength``, 8 x the largest panel radius (hull and
  lid); the panels per wavelength are reported.
* ``irregular_frequencies`` (warning): the top BEM frequency is below capytaine's
  ``FloatingBody.first_irregular_frequency_estimate`` of the hull's interior (the lowest
  sloshing mode of a box of the waterplane's extent and the draft). Harmless with a lid,
  which removes them; reported either way.

:func:`reference_hydrostatics` integrates the hull's hydrostatics along other paths than
:func:`floatmoor.hydro.hydrostatics.hull_hydrostatics` (which uses int f n_z dS only): the
volume from int x n_x dS and int y n_y dS, the height of the centre of buoyancy from
int x z n_x dS and int y z n_y dS, the waterplane area and moments from line integrals
around the waterline (Green's theorem). The database records them for its ``hydrostatics``
check (floatmoor.hydro.checks), a mesh having no analytic geometry to be compared with.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["MeshCheck", "HullTopology", "hull_topology", "check_watertight", "check_normals",
           "check_panel_size", "check_irregular_frequencies", "reference_hydrostatics",
           "run_mesh_checks", "refuse_failed", "summary_lines", "divergence_volumes",
           "COORDINATE_TOLERANCE", "VOLUME_AGREEMENT", "MIN_WAVELENGTH_RADII"]

#: Vertices closer than this fraction of the hull's largest extent are one vertex, and a
#: vertex this close to z = 0 is on the waterline. Mesh files write coordinates to 6-8
#: significant digits (neighbouring panels repeat the same text, so shared vertices agree
#: exactly); 1e-6 merges what the file meant as one point without merging distinct vertices
#: of any mesh fine enough to be solved (MAX_BEM_PANELS panels are ~1e-2 of the extent).
COORDINATE_TOLERANCE = 1e-6
#: Largest spread of the three divergence-theorem volumes relative to the volume. On a closed
#: polyhedral surface they agree to round-off (~1e-15); coordinates written to 6 significant
#: digits put a T-junction's middle vertex up to 1e-6 of the extent off its edge, a gap of
#: ~1e-6 of a panel's area. One flipped panel of the 216-panel test cylinder parts them by
#: 1.6e-2 to 2.6e-2 (tests/hydro/test_mesh_checks.py).
VOLUME_AGREEMENT = 1e-4
#: capytaine's rule: the wavelength must be at least 8 x the largest panel radius
#: (``FloatingBody.minimal_computable_wavelength``, capytaine 3.0 bodies.py).
MIN_WAVELENGTH_RADII = 8.0
#: Once-used edges beyond this count are reported as open without the T-junction matching
#: (which compares every pair); a hull with that many is broken either way.
_MAX_MATCHED_EDGES = 5000
#: Edges compared at a time in the T-junction matching (bounds its memory to ~30 MB).
_MATCH_CHUNK = 200


@dataclass(frozen=True)
class MeshCheck:
    """One check of a hull mesh: ``value`` against ``limit`` (the detail says which way)."""

    name: str
    passed: bool
    fatal: bool  #: a failure refuses the build (else it is a warning)
    value: float
    limit: float
    rule: str  #: what passing means
    detail: str  #: the figure in words
    source: str  #: where the rule comes from
    fix: str  #: what to do when it fails

    def as_dict(self) -> dict:
        """JSON-ready."""
        out = asdict(self)
        out.update(passed=bool(self.passed), fatal=bool(self.fatal), value=float(self.value),
                   limit=float(self.limit))
        return out


@dataclass(frozen=True)
class HullTopology:
    """Merged vertices and oriented edges of a hull mesh (triangles and quads)."""

    vertices: NDArray[np.float64]  #: (m, 3) merged vertices [m]
    panels: NDArray[np.int64]  #: (p, 4) panels on the merged vertices (triangles repeat one)
    triangles: NDArray[np.float64]  #: (t, 3, 3) panels split into triangles [m]
    open_edges: NDArray[np.int64]  #: (k, 2) edges used once below the waterline, unmatched
    waterline_edges: NDArray[np.int64]  #: (w, 2) edges used once on z = 0, as traversed
    nonmanifold_edges: int  #: edges shared by three or more panels
    misoriented_edges: int  #: edges run in the same direction by both their panels
    tjunction_edges: int  #: once-used edges closed by collinear edges (non-conforming mesh)
    degenerate_panels: int  #: panels with fewer than 3 distinct vertices after merging
    tolerance: float  #: merge distance [m]

    @property
    def open_length(self) -> float:
        """Total length of the open edges [m]."""
        if not len(self.open_edges):
            return 0.0
        d = self.vertices[self.open_edges[:, 1]] - self.vertices[self.open_edges[:, 0]]
        return float(np.linalg.norm(d, axis=1).sum())


def _merge_vertices(vertices: NDArray[np.float64], tol: float) -> NDArray[np.int64]:
    """Label of each vertex: vertices within ``tol`` (transitively) share a label."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    n = len(vertices)
    pairs = cKDTree(vertices).query_pairs(r=tol, output_type="ndarray")
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    return labels.astype(np.int64)


def _faces_array(mesh) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    merged = mesh.merged() if hasattr(mesh, "merged") else mesh
    return np.asarray(merged.vertices, dtype=float), np.asarray(merged.faces, dtype=np.int64)


def hull_topology(mesh) -> HullTopology:
    """Merge the vertices of a (merged or symmetric) capytaine hull mesh and sort its edges.

    capytaine stores triangles as quads repeating their last vertex; repeated vertices (also
    after merging) are dropped from a panel's loop.
    """
    vertices, faces = _faces_array(mesh)
    extent = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 0.0
    tol = COORDINATE_TOLERANCE * max(extent, 1e-300)
    labels = _merge_vertices(vertices, tol)
    first = np.full(labels.max() + 1, -1, dtype=np.int64)
    first[labels[::-1]] = np.arange(len(labels))[::-1]  # the first vertex of each label
    points = vertices[first]
    loops = labels[faces]  # (n, 4)
    # triangles of each panel (the original coordinates, quads split as hydrostatics does)
    quads = faces[:, 3] != faces[:, 2]
    triangles = np.concatenate([vertices[faces[:, [0, 1, 2]]],
                                vertices[faces[quads][:, [0, 2, 3]]]])
    # directed edges a -> b of each panel, skipping repeated vertices
    starts = loops
    ends = np.roll(loops, -1, axis=1)
    keep = starts != ends
    distinct = np.array([len(set(row)) for row in loops])
    degenerate = int(np.sum(distinct < 3))
    keep &= (distinct >= 3)[:, None]
    a, b = starts[keep], ends[keep]
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    keys = lo * (labels.max() + 1) + hi
    uniq, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    count_of_edge = counts[inverse]
    # orientation of edges shared by exactly two panels: opposite directions
    forward = (a < b).astype(np.int64)
    pair = count_of_edge == 2
    sums = np.bincount(inverse[pair], weights=forward[pair], minlength=len(uniq))
    misoriented = int(np.sum((counts == 2) & (sums != 1)))
    nonmanifold = int(np.sum(counts > 2))
    once = count_of_edge == 1
    z = points[:, 2]
    on_waterline = (np.abs(z[a]) <= tol) & (np.abs(z[b]) <= tol)
    waterline = np.stack([a[once & on_waterline], b[once & on_waterline]], axis=1)
    candidates = np.stack([a[once & ~on_waterline], b[once & ~on_waterline]], axis=1)
    open_edges, tjunctions = _unmatched(points, candidates, tol)
    panels = []
    for row in loops[distinct >= 3].tolist():
        loop = list(dict.fromkeys(row))  # distinct vertices in order
        panels.append(loop + loop[-1:] * (4 - len(loop)))
    panels = np.array(panels, dtype=np.int64).reshape(-1, 4)
    return HullTopology(vertices=points, panels=panels, triangles=triangles,
                        open_edges=open_edges,
                        waterline_edges=waterline, nonmanifold_edges=nonmanifold,
                        misoriented_edges=misoriented, tjunction_edges=tjunctions,
                        degenerate_panels=degenerate, tolerance=tol)


def _unmatched(points: NDArray[np.float64], edges: NDArray[np.int64], tol: float
               ) -> tuple[NDArray[np.int64], int]:
    """The once-used edges not closed by a T-junction, and how many were.

    Edge e is closed when it lies along another once-used edge (both its ends within ``tol``
    of that edge's segment) or when the once-used edges lying along it add up to its length.
    """
    n = len(edges)
    if n == 0 or n > _MAX_MATCHED_EDGES:
        return edges.reshape(-1, 2), 0
    p, q = points[edges[:, 0]], points[edges[:, 1]]
    d = q - p
    length = np.linalg.norm(d, axis=1)

    slack = tol / np.maximum(length, 1e-300)

    def within(points_: NDArray[np.float64]) -> NDArray[np.bool_]:
        """(n_points, n_edges): the point lies on the edge's segment (within tol)."""
        rel = points_[:, None, :] - p[None, :, :]
        t = np.einsum("ijk,jk->ij", rel, d) / np.maximum(length * length, 1e-300)[None, :]
        dist = np.linalg.norm(rel - t[..., None] * d[None, :, :], axis=2)
        return (dist <= tol) & (t >= -slack[None, :]) & (t <= 1.0 + slack[None, :])

    inside = np.zeros((n, n), dtype=bool)  # inside[i, j]: edge i lies along edge j
    for lo in range(0, n, _MATCH_CHUNK):
        hi = min(n, lo + _MATCH_CHUNK)
        inside[lo:hi] = within(p[lo:hi]) & within(q[lo:hi])
    np.fill_diagonal(inside, False)
    contains_other = inside.any(axis=0)  # edge j holds shorter edges
    along_other = inside.any(axis=1)  # edge i lies along a longer one
    covered = (inside * length[:, None]).sum(axis=0)
    closed = along_other | (contains_other
                            & (np.abs(covered - length) <= tol * (1 + inside.sum(axis=0))))
    return edges[~closed], int(np.sum(closed))


def check_watertight(topology: HullTopology) -> MeshCheck:
    """Every edge below the waterline shared by exactly two panels (module docstring)."""
    n_open = len(topology.open_edges)
    length = topology.open_length
    bad = n_open + topology.nonmanifold_edges
    where = ""
    if n_open:
        v = topology.vertices
        d = np.linalg.norm(v[topology.open_edges[:, 1]] - v[topology.open_edges[:, 0]], axis=1)
        mid = 0.5 * (v[topology.open_edges[:, 0]] + v[topology.open_edges[:, 1]])
        centre = mid[int(np.argmax(d))]
        where = f", e.g. at ({centre[0]:.4g}, {centre[1]:.4g}, {centre[2]:.4g}) m"
    detail = (f"{n_open} open edges below the waterline ({length:.4g} m long{where}), "
              f"{topology.nonmanifold_edges} edges shared by more than two panels")
    if topology.tjunction_edges:
        detail += f"; {topology.tjunction_edges} edges closed by T-junctions"
    if topology.degenerate_panels:
        detail += f"; {topology.degenerate_panels} panels of no area ignored"
    return MeshCheck("watertight", bad == 0, True, float(bad), 0.0,
                     "a watertight hull: every panel edge below the waterline shared by "
                     "exactly two panels", detail,
                     "floatmoor: the hydrostatics and capytaine's boundary integral equations "
                     "assume a closed hull (below the waterplane)",
                     "close the hull below the waterline (every panel edge shared by two "
                     "panels), merge duplicate vertices, and remove internal panels")


def divergence_volumes(triangles: NDArray[np.float64]) -> NDArray[np.float64]:
    """(int x n_x dS, int y n_y dS, int z n_z dS) over the triangles (outward normals: the
    volume three times) [m^3]."""
    area_vector = 0.5 * np.cross(triangles[:, 1] - triangles[:, 0],
                                 triangles[:, 2] - triangles[:, 0])
    centroid = triangles.mean(axis=1)
    return np.einsum("ij,ij->j", centroid, area_vector)


def check_normals(topology: HullTopology) -> MeshCheck:
    """Outward normals: positive, agreeing divergence-theorem volumes and a consistently
    oriented surface (module docstring)."""
    vols = divergence_volumes(topology.triangles)
    scale = float(np.abs(vols).max()) or 1.0
    spread = float((vols.max() - vols.min()) / scale)
    outward = bool(vols.min() > 0.0)
    passed = outward and spread <= VOLUME_AGREEMENT and topology.misoriented_edges == 0
    detail = (f"V = {vols[2]:.6g} m^3 from int z n_z dS; int x n_x dS, int y n_y dS "
              f"{vols[0]:.6g}, {vols[1]:.6g} (spread {spread:.1e} of V, limit "
              f"{VOLUME_AGREEMENT:g}); {topology.misoriented_edges} edges where neighbouring "
              "panels disagree in orientation")
    if not outward:
        detail = "negative volume (normals into the body): " + detail
    return MeshCheck("normals", passed, True, spread if outward else math.inf, VOLUME_AGREEMENT,
                     "outward normals: a positive volume, the same from its three "
                     "divergence-theorem components, and consistently oriented panels",
                     detail, "capytaine convention: normals point out of the body, into the "
                     "water; divergence theorem",
                     "orient every panel's vertices counter-clockwise seen from the water "
                     "(reverse the vertex order of inward panels)")


def check_panel_size(hull, lid, omega_max: float, wavelength: float) -> MeshCheck:
    """capytaine's wavelength rule at the top frequency (module docstring)."""
    import capytaine as cpt

    body = cpt.FloatingBody(mesh=hull, lid_mesh=lid)
    minimal = float(body.minimal_computable_wavelength)
    radius = minimal / MIN_WAVELENGTH_RADII
    per_wavelength = wavelength / (2.0 * radius)
    detail = (f"wavelength {wavelength:.4g} m at the top frequency {omega_max:.4g} rad/s, "
              f"largest panel radius {radius:.4g} m: {per_wavelength:.3g} panel diameters "
              f"per wavelength (at least {MIN_WAVELENGTH_RADII / 2:g}: wavelength >= "
              f"{minimal:.4g} m)")
    return MeshCheck("panel_size", wavelength >= minimal, False, minimal / wavelength, 1.0,
                     "panels small enough for the top frequency (wavelength >= 8 x the largest "
                     "panel radius)", detail,
                     "capytaine 3.0 FloatingBody.minimal_computable_wavelength "
                     "(8 x the largest panel radius)",
                     "refine the mesh (smaller panels) or lower the top [hydro] frequency")


def check_irregular_frequencies(topology: HullTopology, lid, omega_max: float,
                                g: float) -> MeshCheck:
    """The top frequency against the first irregular frequency of the hull's interior
    (module docstring). capytaine's estimate takes the extent of each connected part of the
    waterline, so it is made on the hull with its vertices merged (``topology``)."""
    import capytaine as cpt

    hull = cpt.Mesh(vertices=topology.vertices, faces=topology.panels, auto_clean=False,
                    auto_check=False)
    omega_irr = float(cpt.FloatingBody(mesh=hull).first_irregular_frequency_estimate(g=g))
    below = omega_max < omega_irr
    ratio = omega_max / omega_irr if math.isfinite(omega_irr) else 0.0
    detail = (f"first irregular frequency of the hull's interior ~ {omega_irr:.4g} rad/s, "
              f"top BEM frequency {omega_max:.4g} rad/s")
    if lid is not None:
        with_lid = float(cpt.FloatingBody(mesh=hull, lid_mesh=lid)
                         .first_irregular_frequency_estimate(g=g))
        detail += (f"; harmless with the lid (estimate with it ~ {with_lid:.4g} rad/s)")
    elif not below:
        detail += ": the band reaches it (results near it are spoiled)"
    return MeshCheck("irregular_frequencies", below or lid is not None, False, ratio, 1.0,
                     "a band below the first irregular frequency, or a lid", detail,
                     "capytaine 3.0 FloatingBody.first_irregular_frequency_estimate "
                     "(box of the waterplane's extent and the draft)",
                     "set [hydro] lid = true, or keep the top frequency below it")


def reference_hydrostatics(topology: HullTopology, rotation_center) -> dict[str, float]:
    """Hydrostatic integrals of the hull along other paths than
    :func:`floatmoor.hydro.hydrostatics.hull_hydrostatics` (module docstring).

    Returns
    -------
    dict with ``disp_volume`` [m^3], ``center_of_buoyancy_z`` [m], ``waterplane_area``
    [m^2], ``waterplane_yy`` and ``waterplane_xx`` (integrals of (y - yc)^2 and (x - xc)^2
    over the waterplane) [m^4], about ``rotation_center``.
    """
    tri = topology.triangles
    vols = divergence_volumes(tri)
    volume = 0.5 * float(vols[0] + vols[1])
    area_vector = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    mids = 0.5 * (tri + np.roll(tri, -1, axis=1))  # edge midpoints: exact for quadratics
    xz = (mids[..., 0] * mids[..., 2]).mean(axis=1)
    yz = (mids[..., 1] * mids[..., 2]).mean(axis=1)
    moment_z = 0.5 * float(np.sum(xz * area_vector[:, 0]) + np.sum(yz * area_vector[:, 1]))
    c = np.asarray(rotation_center, dtype=float)
    e = topology.waterline_edges
    v = topology.vertices
    xa, ya = v[e[:, 0], 0] - c[0], v[e[:, 0], 1] - c[1]
    xb, yb = v[e[:, 1], 0] - c[0], v[e[:, 1], 1] - c[1]
    cross = xa * yb - xb * ya
    # outward hull panels run along the waterline clockwise seen from above: minus the
    # counter-clockwise polygon formulas
    area = -0.5 * float(cross.sum())
    ixx = -float(np.sum((ya * ya + ya * yb + yb * yb) * cross)) / 12.0
    iyy = -float(np.sum((xa * xa + xa * xb + xb * xb) * cross)) / 12.0
    return {"disp_volume": volume,
            "center_of_buoyancy_z": moment_z / volume if volume else math.nan,
            "waterplane_area": area, "waterplane_yy": ixx, "waterplane_xx": iyy}


def run_mesh_checks(mesh, *, omega_max: float, wavelength: float, g: float,
                    rotation_center) -> tuple[list[MeshCheck], dict[str, float]]:
    """The four checks of a :class:`~floatmoor.hydro.hull_mesh.HullMesh` read from a file, in
    the module docstring's order, and its :func:`reference_hydrostatics`.

    Parameters
    ----------
    mesh
        The hull mesh (``full_hull`` and ``lid`` are checked).
    omega_max
        Top BEM frequency [rad/s].
    wavelength
        Wavelength at ``omega_max`` in the BEM's water depth [m].
    g
        Gravity [m/s^2].
    rotation_center
        (3,) [m], for the reference hydrostatics.
    """
    topology = hull_topology(mesh.full_hull)
    lid = mesh.lid.merged() if mesh.lid is not None and hasattr(mesh.lid, "merged") \
        else mesh.lid
    checks = [check_watertight(topology), check_normals(topology),
              check_panel_size(mesh.full_hull, lid, omega_max, wavelength),
              check_irregular_frequencies(topology, lid, omega_max, g)]
    return checks, reference_hydrostatics(topology, rotation_center)


def refuse_failed(checks: list[MeshCheck], path: str) -> None:
    """Raise :class:`floatmoor.io.bem_data.BemFileError` for the first failed fatal check
    (naming it, its figure and how to fix it)."""
    from floatmoor.io.bem_data import BemFileError

    for check in checks:
        if check.fatal and not check.passed:
            raise BemFileError(path, f"the {check.name} check of the immersed hull",
                               check.rule, f"{check.detail} ({check.fix})")


def summary_lines(info: dict, checks: list[dict]) -> list[str]:
    """What ``hydro build`` says about a hull read from a file: the file, what was made of
    it and the checks (``info``: MeshFileInfo.as_dict(); ``checks``: MeshCheck.as_dict()s)."""
    used = ", ".join(info["symmetry_used"]) or "none"
    declared = ", ".join(info["symmetry_declared"]) or "none"
    x0, y0, z0, x1, y1, z1 = info["extent"]
    rows = [f"mesh {info['file']} ({info['format']}, {info['length_unit']}, SHA-256 "
            f"{info['sha256'][:12]}): {info['panels_read']} panels read, "
            f"{info['panels_full']} in the whole hull, {info['panels_immersed']} below the "
            f"waterline, {info['lid_panels']} lid panels; symmetry declared {declared}, used "
            f"by the BEM {used}",
            f"  immersed hull x {x0:.4g} to {x1:.4g} m, y {y0:.4g} to {y1:.4g} m, z {z0:.4g} "
            f"to {z1:.4g} m"]
    rows += [f"  note: {note}" for note in info["notes"]]
    for c in checks:
        result = "pass" if c["passed"] else "FAIL" if c["fatal"] else "WARN"
        rows.append(f"  {c['name']:<22}{result:<6}{c['detail']}")
    return rows
