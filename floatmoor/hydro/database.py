"""Hydrodynamic databases on disk: ``hydrodb/NAME.nc``.

A database is a netCDF-3 file (written atomically with :func:`floatmoor.io.netcdf.write_dataset`)
in capytaine's dataset layout: variables ``added_mass`` and ``radiation_damping`` over
(omega, radiating_dof, influenced_dof), ``excitation_force``, ``Froude_Krylov_force`` and
``diffraction_force`` over (complex, omega, wave_direction, influenced_dof) with complex values
split along a ``complex`` dimension (``re``, ``im``) as capytaine's ``separate_complex_values``
does, ``hydrostatic_stiffness`` (buoyancy part, see :mod:`floatmoor.hydro.build`),
``added_mass_infinite`` (and ``added_mass_zero`` in deep water). Attributes record the
floatmoor and capytaine versions, creation time, case text, geometry, mesh panel counts and
hash, water depth, density, gravity, build settings and build time, and ``inputs_hash``: the
SHA-256 of every input that changes the result (:func:`database_inputs`).

Imported databases (``floatmoor hydro import``, :mod:`floatmoor.hydro.importing`) keep the
layout; they record where their data came from instead of a case (attribute ``source``:
``"wamit"`` or ``"bemio"``; a built database says ``"capytaine"``, and a file without the
attribute is a built one), and hold the excitation group (``excitation_force`` alone, or with
its ``Froude_Krylov_force`` and ``diffraction_force`` parts) only when their files give it.
A case uses one with ``[hydro] source = "imported"``; it is up to date when its recorded
water density, gravity, rotation centre and (finite-depth files) water depth equal the case's
and its source files, where present, have their recorded SHA-256 (:func:`stale_keys`).

A database is used for a case only when its recorded inputs equal the case's and it passes
the checks of :mod:`floatmoor.hydro.checks` (:func:`load_for_case`); a missing, truncated or
otherwise unreadable file, one whose contents fail the structural checks, a stale one, or one
failing a check the case does not accept (``[hydro] accept_failed_checks``) raises
:class:`HydroDatabaseError` naming the problem. The checks are recomputed at every load (once
per file version and process; ~0.3-0.8 s on the shipped databases), never trusted from the
file: a database whose values were edited with its recorded inputs kept is checked as it is.
The results recorded by ``floatmoor hydro build`` (attributes ``checks_failed``,
``checks_json``) are for the reader only.

A database is data from elsewhere (docs/guide/safeguards.md#files-from-elsewhere): it must be a
regular netCDF classic file of at most :data:`MAX_DATABASE_BYTES`; the files it records
(source files, case file) are looked for only inside its own project (:func:`project_folder`)
and a source file is read only when it has its recorded size (:func:`located_source_file`);
recorded text reaches a message only through :func:`floatmoor.terminal_text.shown`, and a
recorded command is never offered as advice (:data:`REIMPORT_ADVICE`).

Size: the layout, the structural read, the staleness rules and the reading of what a database
records share :class:`HydroDatabaseError` and the attribute conventions; split, each part would
import the others.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import hashlib
import json
import math
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import xarray as xr

from floatmoor._version import __version__
from floatmoor.case.schema import Case, Environment, Floater, HydroSettings
from floatmoor.errors import FloatmoorError
from floatmoor.file_hash import file_sha256
from floatmoor.hydro.complex_values import merge_complex
from floatmoor.input_files import InputFileError, open_regular, regular_file_size
from floatmoor.io.netcdf import read_dataset, write_dataset
from floatmoor.terminal_text import shown

if TYPE_CHECKING:
    from floatmoor.hydro.build import Progress

__all__ = [
    "HydroDatabaseError", "database_inputs", "inputs_hash", "to_dataset", "build_database",
    "write_database",
    "read_database", "load_for_case", "database_path", "merge_complex", "REQUIRED_VARIABLES",
    "capytaine_major", "EXCITATION_VARIABLES", "DATABASE_SOURCES", "database_source",
    "is_imported", "has_excitation", "labelled_variable", "database_coords", "stale_keys",
    "stale_message", "source_mismatch", "file_sha256", "source_files", "located_source_file",
    "changed_source_files", "REIMPORT_ADVICE", "MAX_DATABASE_BYTES", "project_folder",
    "inside_project", "recorded_json", "database_file_name", "IMPORT_ADVICE",
]

#: Largest database file read [bytes]: the shipped ones are 0.1-0.3 MB and a database of 2000
#: frequencies (the case limit) and 360 directions holds ~100 MB; a netCDF classic file is not
#: compressed, so this bounds the memory a load takes whatever its header declares.
MAX_DATABASE_BYTES = 2**30
#: The leading bytes of a netCDF classic file (CDF-1, CDF-2 64-bit offset; CDF-5 is read by
#: no engine floatmoor has) and of an HDF5 (netCDF-4) file.
_NETCDF_CLASSIC_MAGIC = (b"CDF\x01", b"CDF\x02")
_HDF5_MAGIC = b"\x89HDF"
#: What to do with an imported database that is stale, in floatmoor's own words: the command
#: recorded in a database is the file's text, never offered to be run.
REIMPORT_ADVICE = ("re-import it with 'floatmoor hydro import FILE... -o PATH.nc --force' (the "
                   "files and options 'floatmoor hydro info' lists, with the case's values)")

#: Variables every database holds.
REQUIRED_VARIABLES = ("added_mass", "radiation_damping", "added_mass_infinite",
                      "hydrostatic_stiffness", "disp_volume", "center_of_buoyancy",
                      "rotation_center", "waterplane_area")
#: The excitation group: the total wave excitation, and its Froude-Krylov and diffraction
#: parts. A built database holds all three; an imported one holds them as its files give
#: them (none, the total only, or all three); the parts never without the total, nor one
#: part without the other.
EXCITATION_VARIABLES = ("excitation_force", "Froude_Krylov_force", "diffraction_force")
#: Where a database's data come from (attribute ``source``; a file without it was built by
#: capytaine): ``floatmoor hydro build`` or ``floatmoor hydro import``.
DATABASE_SOURCES = ("capytaine", "wamit", "bemio")

_ATTRS: dict[str, dict[str, str]] = {
    "omega": {"long_name": "wave angular frequency", "units": "rad/s"},
    "period": {"long_name": "wave period", "units": "s"},
    "wavenumber": {"long_name": "wavenumber at the BEM water depth", "units": "rad/m"},
    "wave_direction": {"long_name": "direction the waves travel towards, from +x "
                       "counter-clockwise", "units": "rad"},
    "radiating_dof": {"long_name": "degree of freedom of the motion", "units": "1"},
    "influenced_dof": {"long_name": "degree of freedom of the force", "units": "1"},
    "complex": {"long_name": "real and imaginary parts (e^{-i omega t} convention)",
                "units": "1"},
    "component": {"long_name": "global axis", "units": "1"},
    "added_mass": {"long_name": "added mass (kg, kg m, kg m^2 by DOF pair)", "units": "kg"},
    "radiation_damping": {"long_name": "radiation damping (N s/m, N s, N m s by DOF pair)",
                          "units": "kg/s"},
    "excitation_force": {"long_name": "wave excitation force per unit wave amplitude "
                         "(Froude-Krylov + diffraction; N/m or N m/m)", "units": "N/m"},
    "Froude_Krylov_force": {"long_name": "Froude-Krylov force per unit wave amplitude",
                            "units": "N/m"},
    "diffraction_force": {"long_name": "diffraction force per unit wave amplitude",
                          "units": "N/m"},
    "added_mass_infinite": {"long_name": "added mass at omega = infinity", "units": "kg"},
    "added_mass_zero": {"long_name": "added mass at omega = 0 (built: deep water only)",
                        "units": "kg"},
    "hydrostatic_stiffness": {"long_name": "hydrostatic stiffness of the hull (buoyancy "
                              "only, centre of mass taken at the rotation centre; N/m, N, "
                              "N m by DOF pair)", "units": "N/m"},
    "disp_volume": {"long_name": "displaced volume of the hull mesh", "units": "m^3"},
    "waterplane_area": {"long_name": "waterplane area of the hull mesh", "units": "m^2"},
    "center_of_buoyancy": {"long_name": "centre of buoyancy of the hull mesh", "units": "m"},
    "rotation_center": {"long_name": "rotation centre of the rigid-body DOFs (the floater's "
                        "reference point)", "units": "m"},
}

DOF_DEFINITION = ("Surge, Sway, Heave: translations along global x, y, z; Roll, Pitch, Yaw: "
                  "rotations about axes parallel to x, y, z through rotation_center "
                  "(capytaine rigid_body_dofs)")


class HydroDatabaseError(FloatmoorError):
    """A hydrodynamic database is missing, damaged or stale for the case that asks for it."""


def database_source(ds: xr.Dataset) -> str:
    """``"capytaine"`` (built; also a file without the ``source`` attribute, written before
    it was recorded), ``"wamit"`` or ``"bemio"`` (imported)."""
    return str(ds.attrs.get("source", "capytaine"))


def is_imported(ds: xr.Dataset) -> bool:
    """Whether the database was made by ``floatmoor hydro import``."""
    return database_source(ds) != "capytaine"


def has_excitation(ds: xr.Dataset) -> bool:
    """Whether the database holds wave excitation forces."""
    return "excitation_force" in ds.variables


def capytaine_major() -> int:
    """Major version of the installed capytaine, from its package metadata: every run of a
    floater case asks it (:func:`stale_keys`), and importing capytaine for it cost a run
    35 MB of memory and a second."""
    from importlib.metadata import version

    return int(version("capytaine").split(".")[0])


def database_inputs(floater: Floater, hydro: HydroSettings,
                    environment: Environment) -> dict[str, Any]:
    """Every input that changes the BEM result, as JSON-ready values.

    For ``[hydro] source = "imported"`` the case's values an imported database must have been
    imported with: reference point, water density, gravity and water depth (the last only
    against a finite-depth file; :func:`stale_keys`).
    """
    from floatmoor.hydro.build import BEM_METHOD

    if hydro.source == "imported":
        return {
            "source": "imported",
            "reference_point": [float(v) for v in floater.reference_point],
            "water_density": environment.water_density,
            "gravity": environment.gravity,
            "water_depth": environment.water_depth,
        }
    geometry = dataclasses.asdict(floater.geometry)
    geometry.pop("draft_from_mass", None)
    return {
        "geometry": geometry,
        "reference_point": list(floater.reference_point),
        "panel_size": hydro.panel_size,
        "radial_panels": hydro.radial_panels,
        "lid": hydro.lid,
        "lid_depth": hydro.lid_depth,
        "symmetry": hydro.symmetry,
        "frequencies": [round(w, 12) for w in hydro.frequencies],
        "directions": [round(b, 12) for b in hydro.directions],
        "water_depth": "infinite" if hydro.infinite_depth else environment.water_depth,
        "water_density": environment.water_density,
        "gravity": environment.gravity,
        "capytaine_major": capytaine_major(),
        "bem_method": BEM_METHOD,
    }


def inputs_hash(inputs: dict[str, Any]) -> str:
    """SHA-256 of the canonical JSON of :func:`database_inputs`."""
    text = json.dumps(inputs, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def _split_complex(da: xr.DataArray, name: str) -> xr.DataArray:
    return labelled_variable(name, da.values, da.dims)


def labelled_variable(name: str, values: Any, dims: tuple[str, ...]) -> xr.DataArray:
    """Database variable ``name`` with its ``units`` and ``long_name``; complex values split
    along a leading ``complex`` dimension (``re``, ``im``)."""
    values = np.asarray(values)
    if np.iscomplexobj(values):
        out = xr.DataArray(np.stack([values.real, values.imag]), dims=("complex",) + tuple(dims))
    else:
        out = xr.DataArray(values, dims=tuple(dims))
    out.attrs.update(_ATTRS[name])
    return out


def database_coords(omega: Any, depth: float, gravity: float,
                    directions: Any | None) -> dict[str, tuple]:
    """The coordinates of a database: frequencies with their periods and wavenumbers at the
    BEM depth (``inf``: deep water), DOFs, components, and (``directions`` not None) wave
    directions and the complex parts."""
    from floatmoor.hydro.build import DOFS, wavenumber

    omega = np.asarray(omega, float)
    coords: dict[str, tuple] = {
        "omega": ("omega", omega, _ATTRS["omega"]),
        "period": ("omega", 2.0 * np.pi / omega, _ATTRS["period"]),
        "wavenumber": ("omega", np.array([wavenumber(w, depth, gravity) for w in omega]),
                       _ATTRS["wavenumber"]),
        "radiating_dof": ("radiating_dof", np.array(DOFS), _ATTRS["radiating_dof"]),
        "influenced_dof": ("influenced_dof", np.array(DOFS), _ATTRS["influenced_dof"]),
        "component": ("component", np.array(["x", "y", "z"]), _ATTRS["component"]),
    }
    if directions is not None:
        coords["wave_direction"] = ("wave_direction", np.asarray(directions, float),
                                    _ATTRS["wave_direction"])
        coords["complex"] = ("complex", np.array(["re", "im"]), _ATTRS["complex"])
    return coords


def to_dataset(result, case: Case) -> xr.Dataset:
    """Label a :class:`~floatmoor.hydro.build.BemResult` of ``case`` as a database dataset."""
    import capytaine

    from floatmoor.hydro.build import bem_dataset_arrays
    from floatmoor.hydro.geometry import mesh_hash

    floater, hydro, env = case.floater, case.hydro, case.environment
    assert floater is not None and hydro is not None
    arrays = bem_dataset_arrays(result)
    data_vars = {name: _split_complex(da, name) for name, da in arrays.items()}
    hs = result.hydrostatics
    data_vars["disp_volume"] = xr.DataArray(hs["disp_volume"], attrs=_ATTRS["disp_volume"])
    data_vars["waterplane_area"] = xr.DataArray(hs["waterplane_area"],
                                                attrs=_ATTRS["waterplane_area"])
    data_vars["center_of_buoyancy"] = xr.DataArray(hs["center_of_buoyancy"], dims=("component",),
                                                   attrs=_ATTRS["center_of_buoyancy"])
    data_vars["rotation_center"] = xr.DataArray(np.asarray(floater.reference_point, float),
                                                dims=("component",),
                                                attrs=_ATTRS["rotation_center"])
    depth = result.bem_depth
    coords = database_coords(result.omega, depth, env.gravity, result.directions)
    inputs = database_inputs(floater, hydro, env)
    mesh = result.mesh
    attrs: dict[str, Any] = {
        "title": f"floatmoor hydrodynamic database {hydro.database} ({case.title})",
        "database": hydro.database,
        "source": "capytaine",
        "added_mass_infinite_source": "capytaine (omega = infinity solved)",
        "floater": floater.name,
        "geometry_kind": floater.geometry.kind,
        "geometry_json": json.dumps(inputs["geometry"], sort_keys=True),
        "case_file": case.source,
        "case_toml": case.text,
        "floatmoor_version": __version__,
        "capytaine_version": capytaine.__version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "water_depth": env.water_depth,
        "bem_water_depth": "infinite" if not math.isfinite(depth) else f"{depth!r}",
        "water_density": env.water_density,
        "gravity": env.gravity,
        "hull_panels": int(mesh.hull_panels),
        "lid_panels": int(mesh.lid_panels),
        "mesh_symmetry": mesh.symmetry,
        "mesh_hash": mesh_hash(mesh.full_hull),
        "panel_size": hydro.panel_size if hydro.panel_size is not None else "none",
        "lid_depth": result.lid_depth if result.lid_depth is not None else "none",
        "build_seconds": float(result.build_seconds),
        "build_settings_json": json.dumps({k: inputs[k] for k in
                                           ("panel_size", "radial_panels", "lid", "lid_depth",
                                            "symmetry", "water_depth", "bem_method")},
                                          sort_keys=True),
        "inputs_json": json.dumps(inputs, sort_keys=True),
        "inputs_hash": inputs_hash(inputs),
        "dof_definition": DOF_DEFINITION,
        "time_convention": "e^{-i omega t} (capytaine); WAMIT phases are the conjugate",
        "Conventions": "CF-1.8",
    }
    if mesh.source is not None:  # a hull read from a file: what it was and what its checks found
        attrs["mesh_file_json"] = json.dumps(mesh.source.as_dict(), sort_keys=True)
        attrs["mesh_checks_json"] = json.dumps([c.as_dict() for c in result.mesh_checks])
        attrs["mesh_reference_json"] = json.dumps(result.mesh_reference, sort_keys=True)
    return xr.Dataset(data_vars=data_vars, coords=coords, attrs=attrs)


def build_database(case, *, progress: Progress | None = None) -> xr.Dataset:
    """Run the BEM for a case with ``[floater]`` and ``[hydro]`` and label the result as a
    database dataset (:func:`to_dataset`).

    Parameters
    ----------
    case
        The case (its ``[floater]``, ``[hydro]`` and environment).
    progress
        Called after each frequency (:func:`floatmoor.hydro.build.run_bem`).

    Returns
    -------
    xarray.Dataset
        The database, ready for :func:`write_database`.
    """
    from floatmoor.hydro.build import run_bem

    if case.floater is None or case.hydro is None:
        raise ValueError(f"{case.source}: a case with [floater] and [hydro] tables is needed")
    result = run_bem(case.floater, case.hydro, case.environment, progress=progress)
    return to_dataset(result, case)


def write_database(dataset: xr.Dataset, path: str | os.PathLike[str]) -> None:
    """Write atomically (the folder is created if missing). The ``path`` attribute that
    :func:`read_database` sets (where this process read it from) is not written: a file
    carries no path of the machine it was made on.

    Parameters
    ----------
    dataset
        The database (:func:`build_database`, :func:`read_database`).
    path
        The file to write.
    """
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    if "path" in dataset.attrs:
        dataset = dataset.copy()
        dataset.attrs = {k: v for k, v in dataset.attrs.items() if k != "path"}
    write_dataset(dataset, path)


def read_database(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read and structurally check a database.

    Parameters
    ----------
    path
        The database file (``hydrodb/NAME.nc``).

    Returns
    -------
    xarray.Dataset
        The database, read into memory, with its ``path`` attribute set to ``path``.

    Raises
    ------
    HydroDatabaseError
        Missing or unreadable file, missing variables, wrong shapes or non-finite values.
    """
    p = Path(path)
    try:
        with open_regular(p, MAX_DATABASE_BYTES) as stream:
            magic = stream.read(4)
    except InputFileError as err:
        if err.found == "no such file":
            raise HydroDatabaseError(f"{p}: no hydrodynamic database (build it with "
                                     "'floatmoor hydro build CASE', or import one with "
                                     "'floatmoor hydro import')") from None
        raise HydroDatabaseError(f"{p}: expected a hydrodynamic database (a regular netCDF "
                                 f"file of at most {MAX_DATABASE_BYTES} bytes), found "
                                 f"{err.found}") from None
    if magic not in _NETCDF_CLASSIC_MAGIC:
        found = ("a netCDF-4 / HDF5 file (floatmoor's databases are netCDF classic)"
                 if magic == _HDF5_MAGIC else "not a netCDF file")
        raise HydroDatabaseError(f"{p}: expected a hydrodynamic database (a netCDF classic "
                                 f"file), found {found}")
    try:
        ds = read_dataset(p)
    except Exception as err:  # noqa: BLE001 - any reader failure means a damaged file
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, not readable as "
                                 f"netCDF ({type(err).__name__}: {shown(err, 200)})") from None
    source = ds.attrs.get("source", "capytaine")
    if not isinstance(source, str) or source not in DATABASE_SOURCES:
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, expected a source "
                                 f"attribute among {', '.join(DATABASE_SOURCES)}, found "
                                 f"'{shown(source, 80)}'")
    missing = [v for v in REQUIRED_VARIABLES if v not in ds.variables]
    if missing or "inputs_hash" not in ds.attrs:
        what = ", ".join(missing) if missing else "the inputs_hash attribute"
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, missing {what}")
    n_w = ds.sizes.get("omega", 0)
    if n_w < 2 or ds.sizes.get("radiating_dof") != 6 or ds.sizes.get("influenced_dof") != 6:
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, expected >= 2 "
                                 "frequencies and 6 x 6 DOFs")
    held = [v for v in EXCITATION_VARIABLES if v in ds.variables]
    if held and (held[0] != "excitation_force" or len(held) == 2):
        lacking = [v for v in EXCITATION_VARIABLES if v not in held]
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, partial excitation "
                                 f"forces: {', '.join(held)} without {', '.join(lacking)}")
    for name in REQUIRED_VARIABLES + tuple(held):
        values = np.asarray(ds[name].values, dtype=float)
        if not np.all(np.isfinite(values)):
            raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, non-finite values "
                                     f"in {name}")
    omega = ds["omega"].values
    if np.any(np.diff(omega) <= 0) or omega[0] <= 0:
        raise HydroDatabaseError(f"{p}: damaged hydrodynamic database, frequencies not "
                                 "positive and increasing")
    ds.attrs["path"] = str(p)
    return ds


