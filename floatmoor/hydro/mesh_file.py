"""Hull meshes read from files (``[floater.geometry] kind = "mesh"``).

The file is read with capytaine's ``load_mesh``: its own readers for WAMIT ``gdf``, Nemoh
``mar``, HAMS ``pnl`` and HydroStar ``hst`` files, meshio for the surface formats (STL, OBJ,
PLY, OFF, VTK, VTU, Gmsh ``msh``; triangles and quads). Then, in this order:

1. symmetry: the file holds the positive half (``xz``: y >= 0) or quarter of the hull. The
   formats that carry symmetry flags (GDF ISX/ISY, HST SYMMETRY, PNL, MAR) must flag exactly
   the declared planes; a file declared a half must lie on the positive side of its plane;
2. the coordinates are scaled by the length unit and translated by ``position``. A declared
   plane is kept for the BEM (a capytaine ``ReflectionSymmetricMesh``) when ``[hydro]
   symmetry`` is on and ``position`` does not move it off x = 0 or y = 0; otherwise the file
   is mirrored into the full hull;
3. the hull is clipped at the still water line (panels crossing it are cut, panels lying on
   z = 0 dropped: they are a deck or lid, not wetted hull);
4. with ``[hydro] lid``, capytaine's ``generate_lid`` covers the interior waterplane at
   z = -lid_depth with panels of about ``[hydro] panel_size`` (for a mesh hull the lid's panel
   edge), generated on the full hull and cut to the kept symmetry.

Before any reader runs, the panel and vertex counts the file declares (:func:`claimed_counts`)
are held to :data:`MAX_FILE_PANELS` and :data:`MAX_FILE_VERTICES`, so that a large or forged
header cannot make a reader allocate tens of GiB.

The result is the :class:`~floatmoor.hydro.hull_mesh.HullMesh` the parametric kinds give, so
the BEM and the database code need no special case. A file that cannot be read, holds no
panels, non-finite vertices, nothing below the waterline, panels below the seabed, or more
panels than :data:`floatmoor.case.limits.MAX_BEM_PANELS` raises
:class:`floatmoor.io.bem_data.BemFileError`. The hull checks are
:mod:`floatmoor.hydro.mesh_checks`.
"""

from __future__ import annotations

import contextlib
import io
import logging
import math
import mmap
import re
import struct
import warnings
from dataclasses import asdict, dataclass

import numpy as np

from floatmoor.case.limits import MAX_BEM_PANELS
from floatmoor.case.schema import MeshGeometry
from floatmoor.file_hash import file_sha256
from floatmoor.hydro.hull_mesh import HullMesh
from floatmoor.io.bem_data import BemFileError
from floatmoor.terminal_text import shown

__all__ = ["MeshFileInfo", "mesh_from_file", "read_mesh_file", "NATIVE_FORMATS",
           "MESHIO_FORMATS", "CAPYTAINE_PLANES", "MAX_FILE_PANELS", "MAX_FILE_VERTICES",
           "claimed_counts"]

#: Formats capytaine reads itself (they may carry symmetry flags).
NATIVE_FORMATS = ("gdf", "mar", "nemoh", "pnl", "hst")
#: Formats read through meshio, with meshio's name for each.
MESHIO_FORMATS = {"stl": "stl", "obj": "obj", "ply": "ply", "off": "off", "vtk": "vtk",
                  "vtu": "vtu", "msh": "gmsh"}
#: Case-file plane names and capytaine's.
CAPYTAINE_PLANES = {"xz": "xOz", "yz": "yOz"}
#: meshio cell types that are not surface panels and are skipped (points, lines, volumes).
_SKIPPED_CELLS = {"vertex", "line", "line3", "tetra", "tetra10", "hexahedron", "hexahedron20",
                  "wedge", "pyramid"}
