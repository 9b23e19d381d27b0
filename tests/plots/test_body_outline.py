"""The body in the views: the floater's outline in the side and plan views
and in every animation frame, placed by its 6-DOF motion; its panels in the VTK series; a
semisubmersible's columns in plan; a forced-motion run's polygon through its fairleads; and
one warning line when the body cannot be drawn."""

from __future__ import annotations

import dataclasses
import logging
import re

import numpy as np
import pytest
import xarray as xr
from matplotlib.colors import to_rgb
from scipy.spatial.transform import Rotation

from floatmoor.case.load import load_case
from floatmoor.plots.animation import animate_run
from floatmoor.plots.body_outline import BODY_ALPHA, body_patch, view_polygons
from floatmoor.plots.body_pose import PlacedBody, body_model, placed_body
from floatmoor.plots.body_surface import N_AROUND, body_surface
from floatmoor.plots.context import run_context
from floatmoor.plots.shapes import draw_line_shapes
from floatmoor.plots.style import pyplot
from tests.conftest import CASES

#: Placing the panels is a rotation and a translation of coordinates below 1 m: exact to
#: float64 rounding (about 1e-16 m); 1e-9 m leaves room for the equilibrium fit, which
#: stops at floatmoor.plots.body_pose.OFFSET_TOLERANCE (1e-12 of the body's size) [m].
POSITION_TOL = 1e-9
#: The buoy (cases/cylinder_buoy): diameter 0.515 m, height 0.401 m, draft from its mass
#: 35.85 kg in fresh water, mass / (1000 pi 0.2575^2) = 0.17210 m.
BUOY_RADIUS, BUOY_HEIGHT = 0.2575, 0.401
BUOY_DRAFT = 35.85 / (1000.0 * np.pi * 0.2575**2)
DEEPCWIND = CASES / "deepcwind" / "deepcwind_lc34.toml"
CLUMP_BUOY = CASES / "systems" / "three_line_clump_buoy.toml"
#: Grey of the body's patch over the white axes: 255 - alpha (255 - 0.35 * 255) [0-255];
#: pixels within 6 levels of it on all three channels count as the body's.
BODY_GREY = 255.0 - BODY_ALPHA * (255.0 - 0.35 * 255.0)
GREY_BAND = 6
#: Fewest such pixels a frame shows of the buoy (side patch about 20 x 40 pixels at the
#: animation's 80 dpi, plan patch about 20 x 20; half of that, for lines drawn over it).
MIN_BODY_PIXELS = 600


def _bbox(polygons):
    points = np.concatenate(polygons)
    return points.min(axis=0), points.max(axis=0)


def test_outline_patch_in_side_and_plan_views(dataset):
    context = run_context(dataset)
    samples = [0, 10, 20]
    fig = draw_line_shapes(dataset, samples, context)
    side, plan = fig.axes
    for ax in (side, plan):
        assert len(ax.patches) == len(samples)  # one body patch per drawn time
        for k, patch in enumerate(ax.patches):
            vertices = patch.get_path().vertices
            assert vertices.size > 0 and np.all(np.isfinite(vertices))
            # in the colour of its time's lines
            assert patch.get_facecolor()[:3] == pytest.approx(to_rgb(f"C{k + 1}"))
    vertices = side.patches[1].get_path().vertices
    # the cylinder seen from the side, pitched by theta (roll and yaw are nil in head
    # waves): 2 R cos + H |sin| wide, H cos + 2 R |sin| high (the 36-gon has the extreme
    # points of the circle among its corners)
    theta = float(context.body.offset[4] + dataset["body_displacement"].sel(
        time=1.0, method="nearest").sel(dof="Pitch"))
    c, s = np.cos(theta), abs(np.sin(theta))
    assert np.ptp(vertices, axis=0) == pytest.approx(
        [2 * BUOY_RADIUS * c + BUOY_HEIGHT * s, BUOY_HEIGHT * c + 2 * BUOY_RADIUS * s],
        abs=POSITION_TOL)
    pyplot().close(fig)


