"""Remake tests/data/drift/deepcwind_drift_subset.nc (README.md beside this file):

    PYTHONPATH=. python tests/data/drift/make_deepcwind_drift_subset.py

The mean drift of the shipped DeepCwind database (hydrodb/deepcwind.nc) at 19 of its
frequencies and 3 directions, on the drift mesh ``hydro build --drift`` uses
(floatmoor.hydro.drift_build.drift_waterline_panel_size), with two RAO sets from the same
solves: the case's (cases/deepcwind/deepcwind_free_decay.toml, linearised mooring) and HydroSTAR
case 9's mass properties without mooring. About 10-15 minutes of one core.
"""

from __future__ import annotations

import dataclasses
import logging
import math
import time
from pathlib import Path

import numpy as np
import xarray as xr

REPO = Path(__file__).resolve().parents[3]
OMEGAS = (0.30, 0.42, 0.54, 0.66, 0.74, 0.80, 0.86, 0.92, 0.98, 1.04, 1.10, 1.16, 1.22, 1.28,
          1.34, 1.40, 1.55, 1.70, 1.85)
DIRECTIONS_DEG = (0.0, 30.0, 180.0)
#: HydroSTAR case 9 (tests/data/drift/README.md): mass, inertia about the CoG (0, 0, 0)
HYDROSTAR_9 = dict(mass=1.391572e7, centre_of_mass=(0.0, 0.0, 0.0),
                   inertia=(9.049484e9, 9.049481e9, 1.177594e10, 0.0, 0.0, 0.0))


def main() -> None:
    import capytaine as cpt

    from floatmoor.case.load import load_case
    from floatmoor.hydro.build import _seed_prony, lid_depth_for
    from floatmoor.hydro.database import read_database
    from floatmoor.hydro.drift import DRIFT_TERMS, solve_drift
    from floatmoor.hydro.drift_build import (drift_conditions, drift_panel_size,
                                             drift_waterline_panel_size)
    from floatmoor.hydro.geometry import build_mesh
    from floatmoor.hydro.rao import rao

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    _seed_prony()
    case = load_case(REPO / "cases" / "deepcwind" / "deepcwind_free_decay.toml")
    ds = read_database(REPO / "hydrodb" / "deepcwind.nc")
    x_case, _ = drift_conditions(case, ds)
    x_hs = rao(ds, dataclasses.replace(case.floater, **HYDROSTAR_9))
    omega_all = ds["omega"].values
    i_w = [int(np.argmin(np.abs(omega_all - w))) for w in OMEGAS]
    i_b = [int(np.argmin(np.abs(ds["wave_direction"].values - math.radians(b))))
           for b in DIRECTIONS_DEG]
    omegas, directions = omega_all[i_w], ds["wave_direction"].values[i_b]

    def picked(x: xr.DataArray) -> np.ndarray:
        return x.transpose("omega", "wave_direction", "radiating_dof").values[i_w][:, i_b]

    hydro, floater = case.hydro, case.floater
    ref = np.asarray(floater.reference_point, float)
    top = drift_waterline_panel_size(case)
    lid = (hydro.lid_depth or lid_depth_for(max(hydro.frequencies), case.environment.water_depth,
                                            case.environment.gravity)) if hydro.lid else None
    mesh = build_mesh(floater.geometry, panel_size=drift_panel_size(case), lid_depth=lid,
                      symmetry=hydro.symmetry, waterline_panel_size=top)
    body = cpt.FloatingBody(mesh=mesh.hull, lid_mesh=mesh.lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=ref), center_of_mass=ref)
    start = time.perf_counter()
    result = solve_drift(body, omegas=omegas, directions=directions, motion=picked(x_case),
                         depth=case.environment.water_depth, rho=case.environment.water_density,
                         g=case.environment.gravity, rotation_center=ref,
                         other_motions=(picked(x_hs),))
    seconds = time.perf_counter() - start
    sets = (result, result.others[0])
    motions = np.stack([picked(x_case), picked(x_hs)])
    units = "N/m^2 (Surge, Sway, Heave), N m/m^2 (Roll, Pitch, Yaw)"
    dims = ("rao_set", "omega", "wave_direction", "influenced_dof")
    out = xr.Dataset({
        "mean_drift_near_field": (dims, np.stack([r.near_field for r in sets]),
                                  {"units": units, "long_name": "near-field mean drift"}),
        "mean_drift_far_field": (dims, np.stack([r.far_field for r in sets]),
                                 {"units": units,
                                  "long_name": "far-field mean drift (Surge, Sway, Yaw)"}),
        "mean_drift_near_field_terms": (
            ("rao_set", "omega", "wave_direction", "drift_term", "influenced_dof"),
            np.stack([r.near_field_terms for r in sets]), {"units": units}),
        "drift_rao": (("complex", "rao_set", "omega", "wave_direction", "radiating_dof"),
                      np.stack([motions.real, motions.imag]), {"units": "m/m, rad/m"}),
    }, coords={"rao_set": ["case", "hydrostar_9"], "omega": omegas,
               "wave_direction": directions,
               "influenced_dof": ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"],
               "drift_term": list(DRIFT_TERMS), "complex": ["re", "im"],
               "radiating_dof": ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]})
    out.attrs = {
        "title": "floatmoor mean drift of hydrodb/deepcwind.nc at a subset of frequencies and "
                 "directions (test data)",
        "made_by": f"tests/data/drift/make_deepcwind_drift_subset.py: "
                   f"floatmoor.hydro.drift.solve_drift on the drift mesh of "
                   f"cases/deepcwind/deepcwind_free_decay.toml ({hydro.panel_size:g} m panels, "
                   f"graded to {top:.4f} m at the water line), {mesh.symmetry}, "
                   f"{mesh.full_hull.nb_faces} panels; {seconds:.0f} s wall",
        "rao_sets": "case: the case's mass and linearised mooring; hydrostar_9: m 1.391572e7 "
                    "kg, CoG (0,0,0), I 9.049484e9 9.049481e9 1.177594e10 kg m^2, no mooring "
                    "(Nemoh v3 test case 9)",
    }
    path = REPO / "tests" / "data" / "drift" / "deepcwind_drift_subset.nc"
    out.to_netcdf(path)
    print(f"{path}: {mesh.full_hull.nb_faces} panels, {seconds:.0f} s")


if __name__ == "__main__":
    main()