#: Most panels a mesh file may hold, wet and dry, checked from its header (or a count of its
#: panel records) before any reader allocates: the immersed bound MAX_BEM_PANELS applies
#: after clipping and mirroring, and a file holding the dry hull too, or a quarter that is
#: mirrored, still fits in 4 times it. capytaine's dense BEM needs 2 matrices of 16 N^2 bytes
#: (complex doubles) for N immersed panels: 13 GB at MAX_BEM_PANELS already.
MAX_FILE_PANELS = 4 * MAX_BEM_PANELS
#: Most vertices a mesh file may declare: 4 per panel (unshared quads) at most.
MAX_FILE_VERTICES = 4 * MAX_FILE_PANELS
#: Fraction of the hull's extent within which a vertex is on a plane (as
#: floatmoor.hydro.mesh_checks.COORDINATE_TOLERANCE, the same reasoning).
_PLANE_TOLERANCE = 1e-6


@dataclass(frozen=True)
class MeshFileInfo:
    """What was read from a mesh file and what was made of it (recorded in the database)."""

    file: str  #: as the case file writes it
    sha256: str
    format: str
    length_unit: str
    position: tuple[float, float, float]
    symmetry_declared: tuple[str, ...]
    symmetry_used: tuple[str, ...]  #: the planes the BEM uses
    panels_read: int  #: panels in the file
    panels_full: int  #: of the whole hull (declared symmetry expanded)
    panels_immersed: int  #: of the whole hull below the waterline
    panels_on_waterplane: int  #: dropped, lying on z = 0
    lid_panels: int
    extent: tuple[float, float, float, float, float, float]  #: x, y, z min and max [m]
    notes: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """JSON-ready."""
        return asdict(self)


def _quiet_capytaine() -> None:
    # capytaine logs mesh-quality warnings per mesh it builds; floatmoor's checks report
    logging.getLogger("capytaine").setLevel(logging.ERROR)


def read_mesh_file(path: str, fmt: str):
    """The capytaine mesh of a file as read (possibly a ``ReflectionSymmetricMesh`` when the
    file flags a symmetry), and notes on what was skipped.

    What the readers print or warn is captured (meshio prints why it cannot read a file, then
    exits): a failure's is part of the one-line error, a success's a note.

    Raises
    ------
    BemFileError
        Unreadable or malformed file.
    """
    said = io.StringIO()
    try:
        with contextlib.redirect_stdout(said), contextlib.redirect_stderr(said), \
                warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            mesh, notes = _read_mesh_file(path, fmt)
    except (BemFileError, SystemExit) as err:
        told = "; ".join(dict.fromkeys(line.strip() for line in said.getvalue().splitlines()
                                       if line.strip()))
        if isinstance(err, BemFileError):
            if not told:
                raise
            raise BemFileError(err.path, err.where, err.expected,
                               shown(f"{err.found} (the reader said: {told})")) from None
        raise BemFileError(path, "", f"a {fmt} mesh file capytaine can read",
                           shown(told or "a reader that gave up")) from None
    told = [line.strip() for line in said.getvalue().splitlines() if line.strip()]
    told += [" ".join(str(w.message).split()) for w in caught]
    if told:
        notes.append("the reader said: " + shown("; ".join(dict.fromkeys(told))))
    return mesh, notes


def _gdf_length_unit(path: str) -> None:
    """A GDF file's ULEN (line 2, its length unit) must be a finite number > 0 (capytaine
    reads past it)."""
    with open(path, encoding="utf-8", errors="replace") as handle:
        handle.readline()
        fields = handle.readline().split()
    try:
        ulen = float(fields[0])
    except (IndexError, ValueError):
        ulen = math.nan
    if not (math.isfinite(ulen) and ulen > 0.0):
        raise BemFileError(path, "line 2, ULEN", "a length unit ULEN > 0 (finite)",
                           shown(fields[0] if fields else "nothing", 40))


