"""The views of a run: every figure rendered for a short buoy run and looked at
for content (axes labelled with units, no empty or NaN series), the animation's frame count,
the VTK series read back through meshio, and bad arguments refused with status 2."""

from __future__ import annotations

import re

import numpy as np
import pytest

from floatmoor.cli import main
from floatmoor.io.shape_samples import ShapeDataError, line_shape, node_count, \
    window_samples
from floatmoor.plots.context import run_context
from floatmoor.plots.motions import draw_body_motions
from floatmoor.plots.run_figures import figure_paths
from floatmoor.plots.shapes import draw_line_shapes
from floatmoor.plots.style import tension_unit
from floatmoor.plots.tensions import draw_tension_along_line, draw_tensions
from floatmoor.post.line_shapes import touchdown_point
from tests.plots.conftest import BUOY, RUN, SHAPES

#: An axis label names its unit in brackets: "tension [N]", "pitch [deg]".
UNIT = re.compile(r"\[[^\]]+\]$")
#: The touchdown point is interpolated linearly between the last node on the seabed and the
#: first lifted one; the catenary leaves the seabed tangentially, z = (w / 2T) s^2 above it, so
#: the chord lies at most (w / 2T) ds^2 above the seabed: w = 0.1447 * 9.81 * (1 - 1000 / 7800)
#: = 1.238 N/m (the buoy's chain), T >= 1.9 N at touchdown (its tension there), node spacing
#: ds = 6.95 / 50 = 0.139 m: 6.3e-3 m [m].
SEABED_TOL = 1.238 / (2.0 * 1.9) * 0.139**2


def _check_figure(fig) -> int:
    """Assert every axes with data has unit-labelled axes and finite, non-empty series;
    returns the number of series drawn."""
    series = 0
    for ax in fig.axes:
        lines = [ln for ln in ax.get_lines() if len(ln.get_xdata()) > 0]
        if not lines and not ax.collections:
            continue
        # panels sharing the time axis carry its label on the bottom one
        xlabels = [a.get_xlabel() for a in ax.get_shared_x_axes().get_siblings(ax)]
        assert any(UNIT.search(label) for label in xlabels), xlabels
        assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()
        for ln in ax.get_lines():
            x = np.asarray(ln.get_xdata(), dtype=float)
            y = np.asarray(ln.get_ydata(), dtype=float)
            assert x.size > 0 and y.size == x.size, ln.get_label()
            assert np.all(np.isfinite(x)) and np.all(np.isfinite(y)), ln.get_label()
            series += 1
        for formatter in (ax.xaxis.get_major_formatter(), ax.yaxis.get_major_formatter()):
            assert getattr(formatter, "get_offset", lambda: "")() == ""  # no offset/exponent
    return series


def test_run_plot_writes_every_view_of_a_floater_run_with_shapes(buoy_run):
    paths = figure_paths(buoy_run["png"], floater=True, shapes=True)
    assert list(paths) == ["tensions", "motions", "shapes", "line_tension"]
    from PIL import Image

    for path in paths.values():
        with Image.open(path) as image:
            assert image.format == "PNG" and min(image.size) > 300


def test_tension_histories_in_labelled_units(dataset):
    fig = draw_tensions(dataset, ramp_duration=20.0)
    # 3 lines x (fairlead, anchor); the buoy's chains hold ~3 N: drawn in N
    assert _check_figure(fig) == 6
    assert [ax.get_ylabel() for ax in fig.axes] == ["tension [N]"] * 3
    top = max(np.max(ln.get_ydata()) for ax in fig.axes for ln in ax.get_lines())
    assert top == pytest.approx(float(dataset["fairlead_tension"].max()), rel=1e-12)


def test_tension_unit_follows_the_size():
    assert tension_unit([3.0]) == (1.0, "N")
    assert tension_unit([2.5e5, -1.0]) == (1e3, "kN")
    assert tension_unit([4e6]) == (1e6, "MN")


