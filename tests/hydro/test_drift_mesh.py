"""The mean drift's mesh: walls graded towards the still water line
(floatmoor.hydro.geometry.graded_levels, floatmoor.hydro.drift_build.drift_waterline_panel_size;
docs/validation/floaters.md#mean-wave-drift for the convergence study behind the default)."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.schema import CylinderGeometry
from floatmoor.errors import CaseError
from floatmoor.hydro.build import wavenumber
from floatmoor.hydro.drift_build import DRIFT_WATERLINE_KH, drift_waterline_panel_size
from floatmoor.hydro.geometry import (
    GRADING_RATIO, cylinder_mesh, geometry_properties, graded_levels, semisubmersible_mesh,
)
from floatmoor.hydro.hydrostatics import hull_hydrostatics
from tests.hydro.conftest import DEEPCWIND_CASE

#: Graded and uniform meshes of the same hull: the same polygonal solid, so the same volume
#: and waterplane to round-off.
SAME_SOLID = 1e-9


@pytest.mark.parametrize("top", [0.5, 0.143, 0.044])
def test_graded_levels_start_at_the_top_size_and_grow_by_the_ratio(top):
    z = graded_levels(-14.0, 0.0, 2.0, top)
    heights = -np.diff(z[::-1])
    assert z[0] == pytest.approx(-14.0) and z[-1] == 0.0 and np.all(np.diff(z) > 0)
    assert heights[0] == pytest.approx(top, rel=1e-12)
    graded = heights[heights < 2.0 / GRADING_RATIO]  # then the uniform rows
    assert np.allclose(graded[1:] / graded[:-1], GRADING_RATIO)
    assert heights.max() <= 1.5 * 2.0  # the uniform rest: the nearest whole number of rows
    # uniform without a finer top: the database's own rows
    np.testing.assert_allclose(graded_levels(-14.0, 0.0, 2.0), np.linspace(-14, 0, 8))
    np.testing.assert_allclose(graded_levels(-14.0, 0.0, 2.0, 2.5), np.linspace(-14, 0, 8))


def test_graded_semisubmersible_is_the_same_solid_finer_at_the_waterline(deepcwind_case):
    geometry = deepcwind_case.floater.geometry
    uniform = semisubmersible_mesh(geometry, panel_size=2.0)
    graded = semisubmersible_mesh(geometry, panel_size=2.0, waterline_panel_size=0.25)
    assert graded.symmetry == uniform.symmetry == "rotation-3+mirror-xOz"
    a, b = (hull_hydrostatics(m.full_hull, rho=1025.0, g=9.81, rotation_center=(0, 0, 0))
            for m in (uniform, graded))
    # the columns are the same polygons; where the braces cross the water line next to the
    # offset columns their rows end on another curve: volume +0.23 %, towards the geometry's
    exact = geometry_properties(geometry)
    assert abs(b["disp_volume"] - exact.volume) < abs(a["disp_volume"] - exact.volume)
    assert b["disp_volume"] == pytest.approx(exact.volume, rel=0.005)
    assert b["waterplane_area"] == pytest.approx(exact.waterplane_area, rel=0.005)
    faces = graded.full_hull.as_array_of_faces()
    top = faces[np.isclose(faces[:, :, 2].max(axis=1), 0.0, atol=1e-9)]
    heights = np.ptp(top[:, :, 2], axis=1)
    # the columns' top row 0.25 m high; the braces crossing the water line 0.25 m along
    # their axis, less in z
    assert np.count_nonzero(np.isclose(heights, 0.25, rtol=1e-9)) >= 36 + 3 * 24
    assert heights.max() <= 0.25 * (1 + 1e-9)
    assert graded.full_hull.nb_faces > uniform.full_hull.nb_faces


def test_graded_cylinder_keeps_its_volume():
    geometry = CylinderGeometry(diameter=12.0, draft=14.0, height=20.0, draft_from_mass=False)
    uniform = cylinder_mesh(geometry, panel_size=0.5)
    graded = cylinder_mesh(geometry, panel_size=0.5, waterline_panel_size=0.05)
    assert graded.full_hull.volume == pytest.approx(uniform.full_hull.volume, rel=SAME_SOLID)
    z = np.unique(np.round(graded.full_hull.vertices[:, 2], 9))
    assert z[-1] == 0.0 and z[-1] - z[-2] == pytest.approx(0.05)


def test_default_waterline_panel_size_follows_the_top_wavenumber(deepcwind_case, buoy_case):
    env = deepcwind_case.environment
    k = wavenumber(max(deepcwind_case.hydro.frequencies), env.water_depth, env.gravity)
    assert drift_waterline_panel_size(deepcwind_case) == pytest.approx(DRIFT_WATERLINE_KH / k)
    assert drift_waterline_panel_size(deepcwind_case) == pytest.approx(0.1433, abs=1e-4)
    assert drift_waterline_panel_size(buoy_case) < buoy_case.hydro.panel_size
    from floatmoor.case.load import load_case

    chosen = load_case(DEEPCWIND_CASE, ["hydro.drift_waterline_panel_size=0.5"])
    assert drift_waterline_panel_size(chosen) == 0.5
    # not finer than the database's panels: the uniform mesh
    coarse = load_case(DEEPCWIND_CASE, ["hydro.drift_waterline_panel_size=3.0"])
    assert drift_waterline_panel_size(coarse) is None


def test_drift_waterline_panel_size_must_be_positive():
    from floatmoor.case.load import load_case

    with pytest.raises(CaseError) as info:
        load_case(DEEPCWIND_CASE, ["hydro.drift_waterline_panel_size=-0.1"])
    assert info.value.key == "hydro.drift_waterline_panel_size"


def test_drift_panel_size_sets_the_mesh_below_the_water_line(deepcwind_case):
    from floatmoor.case.load import load_case
    from floatmoor.hydro.drift_build import drift_panel_size

    assert drift_panel_size(deepcwind_case) == 1.4  # the case's key
    assert deepcwind_case.hydro.panel_size == 2.0
    coarser = load_case(DEEPCWIND_CASE, ["hydro.drift_panel_size=2.0"])
    assert drift_panel_size(coarser) == 2.0
    # the water line's default panel is finer than either, so it stays graded
    assert drift_waterline_panel_size(coarser) == drift_waterline_panel_size(deepcwind_case)
    # a water line panel not finer than the drift's own panels: uniform
    assert drift_waterline_panel_size(load_case(DEEPCWIND_CASE, [
        "hydro.drift_panel_size=0.1"])) is None
    with pytest.raises(CaseError) as info:
        load_case(DEEPCWIND_CASE, ["hydro.drift_panel_size=0"])
    assert info.value.key == "hydro.drift_panel_size"