def _read_mesh_file(path: str, fmt: str):
    """:func:`read_mesh_file` without the capture."""
    from capytaine.meshes.io import load_mesh

    _quiet_capytaine()
    notes: list[str] = []
    _refuse_large_counts(path, fmt)
    try:
        if fmt in MESHIO_FORMATS:
            import meshio

            # meshio's STL reader tells binary from ASCII by a uint32 product that overflows
            # on ASCII files (harmless: the sizes then differ)
            with np.errstate(over="ignore"):
                data = meshio.read(path, file_format=MESHIO_FORMATS[fmt])
            kinds = {}
            for block in data.cells:
                kinds[block.type] = kinds.get(block.type, 0) + len(block.data)
            unsupported = {k: n for k, n in kinds.items()
                           if k not in ("triangle", "quad") and k not in _SKIPPED_CELLS}
            if unsupported:
                raise BemFileError(path, "cells", "triangle and quad panels",
                                   ", ".join(f"{n} {k} cells" for k, n in unsupported.items()))
            skipped = {k: n for k, n in kinds.items() if k in _SKIPPED_CELLS}
            if skipped:
                notes.append("skipped " + ", ".join(f"{n} {k} cells" for k, n in skipped.items())
                             + " (not panels)")
            if not (kinds.get("triangle") or kinds.get("quad")):
                raise BemFileError(path, "cells", "triangle or quad panels", "none")
            if data.points.ndim != 2 or data.points.shape[1] != 3:
                raise BemFileError(path, "points", "3-D vertex coordinates",
                                   f"an array of shape {data.points.shape}")
            return load_mesh(data), notes
        mesh = load_mesh(path, file_format=fmt)
        if fmt == "gdf":
            _gdf_length_unit(path)
        return mesh, notes
    except BemFileError:
        raise
    except Exception as err:  # noqa: BLE001 - any reader failure means a malformed file
        text = str(err).strip().splitlines()[0] if str(err).strip() else ""
        raise BemFileError(path, "", f"a {fmt} mesh file capytaine can read",
                           f"{type(err).__name__}: {text}" if text else type(err).__name__) \
            from None


#: Header counts by format: (what, regular expression whose last matching group is the count).
_HEADER_COUNTS: dict[str, tuple[tuple[str, bytes], ...]] = {
    "ply": (("vertices", rb"element[ \t]+vertex[ \t]+(\d+)"),
            ("panels", rb"element[ \t]+face[ \t]+(\d+)")),
    "vtk": (("vertices", rb"\nPOINTS[ \t]+(\d+)"),
            ("panels", rb"\n(?:POLYGONS|CELLS)[ \t]+(\d+)")),
    "vtu": (("vertices", rb'NumberOfPoints="(\d+)"'), ("panels", rb'NumberOfCells="(\d+)"')),
    "gdf": (("panels", rb"\A(?:[^\n]*\n){3}[ \t]*(\d+)"),),
}


def claimed_counts(path: str, fmt: str) -> list[tuple[str, int]]:
    """The vertex and panel counts a mesh file declares in its header (or, for the formats
    without one, its panel records counted), read without loading the file: (what, count).

    A reader sizes its arrays from these counts; a header claiming 1e9 nodes asked for tens
    of GiB before anything was checked. Formats: binary and ASCII STL, OFF, Gmsh ``msh`` 2 and
    4 (ASCII or binary), PLY, legacy VTK, VTU, OBJ and GDF; others are not counted."""
    with open(path, "rb") as stream:
        try:
            data = mmap.mmap(stream.fileno(), 0, access=mmap.ACCESS_READ)
        except ValueError:  # an empty file: the reader says so
            return []
        with data:
            return _counts(data, fmt)


def _counts(data: mmap.mmap, fmt: str) -> list[tuple[str, int]]:
    size = len(data)
    if fmt == "stl":
        if data[:5].lower() == b"solid" and b"facet" in data[:1024]:
            return [("panels", _occurrences(data, b"endfacet"))]
        if size < 84:
            return []
        return [("panels", struct.unpack_from("<I", data, 80)[0])]  # 80-byte header, uint32
    if fmt == "off":
        words = re.sub(rb"#[^\n]*", b"", data[:4096]).split()
        if words and words[0].endswith(b"OFF"):
            numbers = [int(w) for w in words[1:3] if w.isdigit()]
            return list(zip(("vertices", "panels"), numbers))
        return []
    if fmt == "obj":
        return [("vertices", _occurrences(data, b"\nv ")), ("panels", _occurrences(data, b"\nf "))]
    if fmt == "msh":
        return _msh_counts(data)
    found = []
    for what, pattern in _HEADER_COUNTS.get(fmt, ()):
        match = re.search(pattern, data)
        if match:
            found.append((what, int(match.group(1))))
    return found