def test_body_motions_in_metres_and_degrees(dataset):
    fig = draw_body_motions(dataset, ramp_duration=20.0)
    assert _check_figure(fig) == 4  # surge, heave, pitch and the wave elevation
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["surge [m]", "heave [m]", "pitch [deg]", "wave elevation [m]"]
    pitch = fig.axes[2].get_lines()[0].get_ydata()
    np.testing.assert_allclose(pitch, np.degrees(dataset["body_displacement"]
                                                 .sel(dof="Pitch").values), rtol=1e-12)
    assert "sway, roll, yaw" in fig._suptitle.get_text()


def test_line_shapes_with_seabed_water_line_and_touchdown(dataset):
    context = run_context(dataset)
    assert context.water_depth == pytest.approx(0.9)
    samples = [0, 10, 20]
    fig = draw_line_shapes(dataset, samples, context)
    _check_figure(fig)
    side, plan = fig.axes
    assert (side.get_xlabel(), side.get_ylabel()) == ("x [m]", "z [m]")
    assert (plan.get_xlabel(), plan.get_ylabel()) == ("x [m]", "y [m]")
    labels = [ln.get_label() for ln in side.get_lines()]
    assert "still water line z = 0" in labels and "seabed z = -0.9 m" in labels
    # 3 lines at 3 times in each view
    drawn = [ln for ln in side.get_lines() if len(ln.get_xdata()) == 51]
    assert len(drawn) == 9
    touch = [ln for ln in side.get_lines() if ln.get_marker() == "x"]
    assert len(touch) == 9
    for ln in touch:
        assert abs(ln.get_ydata()[0] + 0.9) < SEABED_TOL


def test_touchdown_point_at_the_laid_length(dataset):
    shape = line_shape(dataset, "line3", 10)
    laid = float(dataset["laid_length"].sel(line="line3").sel(time=shape.time))
    point = touchdown_point(dataset, shape)
    assert 0.0 < laid < shape.arc_length[-1]
    # the anchor is at x = 6.9175 and the line runs to -x along the seabed
    assert point[0] == pytest.approx(6.9175 - laid, abs=1e-3 * laid)
    assert point[2] == pytest.approx(-0.9, abs=SEABED_TOL)


def test_tension_along_the_line_and_envelope(dataset):
    fig = draw_tension_along_line(dataset, [5, 15], start=0.5)
    _check_figure(fig)
    for ax, name in zip(fig.axes, dataset["line"].values):
        assert ax.get_xlabel() == "arc length from the anchor [m]"
        assert ax.get_ylabel() == "tension [N]"
        env = ax.collections[0]  # the min-max band
        assert "envelope 0.5 to 2 s (16 shapes)" in env.get_label()
        at = [ln for ln in ax.get_lines() if ln.get_label().startswith("t = ")]
        assert [ln.get_label() for ln in at] == ["t = 0.5 s", "t = 1.5 s"]
        lo, hi = ax.get_lines()[0].get_ydata(), ax.get_lines()[1].get_ydata()
        for ln in at:  # every drawn time inside its envelope
            assert np.all(ln.get_ydata() >= lo - 1e-12) and np.all(ln.get_ydata() <= hi + 1e-12)
        # the top of the envelope at the fairlead is the largest fairlead tension after 0.5 s
        ft = dataset["fairlead_tension"].sel(line=name).sel(time=slice(0.5, None))
        shape_times = dataset["shape_time"].values[5:]
        assert hi[-1] == pytest.approx(float(ft.sel(time=shape_times, method="nearest").max()),
                                       rel=1e-9)