def database_path(case: Case) -> Path:
    """The case's database file (docs/guide/hydro_databases.md#naming-the-database).

    ``[hydro] database`` is a name or, with ``source = "imported"``, may be a path (a ``/``
    in it, or ending in ``.nc``: :func:`floatmoor.case.floater.is_database_path`): a path
    is relative to the case file's folder (absolute allowed); a name is ``hydrodb/NAME.nc``
    in the nearest folder above the case file that has a ``hydrodb`` folder (the repository
    root for the shipped cases), else in the current folder.

    Parameters
    ----------
    case
        The case (its ``[hydro] database`` and the case file's folder).

    Returns
    -------
    pathlib.Path
        The database file (it need not exist).
    """
    from floatmoor.case.floater import is_database_path

    assert case.hydro is not None
    if case.hydro.source == "imported" and is_database_path(case.hydro.database):
        given = Path(case.hydro.database)
        return given if given.is_absolute() else Path(case.source).parent / given
    name = f"{case.hydro.database}.nc"
    for parent in Path(case.source).resolve().parents:
        if (parent / "hydrodb").is_dir():
            return parent / "hydrodb" / name
    return Path("hydrodb") / name


def database_file_name(hydro: HydroSettings) -> str:
    """The file name of ``hydro``'s database (``NAME.nc``, or the last part of its path)."""
    from floatmoor.case.floater import is_database_path

    if hydro.source == "imported" and is_database_path(hydro.database):
        return Path(hydro.database).name
    return f"{hydro.database}.nc"