def test_outline_centre_follows_the_recorded_motion(dataset):
    """The side view's box centre is the cylinder's axis mid-point placed by the recorded
    motion (rotation by scipy's intrinsic z-y'-x'' Euler angles: an independent R)."""
    context = run_context(dataset)
    body = context.body
    mid = np.array([0.0, 0.0, BUOY_HEIGHT / 2 - BUOY_DRAFT])
    for t in (1.0, 2.0):
        placed = placed_body(body, dataset, t)
        d = dataset["body_displacement"].sel(time=t, method="nearest").values
        x = body.offset + d
        R = Rotation.from_euler("ZYX", [x[5], x[4], x[3]]).as_matrix()
        centre = body.centre + x[:3] + R @ (mid - body.centre)
        lo, hi = _bbox(view_polygons(placed, "side"))
        # a box around the tilted cylinder is centred on its axis mid-point
        assert 0.5 * (lo + hi) == pytest.approx(centre[[0, 2]], abs=POSITION_TOL)
        lo, hi = _bbox(view_polygons(placed, "plan"))
        assert 0.5 * (lo + hi) == pytest.approx(centre[[0, 1]], abs=POSITION_TOL)


def test_outline_moves_with_surge_heave_and_pitch(dataset):
    """A displacement written into the record moves the patch by as much (the buoy's own
    motion in 2 s is below 1 mm: too small to see a sign error)."""
    moved = dataset.copy(deep=True)
    k = int(np.argmin(np.abs(moved["time"].values - 1.0)))
    dofs = list(moved["dof"].values)
    for dof, value in {"Surge": 0.3, "Heave": -0.05, "Pitch": 0.2}.items():
        moved["body_displacement"].values[k, dofs.index(dof)] = value
    context = run_context(moved)
    still = placed_body(context.body, moved, 0.0)
    placed = placed_body(context.body, moved, 1.0)
    x = context.body.offset + moved["body_displacement"].values[k]
    R = Rotation.from_euler("ZYX", [x[5], x[4], x[3]]).as_matrix()
    rest = context.body.surface.vertices
    want = context.body.centre + x[:3] + (rest - context.body.centre) @ R.T
    np.testing.assert_allclose(placed.vertices, want, rtol=0, atol=POSITION_TOL)
    # the side patch's box centre moved by surge and heave plus the pitch's turn of the
    # axis mid-point about the reference point
    mid = np.array([0.0, 0.0, BUOY_HEIGHT / 2 - BUOY_DRAFT])
    lo0, hi0 = _bbox(view_polygons(still, "side"))
    lo1, hi1 = _bbox(view_polygons(placed, "side"))
    turn = R @ mid - mid
    assert 0.5 * (lo1 + hi1) - 0.5 * (lo0 + hi0) == pytest.approx(
        [0.3 + turn[0], -0.05 + turn[2]], abs=1e-6)  # x_eq's pitch ~4e-9 rad at rest
    fig = draw_line_shapes(moved, [0, 10], context)
    side = fig.axes[0]
    assert side.patches[1].get_path().vertices[:, 0].max() > \
        side.patches[0].get_path().vertices[:, 0].max() + 0.25
    pyplot().close(fig)


