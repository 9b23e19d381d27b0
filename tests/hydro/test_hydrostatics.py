"""Hydrostatics of the cylinder mesh: exact for the discretised polygon, within 1 % of the
circle.

The hydrostatics are floatmoor's (floatmoor.hydro.hydrostatics, exact quadrature of the
quadratic integrands). "Exact" compares with the analytic values of the inscribed regular
n-gon prism that the mesh is (waterplane area n/2 r^2 sin(2 pi/n), second moment n r^4 sin a (2 + cos a) / 24 with
a = 2 pi / n): the quantity capytaine integrates, so any difference is an error of the mesh or
of the integration, not of the discretisation. The comparison with the circle (1 %) is the
mesh-convergence statement.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.schema import CylinderGeometry
from floatmoor.hydro.geometry import cylinder_mesh
from floatmoor.hydro.hydrostatics import hull_hydrostatics

#: The cylinder's hydrostatics exact to 1e-6 (relative; docs/development.md#case-521-hydrostatics).
EXACT = 1e-6
#: Required: stiffness and displacement against the analytic cylinder within 1 %.
CIRCLE = 0.01
RHO, G = 1000.0, 9.81
RADIUS, DRAFT = 0.2575, 0.17210157


@pytest.fixture(scope="module")
def mesh():
    return cylinder_mesh(CylinderGeometry(diameter=2 * RADIUS, draft=DRAFT, height=0.401,
                                          draft_from_mass=False), panel_size=0.015)


@pytest.fixture(scope="module")
def hydrostatics(mesh):
    n = int(mesh.symmetry.split("-")[1])
    return n, hull_hydrostatics(mesh.full_hull, rho=RHO, g=G, rotation_center=(0.0, 0.0, 0.0))


def _polygon(n: int) -> tuple[float, float]:
    a = 2.0 * math.pi / n
    return 0.5 * n * RADIUS ** 2 * math.sin(a), n * RADIUS ** 4 * math.sin(a) * (2 + math.cos(a)) / 24


def test_cylinder_hydrostatics_exact_for_the_polygon(hydrostatics):
    n, hs = hydrostatics
    area, inertia = _polygon(n)
    volume = area * DRAFT
    c = np.asarray(hs["hydrostatic_stiffness"])
    assert hs["disp_volume"] == pytest.approx(volume, rel=EXACT)
    assert hs["waterplane_area"] == pytest.approx(area, rel=EXACT)
    assert c[2, 2] == pytest.approx(RHO * G * area, rel=EXACT)
    # metacentric formula about the water line with the centre of mass at the rotation centre:
    # C44 = C55 = rho g (I_wp + V z_B), z_B = -T/2
    assert c[3, 3] == pytest.approx(RHO * G * (inertia - volume * DRAFT / 2), rel=EXACT)
    assert c[4, 4] == pytest.approx(RHO * G * (inertia - volume * DRAFT / 2), rel=EXACT)
    assert hs["center_of_buoyancy"][2] == pytest.approx(-DRAFT / 2, rel=EXACT)
    off_diagonal = c - np.diag(np.diag(c))
    assert np.abs(off_diagonal).max() < EXACT * c[2, 2]


def test_capytaine_agrees_on_the_linear_integrals(mesh, hydrostatics):
    """capytaine's one-point panel quadrature is exact for V and C33 (linear integrands), so
    it must agree there; for C44 it is not (second moments), which is why floatmoor
    integrates the hydrostatics itself."""
    import capytaine as cpt

    _, hs = hydrostatics
    body = cpt.FloatingBody(mesh=mesh.full_hull, dofs=cpt.rigid_body_dofs(),
                            center_of_mass=(0.0, 0.0, 0.0))
    ref = body.compute_hydrostatics(rho=RHO, g=G)
    assert ref["disp_volume"] == pytest.approx(hs["disp_volume"], rel=EXACT)
    c = np.asarray(ref["hydrostatic_stiffness"])
    assert c[2, 2] == pytest.approx(hs["hydrostatic_stiffness"][2, 2], rel=EXACT)


def test_cylinder_hydrostatics_within_1_percent_of_the_circle(hydrostatics):
    _, hs = hydrostatics
    area = math.pi * RADIUS ** 2
    c = np.asarray(hs["hydrostatic_stiffness"])
    assert hs["disp_volume"] == pytest.approx(area * DRAFT, rel=CIRCLE)
    assert c[2, 2] == pytest.approx(RHO * G * area, rel=CIRCLE)
    c44 = RHO * G * (math.pi * RADIUS ** 4 / 4 - area * DRAFT * DRAFT / 2)
    assert c[3, 3] == pytest.approx(c44, rel=CIRCLE)


def test_buoy_draft_from_mass_floats_the_buoy(buoy_case, buoy_db):
    """The database's displacement times density is the buoy's mass (case C: draft from the
    mass), to the polygon's area deficit (n = 108: 0.06 %)."""
    assert float(buoy_db["disp_volume"]) * 1000.0 == pytest.approx(buoy_case.floater.mass,
                                                                   rel=1e-3)