#: What to do about a missing imported database (a case cannot build one).
IMPORT_ADVICE = ("import it with 'floatmoor hydro import FILE... -o PATH.nc' (WAMIT .1 .hst "
                 "[.3] [.out], or a BEMIO .h5) and name that PATH.nc in [hydro] database, "
                 "relative to the case file")


def source_mismatch(ds: xr.Dataset, case: Case) -> str | None:
    """Why ``case`` cannot use ``ds`` whatever its values (None when it can): a case whose
    database is built (``[hydro] source = "bem"``) naming an imported one, or the reverse."""
    assert case.hydro is not None
    where = ds.attrs.get("path", case.hydro.database)
    if case.hydro.source == "bem" and is_imported(ds):
        return (f"{where}: imported from {database_source(ds)} files ('floatmoor hydro import'), "
                f"but {case.source} builds its database ([hydro] source = \"bem\"): set [hydro] "
                "source = \"imported\" (without the BEM build keys), or name another database")
    if case.hydro.source == "imported" and not is_imported(ds):
        return (f"{where}: built by capytaine ('floatmoor hydro build'), but {case.source} "
                "names an imported database ([hydro] source = \"imported\"): import one with "
                "'floatmoor hydro import', or set [hydro] source = \"bem\" with the BEM build keys")
    return None


