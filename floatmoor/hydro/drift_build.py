"""Mean drift coefficients of a case's floater, stored in its database
(``floatmoor hydro build CASE --drift``; docs/guide/hydro_databases.md#mean-drift).

:func:`drift_for_case` computes the RAOs the drift uses (:func:`floatmoor.hydro.rao.rao_for_case`:
the case's mass, hydrostatics, its lines' linearised stiffness), meshes the hull as the
database's build did (:func:`floatmoor.hydro.build.checked_mesh`) but with the walls graded
towards the still water line (:func:`drift_waterline_panel_size`; a mesh-file hull is used as
read), and runs :func:`floatmoor.hydro.drift.solve_drift`. :func:`add_drift` puts the result
into the database:

* ``mean_drift_near_field`` (omega, wave_direction, influenced_dof): all six DOFs;
* ``mean_drift_far_field`` (same dims): Surge, Sway, Yaw; NaN for Heave, Roll, Pitch, which
  the momentum route does not give;
* ``mean_drift_near_field_terms`` (drift_term, omega, wave_direction, influenced_dof);
* ``drift_rao`` (complex, omega, wave_direction, radiating_dof): the motions used;

with the conditions (mass matrix, stiffnesses, damping, Kochin angles, seconds) in the
attribute ``drift_json`` and their hash, with the database's ``inputs_hash``, in
``drift_inputs_hash`` (:func:`drift_inputs_hash`): a later change of the case's mass or
mooring makes the drift stale, not the first-order database.

Forces in N/m^2 and moments about the rotation centre in N m/m^2, per unit wave amplitude
squared; the mean force in a regular wave of amplitude a is a^2 times the coefficient.
"""

from __future__ import annotations

import hashlib
import json
import math
from typing import Any

import numpy as np
import xarray as xr

from floatmoor.case.schema import Case
from floatmoor.hydro.drift import DRIFT_TERMS, DriftResult, solve_drift

__all__ = ["DRIFT_VARIABLES", "drift_for_case", "add_drift", "has_drift", "drift_inputs_hash",
           "drift_conditions", "drift_is_current", "drift_is_imported", "IMPORTED_DRIFT_SOURCES",
           "DRIFT_WATERLINE_KH", "drift_waterline_panel_size", "drift_panel_size"]

#: Default panel height at the still water line of the drift's mesh: wavenumber (at the
#: highest frequency) times height 0.05. Convergence study
#: (docs/validation/floaters.md#mean-wave-drift): on the OC4 semisubmersible (2 m panels,
#: 0.8-1.8 rad/s) far and near field agree within 3.3 % of the peak surge drift with
#: k h = 0.05, 4.3 % with 0.087, 9.2 % with 0.17 and 44 % uniform; on a truncated cylinder
#: (0.5 m panels, kR up to 6.8) within 2 % of each other and 2.4 % of the short-wave closed
#: form with k h = 0.05 and 0.07, 6.7 % apart with 0.14, 21 % uniform.
DRIFT_WATERLINE_KH = 0.05

_UNITS = "N/m^2 (Surge, Sway, Heave), N m/m^2 (Roll, Pitch, Yaw)"
_WHAT = ("mean wave drift force and moment about the rotation centre per unit wave amplitude "
         "squared")
DRIFT_VARIABLES: dict[str, dict[str, str]] = {
    "mean_drift_near_field": {
        "long_name": f"{_WHAT}, near field (pressure integration, Pinkster)", "units": _UNITS},
    "mean_drift_far_field": {
        "long_name": f"{_WHAT}, far field (momentum, Maruo-Newman, capytaine); Surge, Sway "
                     "and Yaw only (NaN for Heave, Roll, Pitch)", "units": _UNITS},
    "mean_drift_near_field_terms": {
        "long_name": f"terms of the near-field {_WHAT}", "units": _UNITS},
    "drift_rao": {
        "long_name": "RAO the drift coefficients were computed with (with the mooring's "
                     "linearised stiffness)",
        "units": "m/m (Surge, Sway, Heave), rad/m (Roll, Pitch, Yaw)"},
}


#: ``drift_source`` values of drift imported with the database (``hydro import``).
IMPORTED_DRIFT_SOURCES = ("wamit", "bemio")


def has_drift(ds: xr.Dataset) -> bool:
    """Whether the database holds mean drift coefficients (either route: an import of a WAMIT
    .9 alone has no far field, of a .8 alone no near field)."""
    return "mean_drift_near_field" in ds.variables or "mean_drift_far_field" in ds.variables