def test_equilibrium_offset_places_the_fairleads_where_the_run_recorded_them(dataset):
    """x_eq + d with the kinematics' rotation puts the body points on their recorded
    positions at every output time (the convention and the fitted x_eq together)."""
    context = run_context(dataset)
    body = context.body
    case = load_case(CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml")
    rest = np.array([case.point(name).position for name in body.points])
    from floatmoor.plots.body_surface import BodySurface

    points = BodySurface(rest, np.zeros((0, 4), dtype=np.int64))
    assert body.offset[2] < 0.0  # the chains' weight sinks the buoy (3.6 mm)
    for k in range(0, dataset.sizes["time"], 20):
        x = body.offset + dataset["body_displacement"].isel(time=k).values
        seen = dataset["point_position"].sel(point=list(body.points)).isel(time=k) \
            .transpose("point", "component").values
        np.testing.assert_allclose(points.placed(x, body.centre), seen, rtol=0,
                                   atol=POSITION_TOL)


def _frame(gif, frame: int) -> np.ndarray:
    from PIL import Image

    with Image.open(gif) as image:
        image.seek(frame)
        return np.asarray(image.convert("RGB"), dtype=int)


def test_every_animation_frame_shows_the_body(dataset, tmp_path):
    """Each frame differs from the same animation drawn without the body by the body's
    patches, in grey where no line crosses them."""
    context = run_context(dataset)
    samples = [0, 20]
    with_body, without = tmp_path / "with.gif", tmp_path / "without.gif"
    assert animate_run(dataset, with_body, samples, fps=2, context=context) == 2
    animate_run(dataset, without, samples, fps=2,
                context=dataclasses.replace(context, body=None))
    for k in range(len(samples)):
        drawn, bare = _frame(with_body, k), _frame(without, k)
        changed = np.any(drawn != bare, axis=2)
        grey = changed & (np.ptp(drawn, axis=2) <= GREY_BAND) \
            & (np.abs(drawn[..., 0] - BODY_GREY) <= GREY_BAND)
        # the buoy's side patch is about 20 x 40 pixels, its plan patch about 20 x 20
        assert grey.sum() > MIN_BODY_PIXELS, (k, int(changed.sum()), int(grey.sum()))


def test_vtk_body_panels_round_trip(buoy_run, dataset):
    import meshio

    pvd = (buoy_run["vtk"] / "lines.pvd").read_text()
    parts = re.findall(r'timestep="([^"]+)" group="" part="1" file="([^"]+)"', pvd)
    assert len(parts) == dataset.sizes["shape_time"]
    context = run_context(dataset)
    for time, name in (parts[0], parts[13]):
        mesh = meshio.read(buoy_run["vtk"] / name)
        placed = placed_body(context.body, dataset, float(time))
        np.testing.assert_array_equal(mesh.points, placed.vertices)
        # a closed tube: N_AROUND wall quads and N_AROUND triangles on each end
        assert len(mesh.cells_dict["quad"]) == N_AROUND
        assert len(mesh.cells_dict["triangle"]) == 2 * N_AROUND


def test_semisubmersible_plan_view_shows_its_four_columns():
    """DeepCwind (OC4): a centre column of 6.5 m and three offset columns of 12 m on 24 m
    heave plates, 28.87 m from the centre; the plan view holds each circle and leaves the
    water between the columns open."""
    floater = load_case(DEEPCWIND).floater
    surface = body_surface(floater)
    placed = PlacedBody(surface.vertices, surface.faces, np.zeros(6))
    plt = pyplot()
    fig, ax = plt.subplots()
    path = body_patch(ax, placed, "plan").get_path()
    vertices = np.unique(np.round(path.vertices, 9), axis=0)
    columns = floater.geometry.columns
    assert len(columns) == 4
    for c in columns:
        radii = [0.5 * c.diameter] + ([0.5 * c.heave_plate_diameter]
                                      if c.heave_plate_diameter is not None else [])
        distance = np.hypot(vertices[:, 0] - c.x, vertices[:, 1] - c.y)
        for r in radii:  # every corner of the drawn circle is in the patch
            assert np.sum(np.abs(distance - r) < 1e-6) >= N_AROUND, (c, r)
        assert path.contains_point((c.x, c.y))
    offset = [c for c in columns if np.hypot(c.x, c.y) > 1.0]
    assert sorted(round(float(np.degrees(np.arctan2(c.y, c.x))) % 360) for c in offset) \
        == [0, 120, 240]
    # between two offset columns, inside the delta of pontoons: open water
    gap = 9.0 * np.array([np.cos(np.pi / 3), np.sin(np.pi / 3)])
    assert not path.contains_point(gap)
    lo, hi = path.vertices.min(axis=0), path.vertices.max(axis=0)
    assert hi[0] == pytest.approx(28.867513 + 12.0, abs=1e-6)  # the +x plate's edge
    plt.close(fig)


def test_forced_body_motion_draws_the_polygon_through_its_fairleads():
    """A ``[motion] kind = "body"`` run has no hull: its body is the polygon through the
    body-carried points at each time (here a record written by hand)."""
    case = load_case(CLUMP_BUOY)
    names = [p.name for p in case.points]
    rest = np.array([p.position for p in case.points])
    shift = np.array([5.0, -2.0, 1.0])
    position = np.stack([rest, rest + shift], axis=1)  # (point, time, component)
    ds = xr.Dataset({"point_position": (("point", "time", "component"), position)},
                    coords={"point": names, "time": [0.0, 1.0],
                            "component": ["x", "y", "z"]})
    model = body_model(case, ds)
    assert model is not None and model.surface is None
    assert model.points == ("fairlead1", "fairlead2", "fairlead3")
    placed = placed_body(model, ds, 1.0)
    assert placed.faces is None
    fairleads = np.array([case.point(n).position for n in model.points]) + shift
    (polygon,) = view_polygons(placed, "plan")
    assert len(polygon) == 3  # the triangle through the three fairleads
    assert sorted(map(tuple, np.round(polygon, 9))) == sorted(
        map(tuple, np.round(fairleads[:, :2], 9)))
    x, y = polygon[:, 0], polygon[:, 1]
    assert np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) > 0.0  # counter-clockwise
    # seen from the side the three fairleads (all at z = -10 m + 1 m) make a segment
    (segment,) = view_polygons(placed, "side")
    assert len(segment) == 2 and np.allclose(segment[:, 1], -9.0)