def recorded_json(ds: xr.Dataset, name: str, default: Any) -> Any:
    """The JSON value of attribute ``name`` (``default`` when absent).

    Raises
    ------
    HydroDatabaseError
        The attribute is not JSON Python can read (also 5000-digit integers, which Python
        refuses to convert, and nesting deeper than its recursion limit).
    """
    if name not in ds.attrs:
        return default
    try:
        return json.loads(str(ds.attrs[name]))
    except (ValueError, RecursionError) as err:
        raise HydroDatabaseError(f"{ds.attrs.get('path', 'database')}: damaged hydrodynamic "
                                 f"database, attribute {name} is not readable JSON "
                                 f"({shown(err, 120)})") from None


def source_files(ds: xr.Dataset) -> list[dict[str, Any]]:
    """The source files an imported database records: ``path`` (as given to ``floatmoor hydro
    import``), ``sha256``, ``size`` [bytes], and ``project_path`` for a file inside the
    database's project (empty for a built database); records that are not JSON objects are
    left out."""
    files = recorded_json(ds, "source_files_json", [])
    return [f for f in files if isinstance(f, dict)] if isinstance(files, list) else []


def project_folder(database: str | os.PathLike[str]) -> Path:
    """The project a database belongs to: the folder above its ``hydrodb/`` folder, or the
    database's own folder when that folder has another name (resolved)."""
    folder = Path(database).resolve().parent
    return folder.parent if folder.name == "hydrodb" else folder