def drift_is_imported(ds: xr.Dataset) -> bool:
    """Whether the database's drift was imported (``drift_source`` "wamit" or "bemio")."""
    return has_drift(ds) and ds.attrs.get("drift_source") in IMPORTED_DRIFT_SOURCES


def drift_conditions(case: Case, ds: xr.Dataset, linear_damping=None) -> tuple[Any, dict]:
    """(RAO, conditions) of the case's floater on this database (mooring included)."""
    from floatmoor.hydro.rao import rao_for_case

    return rao_for_case(case, ds, mooring=True, linear_damping=linear_damping)


def drift_inputs_hash(ds: xr.Dataset, conditions: dict[str, Any]) -> str:
    """SHA-256 of the database's ``inputs_hash`` and the RAO conditions (the case file's
    name left out: the same floater in another case file gives the same drift)."""
    kept = {k: v for k, v in conditions.items() if k != "case_file"}
    text = json.dumps({"database": ds.attrs.get("inputs_hash", ""), "conditions": kept},
                      sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def drift_is_current(ds: xr.Dataset, case: Case) -> bool:
    """Whether the database holds drift coefficients for the case's current mass and
    mooring.

    Imported drift (:func:`drift_is_imported`) is current whenever the database is: it was
    computed by the source program with that program's RAOs (its run's mass, mooring and
    damping), which floatmoor cannot recompute, so it has no ``drift_inputs_hash``; its
    source files are recorded with their SHA-256 and checked as the database's are
    (docs/guide/hydro_databases.md#imported-second-order-data). It is never "stale" against
    the case's mass or mooring: matching them is the user's responsibility.
    """
    if not has_drift(ds):
        return False
    if drift_is_imported(ds):
        return True
    _, conditions = drift_conditions(case, ds)
    if ds.attrs.get("drift_inputs_hash") != drift_inputs_hash(ds, conditions):
        return False
    # the drift's own mesh: a changed [hydro] drift_waterline_panel_size (or its default
    # rule) makes it stale too; drift without a recorded mesh was solved on the uniform hull
    try:
        mesh = json.loads(ds.attrs.get("drift_json", "{}")).get("mesh") or {}
    except (TypeError, ValueError):
        return False
    if not isinstance(mesh, dict):
        return False
    base, wanted_base = mesh.get("panel_size"), drift_panel_size(case)
    if base is not None and wanted_base is not None and not _same_size(base, wanted_base):
        return False
    return _same_size(mesh.get("waterline_panel_size"), drift_waterline_panel_size(case))


def _same_size(recorded: Any, wanted: float | None) -> bool:
    """Whether a panel size recorded in ``drift_json`` is the one wanted (None: none, e.g. a
    uniform mesh without graded water line)."""
    if recorded is None or wanted is None:
        return recorded is None and wanted is None
    return isinstance(recorded, (int, float)) and math.isclose(float(recorded), wanted,
                                                                rel_tol=1e-9)


def drift_panel_size(case: Case) -> float | None:
    """Panel size of the drift's mesh away from the still water line [m]: ``[hydro]
    drift_panel_size``, else the database's ``panel_size``."""
    assert case.hydro is not None
    hydro = case.hydro
    return hydro.drift_panel_size if hydro.drift_panel_size is not None else hydro.panel_size


def drift_waterline_panel_size(case: Case) -> float | None:
    """Panel height at the still water line of the drift's mesh [m]: ``[hydro]
    drift_waterline_panel_size``, or :data:`DRIFT_WATERLINE_KH` over the wavenumber of the
    highest frequency; None (uniform) when that is not below ``panel_size``."""
    from floatmoor.hydro.build import wavenumber

    assert case.hydro is not None
    hydro = case.hydro
    if hydro.drift_waterline_panel_size is not None:
        size = hydro.drift_waterline_panel_size
    else:
        depth = math.inf if hydro.infinite_depth else case.environment.water_depth
        size = DRIFT_WATERLINE_KH / wavenumber(max(hydro.frequencies), depth,
                                               case.environment.gravity)
    base = drift_panel_size(case)
    return size if base is None or size < base else None


def drift_for_case(case: Case, ds: xr.Dataset, *, progress=None) -> tuple[DriftResult, Any,
                                                                            dict[str, Any]]:
    """Drift coefficients of the case's floater on its (first-order) database, solved on the
    hull graded towards the still water line (:func:`drift_waterline_panel_size`).

    Parameters
    ----------
    case
        The case (its floater, hydro settings and environment).
    ds
        The case's first-order database (:func:`floatmoor.hydro.database.load_for_case`).
    progress
        Called after each frequency (:func:`floatmoor.hydro.drift.solve_drift`).

    Returns
    -------
    (DriftResult, RAO DataArray, conditions)
    """
    import logging

    import capytaine as cpt

    from floatmoor.case.schema import MeshGeometry
    from floatmoor.hydro.build import _seed_prony, checked_mesh
    from floatmoor.hydro.geometry import GRADING_RATIO, build_mesh, mesh_hash

    assert case.floater is not None and case.hydro is not None
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    _seed_prony()
    x, conditions = drift_conditions(case, ds)
    env, hydro = case.environment, case.hydro
    depth = math.inf if hydro.infinite_depth else env.water_depth
    checked = checked_mesh(case.floater, hydro, env)
    ref = np.asarray(case.floater.reference_point, float)
    mesh, top = checked.mesh, None
    if not isinstance(case.floater.geometry, MeshGeometry):
        top = drift_waterline_panel_size(case)
        mesh = build_mesh(case.floater.geometry, panel_size=drift_panel_size(case),
                          reference_xy=(float(ref[0]), float(ref[1])),
                          lid_depth=checked.lid_depth, symmetry=hydro.symmetry,
                          radial_panels=hydro.radial_panels, waterline_panel_size=top)
    body = cpt.FloatingBody(mesh=mesh.hull, lid_mesh=mesh.lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=ref), center_of_mass=ref,
                            name=case.floater.name)
    motion = x.transpose("omega", "wave_direction", "radiating_dof").values
    result = solve_drift(body, omegas=ds["omega"].values, directions=ds["wave_direction"].values,
                         motion=motion, depth=depth, rho=env.water_density, g=env.gravity,
                         rotation_center=ref, progress=progress)
    result.mesh = {"waterline_panel_size": top, "panel_size": drift_panel_size(case),
                   "grading_ratio": GRADING_RATIO if top is not None else None,
                   "hull_panels": int(mesh.full_hull.nb_faces), "hull_sha256": mesh_hash(
                       mesh.full_hull)}
    return result, x, conditions


