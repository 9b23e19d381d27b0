"""Reading of the ``[floater]`` and ``[hydro]`` tables of a case file.

``[floater]``: ``name``, ``mass`` [kg], ``centre_of_mass`` [m] and ``reference_point`` [m]
(global, body at rest; the reference point is the rotation centre of the six DOFs),
``inertia`` about the centre of mass, ``[Ixx, Iyy, Izz]`` or
``[Ixx, Iyy, Izz, Ixy, Ixz, Iyz]`` [kg m^2], ``radiation = "convolution"`` (default: K(t)
convolved with the velocity history) or ``"state-space"`` (the database's stored realisation
of K(t), ``floatmoor hydro fit-state-space``), and ``[floater.geometry]``:

* ``kind = "cylinder"``: ``diameter``, ``height`` (bottom to top) and optionally ``draft``
  [m]. Without ``draft`` the draft is the one at which the cylinder floats freely,
  ``mass / (water_density pi R^2)`` (docs/cases/cylinder_buoy.md: "the draft follows from the mass"); the
  cylinder's axis passes through the reference point.
* ``kind = "semisubmersible"``: ``[[floater.geometry.columns]]`` (``x``, ``y``, ``diameter``,
  ``z_top``, ``z_bottom``, optional ``heave_plate_diameter`` and ``heave_plate_height``, the
  plate's extent above ``z_bottom``) and optional ``[[floater.geometry.members]]`` (pontoons and
  braces: ``start``, ``end``, ``diameter``) in global coordinates.
* ``kind = "mesh"``: ``file`` (a hull mesh, relative to the case file's folder and inside it),
  optional ``format`` (one of MESH_FORMATS; default from the file's extension),
  ``length_unit`` (default ``"m"``), ``position`` [m] (added to the scaled file coordinates,
  default 0), ``symmetry`` (planes ``"xz"``/``"yz"`` the file is the positive half of,
  default none) and optional ``[[floater.geometry.columns]]`` / ``members`` as for a
  semisubmersible, used by ``[floater.drag]`` only (not meshed). The file is checked to exist
  and be readable, and hashed (SHA-256), here; it is parsed when the database is built
  (floatmoor.hydro.mesh_file). ``[floater.drag]`` needs columns or members.

Without ``[floater.geometry]`` (allowed only when ``[hydro] source = "imported"``) the floater
is its mass properties and its imported database: the hydrostatics come from the database,
nothing is checked against a hull, there is no ``[floater.drag]`` and the views draw no hull.

``[hydro]``: ``database`` (name of ``hydrodb/NAME.nc``; with ``source = "imported"`` also
a path to the ``.nc``, see :func:`floatmoor.hydro.database.database_path`), the frequencies as
``frequency_ranges = [[first, last, count], ...]`` [rad/s] and/or ``frequencies = [...]``
[rad/s], ``directions_deg`` [deg], ``panel_size`` [m], and optionally ``lid`` (default true),
``lid_depth`` [m] (default: wavenumber x depth = 0.15 at the top frequency), ``symmetry``
(default true), ``infinite_depth`` (default false: the BEM uses environment.water_depth) and
``radial_panels`` (cylinder bottom), ``drift_waterline_panel_size`` [m] (the mean drift's
mesh at the water line, ``hydro build --drift``) and ``drift_panel_size`` [m] (that mesh's
panels below, default ``panel_size``). Density and gravity come from ``[environment]``.
``accept_failed_checks = ["kernel_decay", ...]`` (default none) names database checks
(floatmoor.hydro.checks) whose failure a run of the case accepts; a run refuses a database
failing any other check. ``source`` is ``"bem"`` (default: the database is built by
``floatmoor hydro build`` from the keys above) or ``"imported"`` (made by ``floatmoor hydro
import`` from WAMIT or BEMIO files): then only ``database``, ``source`` and
``accept_failed_checks`` may be given.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatmoor.case.drag import DRAG_PRESET, PRESETS, DragSettings, MorisonCoefficients
from floatmoor.case.files import resolve_case_file
from floatmoor.case.limits import MAX_MESH_FILE_BYTES
from floatmoor.case.reader import MISSING, TableReader, _Found
from floatmoor.case.setting import read_settings, settings_of
from floatmoor.case.schema import (
    GEOMETRY_KIND, HYDRO_CHECKS, MESH_FORMATS, MESH_SYMMETRY_PLANES, BemGridKeys, Column,
    CylinderGeometry,
    Environment, Floater, FloaterGeometry, HydroSettings, Member, MeshGeometry,
    SemisubmersibleGeometry,
)
from floatmoor.file_hash import file_sha256

__all__ = ["read_floater", "read_hydro", "check_panel_size", "MAX_FREQUENCIES", "IMPORTED_HYDRO_KEYS",
           "BEM_BUILD_KEYS", "is_database_path"]

#: More frequencies than this is a typing error rather than a plan (a 400-frequency buoy
#: database took 84 s with capytaine 3.0 on one core).
MAX_FREQUENCIES = 2000


def read_floater(t: TableReader, environment: Environment,
                 base_dir: Path | None = None, *, imported: bool = False) -> Floater:
    """Read ``[floater]``; files it names (a hull mesh) are found in ``base_dir``, the case
    file's folder (default the current folder). ``imported``: the case's database is
    imported (``[hydro] source = "imported"``), so ``[floater.geometry]`` is optional (a
    drag model still needs its members)."""
    declared = settings_of(Floater)
    name = declared["name"].read(t, "name")
    mass = declared["mass"].read(t, "mass")
    com = declared["centre_of_mass"].read(t, "centre_of_mass")
    raw = t.data.get("inertia")
    size = 6 if isinstance(raw, list) and len(raw) == 6 else 3
    inertia = declared["inertia"].read(t, "inertia", size=size)
    if any(v <= 0.0 for v in inertia[:3]):
        raise t.error("inertia", "moments of inertia Ixx, Iyy, Izz > 0 [kg m^2]", list(inertia))
    full = tuple(inertia) + (0.0, 0.0, 0.0) if size == 3 else tuple(inertia)
    tensor = np.array([[full[0], full[3], full[4]], [full[3], full[1], full[5]],
                       [full[4], full[5], full[2]]])
    if np.linalg.eigvalsh(tensor).min() <= 0.0:
        raise t.error("inertia", "a positive definite inertia tensor [kg m^2]", list(inertia))
    ref = declared["reference_point"].read(t, "reference_point")
    # the weight m g and its moments about the reference point enter the equilibrium and the
    # hydrostatic stiffness: beyond double precision they are inf (and the solve a traceback)
    arm = max(1.0, *(abs(c - r) for c, r in zip(com, ref)))
    if not math.isfinite(mass * environment.gravity * arm * arm):
        key = "mass" if not math.isfinite(mass * environment.gravity) else "centre_of_mass"
        raise t.error(key, "a mass and centre of mass whose weight m g and its moments "
                      "about the reference point are finite in double precision",
                      mass if key == "mass" else list(com))
    radiation = declared["radiation"].read(t, "radiation")
    geometry = _geometry(t.table("geometry"), mass, environment, base_dir or Path(".")) \
        if t.has("geometry") or not imported else None
    drag = _drag(t.table("drag")) if t.has("drag") else None
    t.finish()
    if drag is not None and geometry is None:
        raise t.error("drag", "a [floater.geometry] whose members carry the drag (a cylinder, "
                      "or columns and members; an imported database needs no hull otherwise)",
                      _Found("a [floater.drag] table without [floater.geometry]"))
    if drag is not None and isinstance(geometry, MeshGeometry) and not (geometry.columns
                                                                        or geometry.members):
        raise t.error("drag", "Morison elements to put the drag on: [[floater.geometry."
                      "columns]] or [[floater.geometry.members]] (a mesh hull has no members "
                      "of its own)", _Found("a [floater.drag] table on a mesh hull without "
                                            "any"))
    if isinstance(geometry, CylinderGeometry) and not -geometry.draft < com[2] < \
            geometry.height - geometry.draft:
        raise t.error("centre_of_mass", "a centre of mass inside the cylinder (z between "
                      f"{-geometry.draft:.6g} and {geometry.height - geometry.draft:.6g} m)",
                      list(com))
    return Floater(name=name, mass=mass, centre_of_mass=com,  # type: ignore[arg-type]
                   inertia=full, reference_point=ref, geometry=geometry,  # type: ignore[arg-type]
                   drag=drag, radiation=radiation)


def _drag(t: TableReader) -> DragSettings:
    """``[floater.drag]``: Morison drag on the members, a ``preset``'s coefficients with the
    table's own overriding them, and the strips' discretisation (floatmoor.case.drag)."""
    preset = PRESETS[DRAG_PRESET.read(t, "preset")]
    coefficients = MorisonCoefficients(**read_settings(MorisonCoefficients, t, {
        key: getattr(preset, key) for key in settings_of(MorisonCoefficients)}))
    settings = DragSettings(coefficients=coefficients, **read_settings(DragSettings, t))
    t.finish()
    return settings


def _geometry(t: TableReader, mass: float, environment: Environment,
              base_dir: Path) -> FloaterGeometry:
    kind = GEOMETRY_KIND.read(t, "kind")
    geometry: FloaterGeometry
    if kind == "mesh":
        geometry = _mesh_geometry(t, environment, base_dir)
    elif kind == "cylinder":
        declared = settings_of(CylinderGeometry)
        diameter = declared["diameter"].read(t, "diameter")
        height = declared["height"].read(t, "height")
        draft = declared["draft"].read(t, "draft")
        from_mass = draft is None
        if draft is None:
            try:
                draft = mass / (environment.water_density * math.pi * (0.5 * diameter) ** 2)
            except (OverflowError, ZeroDivisionError):  # R^2 beyond or below a float
                draft = math.nan
            if not (math.isfinite(draft) and draft > 0.0):
                raise t.error("diameter", "a diameter at which the floater's mass gives a "
                              "finite draft > 0 (mass / (water_density pi R^2)) [m]", diameter)
            if draft >= height:
                raise t.context.error(("floater", "mass"), "a mass the cylinder can float "
                                      f"(draft from the mass below its height {height:g} m)",
                                      f"{mass!r} kg (draft {draft:.6g} m)")
        elif draft >= height:
            raise t.error("draft", f"a draft < floater.geometry.height ({height:g} m) [m]", draft)
        if draft >= environment.water_depth:
            raise t.error("draft" if not from_mass else "kind",
                          f"a cylinder whose draft is less than the water depth "
                          f"({environment.water_depth:g} m)", f"a draft of {draft:.6g} m")
        geometry = CylinderGeometry(diameter=diameter, draft=draft, height=height,
                                    draft_from_mass=from_mass)
    else:
        columns = tuple(_column(c, environment) for c in t.tables("columns"))
        members = tuple(_member(m, environment) for m in t.tables("members", min_items=0)) \
            if t.has("members") else ()
        if not any(c.z_top > 0.0 > c.z_bottom for c in columns):
            raise t.error("columns", "at least one column piercing the water line "
                          "(z_bottom < 0 < z_top)", "none")
        geometry = SemisubmersibleGeometry(columns=columns, members=members)
    t.finish()
    return geometry


def _mesh_geometry(t: TableReader, environment: Environment, base_dir: Path) -> MeshGeometry:
    """``kind = "mesh"`` (module docstring); the caller finishes the table."""
    declared = settings_of(MeshGeometry)
    name = declared["file"].read(t, "file")
    path = resolve_case_file(t, "file", base_dir, name)
    if t.has("format"):
        fmt = declared["format"].read(t, "format")
    else:
        fmt = path.suffix.lower().lstrip(".")
        if fmt not in MESH_FORMATS:
            raise t.error("file", "a mesh file whose extension names its format (one of "
                          + ", ".join(f'"{f}"' for f in MESH_FORMATS)
                          + "), or floater.geometry.format", _Found(f'"{name}"'))
    unit = declared["length_unit"].read(t, "length_unit")
    position = declared["position"].read(t, "position")
    symmetry: tuple[str, ...] = ()
    if t.has("symmetry"):
        raw = declared["symmetry"].read(t, "symmetry")
        if not isinstance(raw, list) or len(set(map(str, raw))) != len(raw) or \
                not all(isinstance(p, str) and p in MESH_SYMMETRY_PLANES for p in raw):
            raise t.error("symmetry", "an array of distinct symmetry planes among "
                          + ", ".join(f'"{p}"' for p in MESH_SYMMETRY_PLANES)
                          + " (the file holds the positive half: y >= 0 for xz, x >= 0 for "
                          "yz)", raw)
        symmetry = tuple(sorted(raw))
    columns = tuple(_column(c, environment) for c in t.tables("columns", min_items=0)) \
        if t.has("columns") else ()
    members = tuple(_member(m, environment) for m in t.tables("members", min_items=0)) \
        if t.has("members") else ()
    try:
        size = path.stat().st_size
        if size > MAX_MESH_FILE_BYTES:
            raise t.error("file", f"a mesh file of at most {MAX_MESH_FILE_BYTES} bytes "
                          "(floatmoor.case.limits.MAX_MESH_FILE_BYTES)",
                          _Found(f"{path}, {size} bytes"))
        digest = file_sha256(path)
    except OSError as err:
        raise t.error("file", "a readable mesh file",
                      _Found(f"{path} unreadable ({err.strerror})")) from None
    return MeshGeometry(file=name, sha256=digest, format=fmt, length_unit=unit,
                        position=position,  # type: ignore[arg-type]
                        symmetry=symmetry, resolved_path=str(path), morison_columns=columns,
                        morison_members=members)


def _column(t: TableReader, environment: Environment) -> Column:
    declared = settings_of(Column)
    x, y, diameter, z_top = (declared[key].read(t, key) for key in ("x", "y", "diameter",
                                                                     "z_top"))
    # bounds from the other values: above the seabed, a plate wider than the column and
    # lower than its top (the declarations word them for the reference page)
    z_bottom = declared["z_bottom"].read(t, "z_bottom", gt=-environment.water_depth, lt=z_top)
    plate = declared["heave_plate_diameter"].read(t, "heave_plate_diameter", gt=diameter)
    plate_height = declared["heave_plate_height"].read(t, "heave_plate_height",
                                                       lt=z_top - z_bottom)
    if (plate is None) != (plate_height is None):
        key = "heave_plate_height" if plate is not None else "heave_plate_diameter"
        raise t.error(key, "heave_plate_diameter and heave_plate_height given together",
                      "only one of them")
    t.finish()
    return Column(x=x, y=y, diameter=diameter, z_top=z_top, z_bottom=z_bottom,
                  heave_plate_diameter=plate, heave_plate_height=plate_height or 0.0)


def _member(t: TableReader, environment: Environment) -> Member:
    start, end, diameter = read_settings(Member, t).values()
    length = float(np.linalg.norm(np.subtract(end, start)))
    if length <= diameter:
        raise t.error("end", f"an end point more than one diameter ({diameter:g} m) from "
                      "start [m]", list(end))
    for key, point in (("start", start), ("end", end)):
        if point[2] < -environment.water_depth:
            raise t.error(key, "a point above the seabed [m]", list(point))
    t.finish()
    return Member(start=start, end=end, diameter=diameter)  # type: ignore[arg-type]


#: The keys of ``[hydro]`` a case with ``source = "imported"`` may give; the others are BEM
#: build settings (``floatmoor hydro build``).
IMPORTED_HYDRO_KEYS = ("database", "source", "accept_failed_checks")


#: The keys of ``[hydro]`` that only a built database takes (a ``[hydro]`` without any of
#: them and without ``source`` has probably forgotten ``source = "imported"``).
BEM_BUILD_KEYS = ("frequency_ranges", "frequencies", "directions_deg", "panel_size", "lid",
                  "lid_depth", "infinite_depth", "symmetry", "radial_panels",
                  "drift_waterline_panel_size", "drift_panel_size")


def _is_name(text: str) -> bool:
    """A database name (``hydrodb/NAME.nc``): letters, digits, '-', '_' and '.'."""
    return bool(text) and all(ch.isalnum() or ch in "-_." for ch in text) \
        and not text.startswith(".")


def is_database_path(text: str) -> bool:
    """``[hydro] database`` names a file by path (a ``/`` in it, or ending in ``.nc``)
    rather than ``hydrodb/NAME.nc`` by name."""
    return "/" in text or "\\" in text or text.endswith(".nc")


def read_hydro(t: TableReader) -> HydroSettings:
    """Read ``[hydro]``."""
    declared = settings_of(HydroSettings)
    database = declared["database"].read(t, "database")
    source = declared["source"].read(t, "source")
    if source == "imported":
        if not (_is_name(database) or (is_database_path(database)
                                       and database.endswith(".nc")
                                       and database.isprintable())):
            raise t.error("database", "a database name (hydrodb/NAME.nc: letters, digits, "
                          "'-', '_' and '.') or the path of the .nc file 'floatmoor hydro "
                          "import' made, relative to the case file's folder", database)
        return _imported_hydro(t, database)
    if not t.has("source") and not any(t.has(key) for key in BEM_BUILD_KEYS):
        raise t.error("source", 'source = "imported" for a database made by \'floatmoor '
                      'hydro import\' (probably missing: [hydro] gives no BEM build key), or '
                      "the BEM build keys (frequency_ranges or frequencies, directions_deg, "
                      "panel_size) for 'floatmoor hydro build'", MISSING)
    if not _is_name(database):
        raise t.error("database", "a file name of letters, digits, '-', '_' and '.' (a path "
                      "to a .nc file only with source = \"imported\")", database)
    grid = settings_of(BemGridKeys)
    omegas: list[float] = []
    if t.has("frequency_ranges"):
        ranges = grid["frequency_ranges"].read(t, "frequency_ranges")
        expected = "an array of [first, last, count] triples with 0 < first < last [rad/s] " \
                   "and count >= 2"
        if not isinstance(ranges, list) or not ranges:
            raise t.error("frequency_ranges", expected, ranges)
        for i, item in enumerate(ranges):
            ok = (isinstance(item, list) and len(item) == 3
                  and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                          and math.isfinite(v) for v in item)
                  and isinstance(item[2], int) and 0 < item[0] < item[1] and item[2] >= 2)
            if not ok:
                raise t.error(("frequency_ranges", i), expected, item)
            if item[2] > MAX_FREQUENCIES:  # checked before the frequencies are generated
                raise t.error(("frequency_ranges", i, 2), f"a count of at most "
                              f"{MAX_FREQUENCIES} frequencies", item[2])
            omegas.extend(np.linspace(float(item[0]), float(item[1]), int(item[2])).tolist())
    if t.has("frequencies"):
        raw = t.data["frequencies"]
        size = len(raw) if isinstance(raw, list) and raw else 1
        omegas.extend(grid["frequencies"].read(t, "frequencies", size=size))
    if not omegas:
        raise t.error("frequency_ranges", "frequency_ranges or frequencies (at least 2 "
                      "frequencies) [rad/s]", t.data.get("frequency_ranges", None)
                      if t.has("frequency_ranges") else MISSING)
    values = np.unique(np.round(np.asarray(omegas, float), 12))
    if len(values) < 2 or len(values) > MAX_FREQUENCIES:
        raise t.error("frequency_ranges", f"between 2 and {MAX_FREQUENCIES} distinct "
                      "frequencies [rad/s]", f"{len(values)}")
    raw_dir = t.data.get("directions_deg")
    size = len(raw_dir) if isinstance(raw_dir, list) and raw_dir else 1
    directions_deg = grid["directions_deg"].read(t, "directions_deg", size=size)
    if any(not -360.0 <= d <= 360.0 for d in directions_deg) or \
            len(set(directions_deg)) != len(directions_deg) or \
            list(directions_deg) != sorted(directions_deg):
        raise t.error("directions_deg", "distinct increasing directions within [-360, 360] "
                      "[deg]", list(directions_deg))
    settings = HydroSettings(
        database=database,
        frequencies=tuple(float(v) for v in values),
        directions=tuple(math.radians(d) for d in directions_deg),
        **read_settings(HydroSettings, t, skip=("database", "source", "accept_failed_checks")),
        accept_failed_checks=_accepted_checks(t),
    )
    t.finish()
    return settings


def _imported_hydro(t: TableReader, database: str) -> HydroSettings:
    """``[hydro]`` of a database made by ``floatmoor hydro import``: no BEM build keys."""
    for key in t.data:
        if key not in IMPORTED_HYDRO_KEYS:
            raise t.error(key, 'no BEM build settings with source = "imported" (they belong to '
                          "'floatmoor hydro build'; an imported database is made by 'floatmoor "
                          "hydro import'): only " + ", ".join(IMPORTED_HYDRO_KEYS),
                          t.data[key])
    settings = HydroSettings(database=database, frequencies=(), directions=(), panel_size=None,
                             lid=False, lid_depth=None, infinite_depth=False, symmetry=False,
                             accept_failed_checks=_accepted_checks(t), source="imported")
    t.finish()
    return settings


def _accepted_checks(t: TableReader) -> tuple[str, ...]:
    """``accept_failed_checks``: distinct names of database checks (default none)."""
    if not t.has("accept_failed_checks"):
        return ()
    raw = settings_of(HydroSettings)["accept_failed_checks"].read(t, "accept_failed_checks")
    if not isinstance(raw, list) or len(set(map(str, raw))) != len(raw) or \
            not all(isinstance(name, str) and name in HYDRO_CHECKS for name in raw):
        raise t.error("accept_failed_checks", "an array of distinct database check names "
                      "among " + ", ".join(f'"{name}"' for name in HYDRO_CHECKS), raw)
    return tuple(raw)


def check_panel_size(floater: Floater, hydro: HydroSettings, error) -> None:
    """``[hydro] panel_size`` is required to mesh a parametric hull and, for a mesh file, to
    panel its lid; a mesh hull without a lid needs none. ``error(key, expected, found)``
    raises the loader's CaseError."""
    if hydro.source != "bem" or hydro.panel_size is not None:
        return
    if floater.geometry.kind == "mesh" and not hydro.lid:
        return
    what = "the lid's panel edge of a mesh hull" if floater.geometry.kind == "mesh" \
        else "the hull's target panel edge"
    from floatmoor.case.reader import describe_value

    error("panel_size", f"a panel size [m] ({what})", describe_value(MISSING))