def inside_project(ds: xr.Dataset, recorded: Any) -> Path | None:
    """The path a database records (relative to its project, or absolute) resolved, if it
    lies inside the database's project (:func:`project_folder`); None otherwise (also for a
    database read from no file)."""
    if "path" not in ds.attrs or not isinstance(recorded, str) or not recorded \
            or "\x00" in recorded:
        return None
    project = project_folder(ds.attrs["path"])
    try:
        candidate = (project / recorded).resolve()
    except (OSError, RuntimeError, ValueError):  # a symbolic-link loop, an odd name
        return None
    return candidate if candidate.is_relative_to(project) else None


def _recorded_size(record: dict[str, Any]) -> int | None:
    size = record.get("size")
    return size if isinstance(size, int) and not isinstance(size, bool) and size >= 0 else None


def located_source_file(ds: xr.Dataset, record: dict[str, Any]) -> Path | None:
    """Where a recorded source file is now, only ever inside the database's project
    (:func:`inside_project`): its ``project_path`` there when recorded, else its ``path`` as
    given when that lies inside; None when it is not there as a regular file (a recorded path
    leading out of the project, to a FIFO or a device is never looked at further)."""
    candidate = inside_project(ds, record.get("project_path") or record.get("path"))
    if candidate is None:
        return None
    try:
        regular_file_size(candidate)
    except InputFileError:
        return None
    return candidate


