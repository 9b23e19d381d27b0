"""Mean drift of the semisubmersible and the published HydroSTAR cases (Nemoh v3 test cases
8b and 9, tests/data/drift/README.md).

The semisubmersible's drift is stored (tests/data/drift/deepcwind_drift_subset.nc: 19
frequencies, 3 directions, the shipped database's mesh, both RAO sets from the same solves
through ``solve_drift(..., other_motions=...)``, 549 s), so the default tests need no BEM; the
truncated
cylinder of case 8b is solved by a slow test. HydroSTAR's RAOs are not among the transcribed
data, so the motions could not be compared first: the cases' mass properties are used as
published (the cylinder's inertia, not published, is taken as a uniform solid's).
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
import xarray as xr

from tests.hydro.conftest import REPO

DATA = REPO / "tests" / "data" / "drift"
SUBSET = DATA / "deepcwind_drift_subset.nc"
#: The issue's criterion for the consistency and published comparisons.
DRIFT_RTOL = 0.05


def _hydrostar(name: str, heading_deg: float) -> np.ndarray:
    """(omega, Fx) rows of a HydroSTAR table at one heading."""
    rows = [(float(r["omega_rad_s"]), float(r["Fx_N_per_m2"]))
            for r in csv.DictReader(open(DATA / name, encoding="utf-8"))
            if float(r["heading_deg"]) == heading_deg]
    return np.array(rows)


@pytest.fixture(scope="module")
def subset():
    return xr.open_dataset(SUBSET).load()


def test_semisubmersible_far_and_near_field_in_surge(subset):
    """The shipped DeepCwind database with the case's moored RAOs, heading 0: far and near
    field within 5 % of the peak surge drift (132 kN/m^2) up to 1.16 rad/s (measured 1.5 %
    at 0.66-1.10, 4.8 % at 1.16). Above, the near field is 10-50 % above the far field
    (1.22-1.85 rad/s, kR of the 12 m columns 1.8-2.1): the near field's velocity term is
    under-resolved on the 4380-panel mesh, as on the bottom-mounted cylinder at kR = 5 with
    80 x 20 panels; the far field, which needs only the Kochin functions, is the one to use
    there."""
    case = subset.sel(rao_set="case", wave_direction=0.0, influenced_dof="Surge")
    near, far = case["mean_drift_near_field"].values, case["mean_drift_far_field"].values
    omega = subset["omega"].values
    peak = np.abs(far).max()
    low = omega <= 1.161
    assert np.abs(far[low] - near[low]).max() <= DRIFT_RTOL * peak
    high = omega >= 1.22
    assert np.all(near[high] > 1.08 * far[high])  # the known limit above


def test_semisubmersible_against_hydrostar_case_9(subset):
    """HydroSTAR case 9 (its mass properties, no mooring; HydroSTAR's grid interpolated onto
    ours), heading 30 deg, 0.74-1.70 rad/s, away from the heave resonance (0.36 rad/s) and
    from the low frequencies where the drift is below 1 % of its peak: the far field within
    5 % at 8 of the 14 frequencies and within 12.2 % at all (worst at 0.98 rad/s, a trough of
    the drift between the columns' interference peaks, -12.2 %, and 1.40 rad/s, -9.0 %); the
    near field within 5 % at 0.74-1.22 rad/s but for 0.92-1.04 (-5.7 to -12.4 %), and 9-33 %
    high at 1.28-1.70 rad/s (its mesh limit, previous test). At heading 0 our 180 deg near
    field (sign turned) is within 6.9 % of theirs at 0.98-1.34 rad/s, closer than our 0 deg:
    HydroSTAR's mesh seems to have the offset column on -x, ours on +x (heading 30 is the
    same for both by the hull's 3-fold and mirror symmetry)."""
    hs = _hydrostar("hydrostar_9_oc4_semisub_h200.csv", 30.0)
    ours = subset.sel(rao_set="hydrostar_9", influenced_dof="Surge").isel(wave_direction=1)
    omega = subset["omega"].values
    band = (omega >= 0.73) & (omega <= 1.71)
    ref = np.interp(omega[band], hs[:, 0], hs[:, 1])
    rel = np.abs(ours["mean_drift_far_field"].values[band] / ref - 1.0)
    assert np.count_nonzero(rel <= DRIFT_RTOL) >= 8 and rel.max() <= 0.125
    hs0 = _hydrostar("hydrostar_9_oc4_semisub_h200.csv", 0.0)
    turned = -subset.sel(rao_set="hydrostar_9", influenced_dof="Surge").isel(
        wave_direction=2)["mean_drift_near_field"].values
    mid = (omega >= 0.97) & (omega <= 1.35)
    rel0 = np.abs(turned[mid] / np.interp(omega[mid], hs0[:, 0], hs0[:, 1]) - 1.0)
    assert rel0.max() <= 0.07


@pytest.mark.slow
def test_truncated_cylinder_against_hydrostar_case_8b():
    """Case 8b: R 6 m, draft 14 m, deep water, m = rho V, CoG (0,0,0); panels 0.5 m (3040 +
    912 lid), 0.82-3.33 rad/s (kR 0.4-6.8; the README's usable range 0.8-3.4), heading 0.
    Measured (every HydroSTAR frequency in the range, 27 s): the near field -8 % to +2.7 %
    from 0.94 rad/s up, within 5 % from 1.70 rad/s (-4.2 % to +2.7 %; -5.1 % at 1.57); the far field within
    5.7 % at 0.94-2.07 rad/s but 10-19 % low at kR > 4 (uniform 0.5 m panels: the Kochin
    functions' one-point quadrature of e^{kz} over the top panels; with panels graded towards
    the surface, as on the bottom-mounted cylinder, it holds to kR = 5). At the heave
    resonance (0.82 rad/s) the far field is 15 % high, the near field +1.2 %. The 5-8 % low
    near field at 0.94-1.44 rad/s, where the drift is small and surge and pitch motions
    matter, may come from the unpublished inertia."""
    import logging

    import capytaine as cpt

    from floatmoor.case.schema import CylinderGeometry
    from floatmoor.hydro.build import lid_depth_for
    from floatmoor.hydro.drift import solve_drift
    from floatmoor.hydro.geometry import cylinder_mesh
    from floatmoor.hydro.hydrostatics import hull_hydrostatics
    from capytaine.bem.airy_waves import froude_krylov_force

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    rho, g, radius, draft = 1025.0, 9.81, 6.0, 14.0
    hs = _hydrostar("hydrostar_8b_cylinder_R6_T14_deep.csv", 0.0)
    omegas = hs[(hs[:, 0] > 0.8) & (hs[:, 0] < 3.4), 0][::4]
    mesh = cylinder_mesh(CylinderGeometry(diameter=2 * radius, draft=draft, height=20.0,
                                          draft_from_mass=False), panel_size=0.5,
                         lid_depth=lid_depth_for(float(omegas.max()), math.inf, g))
    body = cpt.FloatingBody(mesh=mesh.hull, lid_mesh=mesh.lid,
                            dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)),
                            center_of_mass=(0, 0, 0))
    hydrostatics = hull_hydrostatics(mesh.full_hull, rho=rho, g=g, rotation_center=np.zeros(3))
    m = rho * hydrostatics["disp_volume"]
    i_xx = m * (3 * radius ** 2 + draft ** 2) / 12 + m * (draft / 2) ** 2
    mass = np.diag([m, m, m, i_xx, i_xx, m * radius ** 2 / 2])
    stiffness = np.asarray(hydrostatics["hydrostatic_stiffness"])
    solver = cpt.BEMSolver(method="direct")
    dofs = list(body.dofs)
    motion = np.zeros((len(omegas), 1, 6), complex)
    for i, w in enumerate(omegas):
        a, b = np.zeros((6, 6)), np.zeros((6, 6))
        for j, dof in enumerate(dofs):
            r = solver.solve(cpt.RadiationProblem(body=body, radiating_dof=dof, omega=w,
                                                  rho=rho, g=g), keep_details=False)
            for k, other in enumerate(dofs):
                a[k, j], b[k, j] = r.added_mass[other], r.radiation_damping[other]
        problem = cpt.DiffractionProblem(body=body, omega=w, wave_direction=0.0, rho=rho, g=g)
        r, fk = solver.solve(problem, keep_details=False), froude_krylov_force(problem)
        force = np.array([r.forces[o] + fk[o] for o in dofs])
        motion[i, 0] = np.linalg.solve(-w * w * (mass + a) - 1j * w * b + stiffness, force)
    result = solve_drift(body, omegas=omegas, directions=np.array([0.0]), motion=motion,
                         depth=math.inf, rho=rho, g=g, rotation_center=np.zeros(3))
    ref = np.interp(omegas, hs[:, 0], hs[:, 1])
    near = np.abs(result.near_field[:, 0, 0] / ref - 1.0)
    far = np.abs(result.far_field[:, 0, 0] / ref - 1.0)
    assert np.all(near[omegas >= 1.6] <= DRIFT_RTOL)
    assert np.all(near[omegas >= 0.9] <= 0.085)
    assert np.all(far[(omegas >= 0.9) & (omegas <= 2.1)] <= 0.06)
