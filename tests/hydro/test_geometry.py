"""Meshes against the analytic geometry: volume, waterplane, symmetry."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.schema import Column, CylinderGeometry, Member, SemisubmersibleGeometry
from floatmoor.hydro.hydrostatics import hull_hydrostatics
from floatmoor.hydro.geometry import (
    SYMMETRY_TOLERANCE, cylinder_mesh, geometry_properties, semisubmersible_mesh,
)

#: A mesh's waterplane and volume are those of its inscribed polygons: exact to round-off.
ROUND_OFF = 1e-9


def _polygon_area(radius: float, n: int) -> float:
    return 0.5 * n * radius * radius * math.sin(2.0 * math.pi / n)


def test_cylinder_mesh_is_the_inscribed_prism():
    geometry = CylinderGeometry(diameter=0.515, draft=0.1721, height=0.401, draft_from_mass=False)
    mesh = cylinder_mesh(geometry, panel_size=0.02, lid_depth=0.01)
    n = int(mesh.symmetry.split("-")[1])
    area = _polygon_area(0.2575, n)
    full = mesh.full_hull
    assert full.waterplane_area == pytest.approx(area, rel=ROUND_OFF)
    assert full.volume == pytest.approx(area * 0.1721, rel=ROUND_OFF)
    assert mesh.lid_panels > 0 and mesh.lid.merged().faces_centers[:, 2] == pytest.approx(-0.01)


def test_cylinder_mesh_converges_to_the_circle():
    geometry = CylinderGeometry(diameter=1.0, draft=1.0, height=2.0, draft_from_mass=False)
    coarse = cylinder_mesh(geometry, panel_size=0.25).full_hull.volume
    fine = cylinder_mesh(geometry, panel_size=0.05).full_hull.volume
    exact = math.pi * 0.25
    assert abs(fine - exact) < abs(coarse - exact) / 10  # second order: (0.25/0.05)^2 = 25
    assert fine == pytest.approx(exact, rel=3e-3)


def test_deepcwind_mesh_matches_the_geometry(deepcwind_case):
    geometry = deepcwind_case.floater.geometry
    props = geometry_properties(geometry)
    # OC4 published displacement 13,917 m^3 (docs/cases/deepcwind.md): the analytic geometry within 0.1 %
    assert props.volume == pytest.approx(13917.0, rel=1e-3)
    mesh = semisubmersible_mesh(geometry, panel_size=deepcwind_case.hydro.panel_size,
                                lid_depth=0.1)
    assert mesh.symmetry == "rotation-3+mirror-xOz"
    full = mesh.full_hull
    # waterplane and volume: polygons of 36 and 60 sides inscribed in the columns (-0.5 % and
    # -0.18 %) and the braces' ellipses; the hydrostatic integrals use n_z only, blind to the
    # gaps left on vertical walls at the member junctions
    hs = hull_hydrostatics(full, rho=1025.0, g=9.80665, rotation_center=(0.0, 0.0, 0.0))
    assert hs["waterplane_area"] == pytest.approx(props.waterplane_area, rel=0.005)
    assert hs["disp_volume"] == pytest.approx(props.volume, rel=0.005)
    assert hs["center_of_buoyancy"] == pytest.approx(props.centre_of_buoyancy, abs=0.02)


def test_symmetric_semisub_mesh_rebuilds_the_full_mesh(deepcwind_case):
    geometry = deepcwind_case.floater.geometry
    mesh = semisubmersible_mesh(geometry, panel_size=4.0, lid_depth=0.1)
    merged = mesh.hull.merged()
    assert merged.nb_faces == mesh.full_hull.nb_faces
    assert merged.faces_areas.sum() == pytest.approx(mesh.full_hull.faces_areas.sum(),
                                                     rel=SYMMETRY_TOLERANCE)
    assert mesh.hull.n == 3 and mesh.hull.wedge.half.nb_faces * 6 == merged.nb_faces


def test_asymmetric_semisub_is_meshed_without_symmetry():
    cols = (Column(0.0, 0.0, 4.0, 5.0, -10.0), Column(20.0, 0.0, 4.0, 5.0, -10.0),
            Column(-10.0, 12.0, 4.0, 5.0, -8.0))
    mesh = semisubmersible_mesh(SemisubmersibleGeometry(cols), panel_size=2.0)
    assert mesh.symmetry == "none"
    props = geometry_properties(SemisubmersibleGeometry(cols))
    assert mesh.full_hull.volume == pytest.approx(props.volume, rel=0.01)


def test_member_ends_lie_on_the_column_surface():
    cols = (Column(0.0, 0.0, 6.0, 5.0, -10.0), Column(30.0, 0.0, 6.0, 5.0, -10.0))
    member = Member((3.0, 0.0, -8.0), (27.0, 0.0, -8.0), 1.0)
    mesh = semisubmersible_mesh(SemisubmersibleGeometry(cols, (member,)), panel_size=0.5,
                                symmetry=False)
    v = mesh.full_hull.vertices
    on_member = np.abs(np.hypot(v[:, 1], v[:, 2] + 8.0) - 0.5) < 1e-9
    ends = v[on_member & (v[:, 0] < 15.0)]
    first = ends[np.argmin(ends[:, 0])]
    # the innermost ring of the member is on the first column's surface (radius 3)
    assert np.hypot(first[0], first[1]) == pytest.approx(3.0, abs=1e-9)
    # the hydrostatic volume (n_z-weighted integrals, blind to the gaps on vertical walls at the
    # junction) is the analytic one less the 36-gon deficit of the columns (0.5 %)
    props = geometry_properties(SemisubmersibleGeometry(cols, (member,)))
    volume = hull_hydrostatics(mesh.full_hull, rho=1000.0, g=9.81,
                               rotation_center=(0.0, 0.0, 0.0))["disp_volume"]
    assert volume == pytest.approx(props.volume, rel=0.01)