def changed_source_files(ds: xr.Dataset) -> list[str]:
    """The recorded source files present in the project (:func:`located_source_file`) that
    changed since the import: another size than the recorded one (not read), or the recorded
    size and another SHA-256 (missing files cannot be checked and are not listed)."""
    changed = []
    for record in source_files(ds):
        found = located_source_file(ds, record)
        size = _recorded_size(record)
        if found is None or size is None:
            continue
        try:
            same = found.stat().st_size == size and file_sha256(found, size) == record.get(
                "sha256")
        except OSError:  # gone, or replaced by another kind of file, since it was located
            continue
        if not same:
            changed.append(shown(record.get("path"), 200))
    return changed


def _imported_stale_keys(ds: xr.Dataset, case: Case) -> list[str]:
    """The case's values an imported database differs in (with both values), and its changed
    source files."""
    assert case.floater is not None
    env = case.environment
    out = []

    def differs(name: str, recorded: Any, wanted: float) -> None:
        try:
            same = math.isclose(float(recorded), float(wanted), rel_tol=1e-12, abs_tol=1e-12)
        except (TypeError, ValueError):
            same = False
        if not same:
            out.append(f"{name} (database {shown(recorded, 40)}, case {wanted!r})")

    differs("water_density", ds.attrs.get("water_density"), env.water_density)
    differs("gravity", ds.attrs.get("gravity"), env.gravity)
    rc = np.asarray(ds["rotation_center"].values, float)
    if not np.allclose(rc, case.floater.reference_point, rtol=0.0, atol=1e-9):
        out.append(f"reference_point (database {rc.tolist()}, case "
                   f"{list(case.floater.reference_point)})")
    depth = ds.attrs.get("bem_water_depth", "")
    if depth != "infinite":
        differs("water_depth", depth, env.water_depth)
    out.extend(f"source file {name} (changed since the import: SHA-256 differs)"
               for name in changed_source_files(ds))
    return out


