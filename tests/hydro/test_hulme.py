"""A floating hemisphere in deep water against Hulme's (1982) heave coefficients.

Reference values: Hulme, A. (1982) "The wave forces acting on a floating hemisphere undergoing
forced periodic oscillations", J. Fluid Mech. 121, 443-463, heave table; transcribed in
LHEEA/Hulme_Heaving_Sphere, comparison/HulmeResult.dat (github.com/LHEEA). Non-dimensional
added mass A33 / (rho 2/3 pi a^3) and damping B33 / (rho 2/3 pi a^3 omega) against
K a = omega^2 a / g.

A small BEM run (a coarse rotation-symmetric hemisphere, four frequencies, no lid: the first
irregular frequency of a hemisphere is at K a ~ 2.5, above the points used) takes a few
seconds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.hydro.geometry import hemisphere_mesh

#: Against Hulme's (1982) potential-flow solution for the hemisphere (docs/development.md#where-tests-live).
pytestmark = pytest.mark.verification

#: Hulme (1982), heave: K a -> (added mass, damping), non-dimensional as above.
HULME_HEAVE = {0.2: (0.7938, 0.2793), 0.5: (0.5861, 0.3391), 1.0: (0.4284, 0.2484),
               1.6: (0.3871, 0.1469)}
#: Heave added mass and damping within 3 % of Hulme's values
#: (docs/development.md#case-523-floating-hemisphere).
HULME_TOLERANCE = 0.03
RADIUS, RHO, G = 1.0, 1000.0, 9.81


@pytest.fixture(scope="module")
def hemisphere_coefficients():
    import capytaine as cpt

    mesh = hemisphere_mesh(RADIUS, n_theta=40, n_phi=14)
    body = cpt.FloatingBody(mesh=mesh.hull, dofs=cpt.rigid_body_dofs(only=["Heave"]),
                            center_of_mass=(0.0, 0.0, 0.0))
    from floatmoor.hydro.build import BEM_METHOD

    solver = cpt.BEMSolver(method=BEM_METHOD)
    out = {}
    for ka in HULME_HEAVE:
        omega = math.sqrt(ka * G / RADIUS)
        res = solver.solve(cpt.RadiationProblem(body=body, radiating_dof="Heave", omega=omega,
                                                water_depth=np.inf, rho=RHO, g=G),
                           keep_details=False)
        scale = RHO * 2.0 / 3.0 * math.pi * RADIUS ** 3
        out[ka] = (res.added_mass["Heave"] / scale,
                   res.radiation_damping["Heave"] / (scale * omega))
    return out


@pytest.mark.parametrize("ka", sorted(HULME_HEAVE))
def test_hemisphere_heave_matches_hulme(hemisphere_coefficients, ka):
    added, damping = hemisphere_coefficients[ka]
    ref_a, ref_b = HULME_HEAVE[ka]
    assert added == pytest.approx(ref_a, rel=HULME_TOLERANCE)
    assert damping == pytest.approx(ref_b, rel=HULME_TOLERANCE)


def test_hemisphere_mesh_volume_converges_to_sphere_half():
    mesh = hemisphere_mesh(RADIUS, n_theta=40, n_phi=14).full_hull
    assert mesh.volume == pytest.approx(2.0 / 3.0 * math.pi * RADIUS ** 3, rel=0.01)