def _occurrences(data: mmap.mmap, needle: bytes) -> int:
    count, at = 0, data.find(needle)
    while at >= 0:
        count += 1
        at = data.find(needle, at + len(needle))
    return count


def _msh_counts(data: mmap.mmap) -> list[tuple[str, int]]:
    """Gmsh: the counts after ``$Nodes`` and ``$Elements`` (version 4 binary: size_t)."""
    header = re.search(rb"\$MeshFormat\s+(\d+)(?:\.\d+)?\s+(\d)\s+(\d+)", data)
    version, binary, width = (int(header.group(1)), header.group(2) == b"1",
                              int(header.group(3))) if header else (2, False, 8)
    found = []
    for what, section in (("vertices", b"$Nodes"), ("panels", b"$Elements")):
        at = data.find(section + b"\n")
        if at < 0:
            continue
        at += len(section) + 1
        if version >= 4 and binary and width in (4, 8):
            if at + 2 * width <= len(data):
                found.append((what, struct.unpack_from("<Q" if width == 8 else "<I", data,
                                                       at + width)[0]))
            continue
        numbers = data[at:at + 200].split(b"\n", 1)[0].split()
        if numbers:
            index = 1 if version >= 4 and len(numbers) > 1 else 0
            if numbers[index].isdigit():
                found.append((what, int(numbers[index])))
    return found


def _refuse_large_counts(path: str, fmt: str) -> None:
    """Refuse a file whose declared (or counted) panels or vertices exceed the bounds, before
    a reader allocates for them."""
    try:
        counts = claimed_counts(path, fmt)
    except OSError as err:
        raise BemFileError(path, "", "a readable mesh file", err.strerror or str(err)) from None
    for what, count in counts:
        bound = MAX_FILE_PANELS if what == "panels" else MAX_FILE_VERTICES
        if count > bound:
            raise BemFileError(path, what, f"at most {bound} {what} in the file (floatmoor."
                               f"hydro.mesh_file.MAX_FILE_{what.upper()}, from the "
                               f"{MAX_BEM_PANELS} immersed panels the dense BEM's O(N^2) "
                               "memory allows)", f"{count}")


def _unwrap(mesh) -> tuple[object, tuple[str, ...]]:
    """The innermost mesh and the case-file names of the planes a symmetric mesh flags."""
    from capytaine.meshes import ReflectionSymmetricMesh

    planes = []
    names = {v: k for k, v in CAPYTAINE_PLANES.items()}
    while isinstance(mesh, ReflectionSymmetricMesh):
        planes.append(names[mesh.plane])
        mesh = mesh.half
    return mesh, tuple(sorted(planes))


def _plain(vertices: np.ndarray, faces: np.ndarray, name: str):
    import capytaine as cpt

    return cpt.Mesh(vertices=vertices, faces=faces, name=name, auto_check=False,
                    auto_clean=False)


def _wrap(mesh, planes: tuple[str, ...], name: str):
    """``mesh`` (the positive part) as a ReflectionSymmetricMesh over ``planes`` (xz inner)."""
    import capytaine as cpt

    for plane in sorted(planes):
        mesh = cpt.ReflectionSymmetricMesh(mesh, plane=CAPYTAINE_PLANES[plane], name=name)
    return mesh