def stale_keys(ds: xr.Dataset, case: Case) -> list[str]:
    """Input keys whose recorded values differ from the case's (empty when up to date).

    An imported database (``[hydro] source = "imported"``) is up to date when its recorded
    water density, gravity, reference point (rotation centre) and, for a finite-depth file,
    water depth equal the case's, and its source files, where they still exist at their
    recorded paths (:func:`located_source_file`), have the recorded SHA-256.
    """
    assert case.floater is not None and case.hydro is not None
    if case.hydro.source == "imported" and is_imported(ds):
        return _imported_stale_keys(ds, case)
    wanted = database_inputs(case.floater, case.hydro, case.environment)
    if ds.attrs.get("inputs_hash") == inputs_hash(wanted):
        return []
    try:
        recorded = json.loads(str(ds.attrs.get("inputs_json", "{}")))
    except (ValueError, RecursionError):
        recorded = {}
    if not isinstance(recorded, dict):
        recorded = {}
    keys = sorted(k for k in set(wanted) | set(recorded) if wanted.get(k) != recorded.get(k))
    # the recorded keys are the file's text: escaped for the messages that list them
    return [shown(k, 80) for k in keys] or ["inputs_hash"]


def load_for_case(case: Case, path: str | os.PathLike[str] | None = None, *,
                  checks: bool = True) -> xr.Dataset:
    """The database of ``case``, checked to be readable, built from the case's inputs and
    (with ``checks``) to pass the database checks.

    A failed check named in the case's ``[hydro] accept_failed_checks`` is reported with an
    :class:`~floatmoor.errors.AcceptedCheckWarning` (once per process; the command line shows
    it as one line) instead of refusing the database.

    Parameters
    ----------
    case
        A case with ``[floater]`` and ``[hydro]``.
    path
        The database file (default: :func:`database_path` of the case).
    checks
        Run the checks of :func:`floatmoor.hydro.checks.run_checks` (False: only whether the
        file is readable and up to date, as ``hydro build`` asks before rebuilding).

    Raises
    ------
    HydroDatabaseError
        Missing, damaged, stale (the message names the inputs that differ), or failing a check
        the case does not accept (the message names each with its value and tolerance, and
        how to accept it).
    """
    if case.floater is None or case.hydro is None:
        raise HydroDatabaseError(f"{case.source}: the case has no [floater] and [hydro] tables")
    p = Path(path) if path is not None else database_path(case)
    if case.hydro.source == "imported" and not os.path.lexists(p):
        raise HydroDatabaseError(f"{p}: no hydrodynamic database, which {case.source} names "
                                 f"([hydro] database = '{shown(case.hydro.database, 200)}', "
                                 f"source = \"imported\"): {IMPORT_ADVICE}")
    ds = read_database(p)
    mismatch = source_mismatch(ds, case)
    if mismatch:
        raise HydroDatabaseError(mismatch)
    differ = stale_keys(ds, case)
    if differ:
        raise HydroDatabaseError(stale_message(p, ds, case.source, differ))
    if checks:
        _enforce_values(ds, p, case)
        _enforce_checks(ds, p, case)
    return ds