def test_animation_frame_count_and_content(buoy_run):
    from PIL import Image

    gif = buoy_run["folder"] / "buoy.gif"
    assert main(["animate", str(buoy_run["nc"]), "-o", str(gif), "--every", "5",
                 "--fps", "4", "--quiet"]) == 0
    with Image.open(gif) as image:
        assert image.n_frames == len(range(0, SHAPES, 5))  # t = 0, 0.5, 1, 1.5, 2 s
        image.seek(2)
        pixels = np.asarray(image.convert("RGB")).reshape(-1, 3)
    # the lines are drawn in C1, C2, C3 (orange, green, red): each colours some pixels
    for colour in ((255, 127, 14), (44, 160, 44), (214, 39, 40)):
        assert np.any(np.all(np.abs(pixels.astype(int) - colour) < 40, axis=1)), colour


def test_animation_draws_the_still_figure_once(buoy_run, monkeypatch):
    # blitting: the axes, ticks and legend are drawn once, each frame draws only the moving
    # artists (drawing the whole figure twice per frame took 0.4 s a frame: 124 s for 301);
    # the frames still differ, and show the body patch and the clock
    from matplotlib.figure import Figure
    from PIL import Image

    draws = []
    whole = Figure.draw
    monkeypatch.setattr(Figure, "draw", lambda self, renderer: draws.append(1) or
                        whole(self, renderer))
    gif = buoy_run["folder"] / "blit.gif"
    assert main(["animate", str(buoy_run["nc"]), "-o", str(gif), "--quiet"]) == 0
    assert len(draws) == 1
    with Image.open(gif) as image:
        assert image.n_frames == SHAPES
        frames = []
        for k in (0, SHAPES - 1):
            image.seek(k)
            frames.append(np.asarray(image.convert("RGB")))
    assert np.any(frames[0] != frames[1])


def test_animation_window_selects_frames(dataset):
    assert window_samples(dataset, start=0.5, end=1.0) == [5, 6, 7, 8, 9, 10]
    assert window_samples(dataset, every=10) == [0, 10, 20]
    with pytest.raises(ShapeDataError, match="0 to 2 s"):
        window_samples(dataset, start=3.0)


def test_vtk_round_trip_through_meshio(buoy_run, dataset):
    import meshio

    pvd = (buoy_run["vtk"] / "lines.pvd").read_text()
    files = re.findall(r'part="0" file="([^"]+)"', pvd)
    times = [float(t) for t in re.findall(r'timestep="([^"]+)" group="" part="0"', pvd)]
    assert len(files) == SHAPES
    np.testing.assert_allclose(times, dataset["shape_time"].values, rtol=0, atol=0)
    for k in (0, 13):
        mesh = meshio.read(buoy_run["vtk"] / files[k])
        want = [line_shape(dataset, str(n), k) for n in dataset["line"].values]
        np.testing.assert_array_equal(mesh.points, np.concatenate([s.position for s in want]))
        np.testing.assert_array_equal(mesh.point_data["tension"],
                                      np.concatenate([s.tension for s in want]))
        cells = mesh.cells_dict["line"]
        assert cells.shape == (sum(s.arc_length.size - 1 for s in want), 2)
        assert np.all(cells[:, 1] == cells[:, 0] + 1)
        np.testing.assert_array_equal(np.bincount(mesh.cell_data["line_index"][0]),
                                      [s.arc_length.size - 1 for s in want])


def test_vtk_command_writes_the_chosen_window(buoy_run, tmp_path):
    assert main(["vtk", str(buoy_run["nc"]), "-o", str(tmp_path / "v"), "--start", "1",
                 "--every", "2", "--quiet"]) == 0
    samples = [10, 12, 14, 16, 18, 20]
    from floatmoor.io.output_folders import MANIFEST_NAME

    assert sorted(p.name for p in (tmp_path / "v").iterdir()) == sorted(
        ["lines.pvd", MANIFEST_NAME] + [f"lines_{k:06d}.vtu" for k in samples]
        + [f"body_{k:06d}.vtu" for k in samples])