def mesh_from_file(geometry: MeshGeometry, *, lid_depth: float | None,
                   lid_panel_size: float, symmetry: bool = True,
                   water_depth: float = math.inf) -> HullMesh:
    """The immersed hull (and lid) of a mesh geometry (module docstring).

    Parameters
    ----------
    geometry
        A mesh geometry read from a case (with its resolved path).
    lid_depth
        Depth of the lid below the still water line [m], or None for no lid.
    lid_panel_size
        Target edge of the lid's panels [m] (``[hydro] panel_size``).
    symmetry
        Keep the declared symmetry planes for the BEM (``[hydro] symmetry``).
    water_depth
        The seabed's depth [m]: no panel may lie below it.

    Raises
    ------
    BemFileError
    """
    path = geometry.path
    if path is None:
        raise ValueError("a mesh geometry read from a database has no file to mesh")
    try:
        digest = file_sha256(path)
    except OSError as err:
        raise BemFileError(path, "", "a readable mesh file", err.strerror or str(err)) from None
    if digest != geometry.sha256:
        raise BemFileError(path, "", f"the file hashed when the case was loaded (SHA-256 "
                           f"{geometry.sha256[:12]}...)", f"a file changed since (SHA-256 "
                           f"{digest[:12]}...); load the case again")
    loaded, notes = read_mesh_file(path, geometry.format)
    base, flagged = _unwrap(loaded)
    declared = tuple(sorted(geometry.symmetry))
    if geometry.format in NATIVE_FORMATS and flagged != declared:
        def say(planes):
            return "symmetry " + ", ".join(planes) if planes else "no symmetry"

        raise BemFileError(path, "symmetry flags", f"the file's flags to agree with "
                           f"floater.geometry.symmetry ({say(declared)})",
                           f"{say(flagged)} flagged in the file")
    vertices = np.asarray(base.vertices, dtype=float)
    faces = np.asarray(base.faces, dtype=np.int64)
    panels_read = int(base.nb_faces)
    if len(faces) == 0:
        raise BemFileError(path, "panels", "at least one panel", "none")
    if not np.all(np.isfinite(vertices)):
        bad = int(np.sum(~np.all(np.isfinite(vertices), axis=1)))
        raise BemFileError(path, "vertices", "finite coordinates", f"{bad} vertices with NaN "
                           "or infinite coordinates")
    vertices = vertices * geometry.scale
    extent_size = float(np.ptp(vertices, axis=0).max())
    tol = _PLANE_TOLERANCE * max(extent_size, 1e-300)
    for plane in declared:
        axis = 1 if plane == "xz" else 0
        lowest = float(vertices[:, axis].min())
        if lowest < -tol:
            raise BemFileError(path, "vertices", f"the positive half {'xy'[axis]} >= 0 of the "
                               f"hull (floater.geometry.symmetry has \"{plane}\")",
                               f"vertices down to {'xy'[axis]} = {lowest:.6g} m (a full hull? "
                               "then declare no symmetry)")
    position = np.asarray(geometry.position, dtype=float)
    keep = tuple(p for p in declared if symmetry
                 and position[1 if p == "xz" else 0] == 0.0)
    for plane in declared:
        if plane not in keep and symmetry:
            notes.append(f"symmetry {plane} not used by the BEM: position moves its plane "
                         f"off {'y' if plane == 'xz' else 'x'} = 0")
    mesh = _plain(vertices, faces, "hull")
    for plane in declared:
        if plane not in keep:
            import capytaine as cpt

            mesh = cpt.Mesh.join_meshes(mesh, mesh.mirrored(CAPYTAINE_PLANES[plane]),
                                        name="hull")
    panels_full = int(mesh.nb_faces) * 2 ** len(keep)
    mesh = mesh.translated(position, name="hull")
    span = np.concatenate([vertices.min(axis=0) + position, vertices.max(axis=0) + position])
    if span[2] >= -tol:
        raise BemFileError(path, "vertices", "panels below the waterline z = 0 (after "
                           "length_unit and position)", f"none: the hull spans z = "
                           f"{span[2]:.6g} to {span[5]:.6g} m")
    clipped = mesh.clipped(origin=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), name="hull")
    cv = np.asarray(clipped.vertices, dtype=float)
    cf = np.asarray(clipped.faces, dtype=np.int64)
    on_plane = np.all(np.abs(cv[cf, 2]) <= tol, axis=1)
    if np.any(on_plane):
        notes.append(f"dropped {int(on_plane.sum()) * 2 ** len(keep)} panels lying on the "
                     "waterplane z = 0 (a deck or lid, not wetted hull)")
    cf = cf[~on_plane]
    if len(cf) == 0:
        raise BemFileError(path, "vertices", "panels below the waterline z = 0 (after "
                           "length_unit and position)", f"none: the hull spans z = "
                           f"{span[2]:.6g} to {span[5]:.6g} m")
    used = np.unique(cf)
    lowest = float(cv[used, 2].min())
    if math.isfinite(water_depth) and lowest < -water_depth - tol:
        raise BemFileError(path, "vertices", f"a hull above the seabed (z >= "
                           f"{-water_depth:g} m, environment.water_depth)",
                           f"panels down to z = {lowest:.6g} m")
    part = _plain(cv, cf, "hull")
    hull = _wrap(part, keep, "hull")
    full = hull.merged(name="hull") if keep else part
    immersed = int(full.nb_faces)
    if immersed > MAX_BEM_PANELS:
        raise BemFileError(path, "panels", f"at most {MAX_BEM_PANELS} panels below the "
                           "waterline (floatmoor.case.limits.MAX_BEM_PANELS)", f"{immersed}")
    lid = lid_full = None
    if lid_depth is not None:
        lid_full = _lid(full, path, lid_depth, lid_panel_size)
        lid = lid_full
        for plane in keep:
            normal = (0.0, -1.0, 0.0) if plane == "xz" else (-1.0, 0.0, 0.0)
            lid = lid.clipped(origin=(0.0, 0.0, 0.0), normal=normal, name="lid")
        lid = _wrap(lid, keep, "lid")
    label = "+".join(f"mirror-{CAPYTAINE_PLANES[p]}" for p in sorted(keep)) or "none"
    fv = np.asarray(full.vertices, dtype=float)
    info = MeshFileInfo(
        file=geometry.file, sha256=geometry.sha256, format=geometry.format,
        length_unit=geometry.length_unit, position=tuple(float(v) for v in position),
        symmetry_declared=declared, symmetry_used=keep, panels_read=panels_read,
        panels_full=panels_full, panels_immersed=immersed,
        panels_on_waterplane=int(on_plane.sum()) * 2 ** len(keep),
        lid_panels=0 if lid is None else int(lid.nb_faces),
        extent=tuple(float(v) for v in np.concatenate([fv.min(axis=0), fv.max(axis=0)])),
        notes=tuple(notes))
    return HullMesh(hull, lid, full, label, source=info)


def _lid(full, path: str, lid_depth: float, panel_size: float):
    """capytaine's lid of the full immersed hull at z = -lid_depth, checked not empty."""
    v = np.asarray(full.vertices, dtype=float)
    spans = np.ptp(v[:, :2], axis=0)
    estimate = math.prod(1.1 * s / panel_size + 1.0 for s in spans)
    if estimate > MAX_BEM_PANELS:
        raise BemFileError(path, "lid", f"a lid of at most {MAX_BEM_PANELS} panels "
                           "([hydro] panel_size is the lid's panel edge for a mesh hull; "
                           "floatmoor.case.limits.MAX_BEM_PANELS)",
                           f"~{estimate:.3g} panels of {panel_size:g} m")
    lid = full.generate_lid(z=-lid_depth, faces_max_radius=panel_size / math.sqrt(2.0),
                            name="lid")
    if lid.nb_faces == 0:
        raise BemFileError(path, "lid", f"an interior waterplane at z = {-lid_depth:.4g} m "
                           "for the [hydro] lid (capytaine generate_lid)", "none: no panel of "
                           "the lid lies inside the hull (set [hydro] lid = false or another "
                           "lid_depth)")
    return lid