def stale_message(path: str | os.PathLike[str], ds: xr.Dataset, case_file: str,
                  differ: list[str]) -> str:
    """``PATH: stale hydrodynamic database for CASE: ...`` with how to renew it: rebuild a
    built database, re-import an imported one."""
    if is_imported(ds):
        return (f"{path}: stale hydrodynamic database for {case_file}: differs in "
                f"{', '.join(differ)}; {REIMPORT_ADVICE}")
    return (f"{path}: stale hydrodynamic database for {case_file}: recorded inputs differ in "
            f"{', '.join(differ)}; rebuild with 'floatmoor hydro build CASE --force'")


def _enforce_values(ds: xr.Dataset, path: Path, case: Case) -> None:
    """Refuse values no body can have (floatmoor.hydro.values), whatever the case accepts."""
    from floatmoor.hydro.values import value_problems

    assert case.floater is not None
    problems = value_problems(ds, case.floater.mass_matrix())
    if problems:
        raise HydroDatabaseError(f"{path}: hydrodynamic database with impossible values (not "
                                 f"as built, whatever its recorded inputs): {'; '.join(problems)}"
                                 "; rebuild it with 'floatmoor hydro build CASE --force'")


#: Check results per database file version (resolved path, modification time, size).
_CHECKS_CACHE: dict[tuple[str, int, int], list[Any]] = {}
#: (file version, accepted checks) whose accepted failures were already reported.
_REPORTED: set[tuple[tuple[str, int, int], tuple[str, ...]]] = set()


def _enforce_checks(ds: xr.Dataset, path: Path, case: Case) -> None:
    """Refuse ``ds`` when it fails a check ``case`` does not accept; warn of accepted ones
    (:class:`~floatmoor.errors.AcceptedCheckWarning`, once per file version and accepted
    checks)."""
    import warnings

    from floatmoor.errors import AcceptedCheckWarning
    from floatmoor.hydro.checks import describe_failures, run_checks

    assert case.hydro is not None
    stat = path.stat()
    key = (str(path.resolve()), stat.st_mtime_ns, stat.st_size)
    if key not in _CHECKS_CACHE:
        _CHECKS_CACHE[key] = run_checks(ds)
    failed = [r for r in _CHECKS_CACHE[key] if not r.passed]
    accepted = case.hydro.accept_failed_checks
    refused = [r for r in failed if r.name not in accepted]
    if refused:
        names = ", ".join(f'"{r.name}"' for r in failed)
        raise HydroDatabaseError(
            f"{path}: hydrodynamic database fails its checks: {describe_failures(refused)}; "
            f"see 'floatmoor hydro check {path}', rebuild it with other [hydro] settings, or "
            f"accept in {case.source}: [hydro] accept_failed_checks = [{names}]")
    tolerated = [r for r in failed if r.name in accepted]
    if tolerated and (key, accepted) not in _REPORTED:
        _REPORTED.add((key, accepted))
        warnings.warn(AcceptedCheckWarning(
            f"{path}: failed checks accepted by {case.source} ([hydro] accept_failed_checks): "
            f"{describe_failures(tolerated)}"), stacklevel=2)