def test_node_count_cuts_the_padding():
    assert node_count(np.array([0.0, 1.0, 2.0, 2.0, 2.0])) == 3
    assert node_count(np.array([0.0, 1.0, 2.0])) == 3


@pytest.mark.parametrize("args, message", [
    (["--fps", "0"], "--fps: expected a number > 0"),
    (["--fps", "nan"], "--fps: expected a number > 0"),
    (["--every", "0"], "--every: expected a whole number >= 1"),
    (["--every", "1.5"], "--every: expected a whole number >= 1"),
    (["--start", "-1"], "--start: expected a time >= 0"),
    (["--start", "1", "--end", "0.5"], "--end: expected a time >= --start"),
    (["--start", "5"], "expected a window holding line-shape samples"),
    (["-o", "{folder}/out.avi"], "expected an animation file (.gif, .mp4)"),
    (["-o", "{nc}"], "expected an animation file"),
])
def test_animate_bad_arguments_exit_2_and_write_nothing(buoy_run, capsys, args, message):
    out = buoy_run["folder"] / "bad.gif"
    argv = ["animate", str(buoy_run["nc"]), "-o", str(out), "--quiet"]
    argv += [a.format(folder=buoy_run["folder"], nc=buoy_run["nc"]) for a in args]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err
    assert not out.exists() and not (buoy_run["folder"] / "out.avi").exists()


def test_mp4_without_ffmpeg_is_refused(buoy_run, capsys):
    from matplotlib import animation

    if animation.writers.is_available("ffmpeg"):
        pytest.skip("ffmpeg is installed here: .mp4 files are written")
    out = buoy_run["folder"] / "run.mp4"
    assert main(["animate", str(buoy_run["nc"]), "-o", str(out)]) == 2
    assert "ffmpeg" in capsys.readouterr().err and not out.exists()


def test_views_of_a_run_without_shapes_are_refused(dataset, tmp_path, capsys):
    from floatmoor.io.netcdf import write_dataset

    out = tmp_path / "noshape.nc"
    write_dataset(dataset.drop_vars(["shape_position", "shape_tension", "arc_length",
                                     "shape_time"]), out)
    for argv in (["animate", str(out), "-o", str(tmp_path / "a.gif")],
                 ["vtk", str(out), "-o", str(tmp_path / "v")]):
        assert main(argv) == 2
        assert "holds no line shapes" in capsys.readouterr().err
    assert main(["run", str(BUOY), "--set", "simulation.duration=0.2", "-o",
                 str(tmp_path / "x.nc"), "--vtk", str(tmp_path / "v")]) == 2
    assert "--vtk: expected a case that records line shapes" in capsys.readouterr().err
    assert main(["run", str(BUOY), *RUN, "-o", str(tmp_path / "x.nc"), "--plot",
                 str(tmp_path / "x.png"), "--plot-times", "0.5,7"]) == 2
    assert "--plot-times: expected comma-separated times from 0 to 2 s" in \
        capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["noshape.nc"]


def test_a_partial_run_shows_its_complete_shapes_only(dataset):
    """An interrupted run leaves NaN in its unfinished shape samples: the views stop before
    them, and a run with none complete has no shape views."""
    from floatmoor.io.shape_samples import has_complete_shapes

    partial = dataset.copy(deep=True)
    for name in ("shape_position", "shape_tension"):
        partial[name][{"shape_time": slice(15, None)}] = np.nan
    assert window_samples(partial) == list(range(15))
    assert window_samples(partial, every=7) == [0, 7, 14]
    fig = draw_tension_along_line(partial, [14], start=0.0)
    assert "envelope 0 to 1.4 s (15 shapes)" in fig.axes[0].collections[0].get_label()
    assert has_complete_shapes(partial)
    for name in ("shape_position", "shape_tension"):
        partial[name][:] = np.nan
    assert not has_complete_shapes(partial)
    with pytest.raises(ShapeDataError, match="none complete among 21"):
        window_samples(partial)