def test_a_run_whose_case_does_not_re_read_is_drawn_without_the_body(dataset, caplog):
    broken = dataset.copy()
    broken.attrs = dict(dataset.attrs, case_toml="[not a case")
    with caplog.at_level(logging.WARNING, logger="floatmoor.plots"):
        context = run_context(broken)
    assert context.body is None
    (record,) = caplog.records
    message = record.getMessage()
    assert "\n" not in message and "drawn without the body" in message
    fig = draw_line_shapes(broken, [0, 20], context)
    assert not fig.axes[0].patches and not fig.axes[1].patches
    pyplot().close(fig)


def test_mesh_hull_is_the_whole_file_mirrored_scaled_and_placed(tmp_path):
    """A quarter hull in millimetres (GDF flags ISX = ISY = 1, declared symmetric), moved by
    ``position``, is drawn as the whole hull: the full file's panels, moved."""
    from floatmoor.io.bem_data import BemFileError
    from tests.hydro.mesh_files import quarter, tiny_faces, write_case, write_gdf

    faces = tiny_faces()
    position = np.array([0.5, -0.2, 0.1])
    write_gdf(tmp_path / "full.gdf", faces)
    write_gdf(tmp_path / "quarter.gdf", quarter(faces) * 1000.0, isx=1, isy=1)
    full = body_surface(load_case(write_case(
        tmp_path, 'kind = "mesh"\nfile = "full.gdf"', name="full.toml")).floater)
    case = load_case(write_case(
        tmp_path, 'kind = "mesh"\nfile = "quarter.gdf"\nlength_unit = "mm"\n'
        'symmetry = ["xz", "yz"]\nposition = [0.5, -0.2, 0.1]', name="quarter.toml"))
    surface = body_surface(case.floater)
    assert len(surface.faces) == len(full.faces)

    def panel_set(s, shift):
        return sorted(tuple(sorted(set(map(tuple, np.round(s.vertices[f] + shift, 9)))))
                      for f in s.faces)

    assert panel_set(surface, 0.0) == panel_set(full, position)
    # mirrored triangles keep the convention: their third vertex repeated
    assert np.sum(surface.faces[:, 3] == surface.faces[:, 2]) == \
        np.sum(full.faces[:, 3] == full.faces[:, 2])
    (tmp_path / "quarter.gdf").write_text("changed\n")
    with pytest.raises(BemFileError, match="changed since"):
        body_surface(case.floater)


def test_vtk_polygon_through_a_forced_bodys_points(dataset, tmp_path):
    """The forced body's VTK part: one polygon through its points in turn, whatever order
    the case lists them in (here five corners of a tilted pentagon, shuffled)."""
    import meshio

    from floatmoor.io.vtk import write_vtk_series
    from floatmoor.plots.body_pose import polygon_through

    phi = 2.0 * np.pi * np.arange(5) / 5
    ring = np.column_stack([10 * np.cos(phi), 10 * np.sin(phi), np.zeros(5)])
    R = Rotation.from_euler("ZYX", [0.3, 0.4, 0.5]).as_matrix()
    shuffle = [3, 0, 4, 1, 2]
    points = ring[shuffle] @ R.T + [1.0, 2.0, -5.0]
    order = polygon_through(points)[0]
    around = np.array(shuffle)[order]  # the ring's own indices, in the polygon's turn
    steps = np.diff(np.concatenate([around, around[:1]])) % 5
    assert set(steps) in ({1}, {4})  # each corner next to its neighbour on the ring
    pvd = write_vtk_series(dataset, tmp_path, [0],
                           body=lambda t: (points, polygon_through(points)))
    assert 'part="1" file="body_000000.vtu"' in pvd.read_text()
    mesh = meshio.read(tmp_path / "body_000000.vtu")
    np.testing.assert_array_equal(mesh.points, points)
    np.testing.assert_array_equal(mesh.cells_dict["polygon"], polygon_through(points))