def add_drift(ds: xr.Dataset, result: DriftResult, x, conditions: dict[str, Any]) -> xr.Dataset:
    """The database with the drift variables and attributes (replacing earlier ones).

    Parameters
    ----------
    ds
        The database.
    result
        The drift coefficients (:func:`drift_for_case`).
    x
        The RAO the body moved by in the drift solve (:func:`drift_for_case`).
    conditions
        The conditions of that RAO (:func:`drift_for_case`), recorded as attributes.

    Returns
    -------
    xarray.Dataset
        A new dataset; ``ds`` is unchanged.
    """
    dims = ("omega", "wave_direction", "influenced_dof")
    out = ds.drop_vars([v for v in DRIFT_VARIABLES if v in ds.variables])
    out = out.drop_dims([d for d in ("drift_term",) if d in out.dims])
    values = x.transpose("omega", "wave_direction", "radiating_dof").values
    new = {
        "mean_drift_near_field": (dims, result.near_field),
        "mean_drift_far_field": (dims, result.far_field),
        "mean_drift_near_field_terms": (("drift_term",) + dims,
                                        np.moveaxis(result.near_field_terms, 2, 0)),
        "drift_rao": (("complex", "omega", "wave_direction", "radiating_dof"),
                      np.stack([values.real, values.imag])),
    }
    for name, (d, v) in new.items():
        out[name] = xr.DataArray(v, dims=d, attrs=DRIFT_VARIABLES[name])
    out = out.assign_coords(drift_term=("drift_term", np.array(DRIFT_TERMS),
                                        {"long_name": "near-field term (I waterline, II "
                                         "velocity, III pressure gradient, IV rotation, V "
                                         "hydrostatic)", "units": "1"}))
    record = {**conditions, "kochin_angles": int(len(result.theta)),
              "drift_seconds": float(result.seconds), "bem_method": "indirect",
              "near_field_terms": list(DRIFT_TERMS), "mesh": result.mesh,
              "far_field": "capytaine.post_pro.mean_drift_force.far_field_mean_drift_force, "
                           "Kochin functions / tanh(kh) in finite depth"}
    out.attrs["drift_json"] = json.dumps(record)
    out.attrs["drift_source"] = "floatmoor"
    out.attrs["drift_inputs_hash"] = drift_inputs_hash(ds, conditions)
    return out
