"""Line shapes of one run at chosen times: side view (x-z) and plan view (x-y), with the
seabed, the still water line z = 0, the anchors, the touchdown points and the body's outline
(:mod:`floatmoor.plots.body_outline`) at each time.

The scene helpers (:func:`frame`, :func:`scene_limits`, :func:`draw_references`) are shared
with :mod:`floatmoor.plots.animation`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.io.shape_samples import LineShape, line_shape
from floatmoor.plots.body_outline import body_patch
from floatmoor.plots.body_pose import PlacedBody, placed_body
from floatmoor.plots.context import RunContext
from floatmoor.plots.series import check_series
from floatmoor.plots.style import figure_title, plain_axes, pyplot
from floatmoor.post.line_shapes import touchdown_point

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_line_shapes", "Frame", "frame", "scene_limits",
           "draw_references", "SCENE_MARGIN"]

#: Margin around the drawn lines, as a fraction of the larger extent of a view.
SCENE_MARGIN = 0.05


@dataclass(frozen=True)
class Frame:
    """The lines and the floater at one shape sample.

    Attributes
    ----------
    time
        [s]
    shapes
        One per line, in dataset order.
    touchdowns
        The touchdown point of each line [m], or None.
    body
        The floater's reference point displaced [m] (None without a floater).
    outline
        The body placed at ``time`` (None when the run's body is not drawn).
    """

    time: float
    shapes: list[LineShape]
    touchdowns: list[NDArray[np.float64] | None]
    body: NDArray[np.float64] | None
    outline: PlacedBody | None = None


def frame(dataset: xr.Dataset, sample: int, context: RunContext) -> Frame:
    """The :class:`Frame` of shape sample ``sample`` (positions checked finite).

    Raises
    ------
    FigureDataError
        When a node position is not finite.
    """
    shapes = []
    for name in dataset["line"].values:
        shape = line_shape(dataset, str(name), sample)
        check_series(shape.position, f"shape of line {name} at t = {shape.time:g} s")
        shapes.append(shape)
    t = shapes[0].time
    body = outline = None
    if context.body is not None:
        outline = placed_body(context.body, dataset, t)
        check_series(outline.vertices, f"body at t = {t:g} s")
    if outline is not None and outline.displacement is not None:
        body = np.asarray(context.reference_point) + outline.displacement[:3]
    elif "body_displacement" in dataset:  # no body model: the centre x_eq + d (d: older files)
        disp = dataset["body_displacement"].sel(time=t, method="nearest")
        if "body_equilibrium" in dataset:
            disp = disp + dataset["body_equilibrium"]
        body = np.asarray(context.reference_point) + np.array(
            [float(disp.sel(dof=d)) for d in ("Surge", "Sway", "Heave")])
    return Frame(t, shapes, [touchdown_point(dataset, s) for s in shapes], body, outline)


def scene_limits(frames: Sequence[Frame], context: RunContext
                 ) -> tuple[tuple[float, float], tuple[float, float], tuple[float, float]]:
    """(x, y, z) axis limits [m] holding every line and body of ``frames``, the seabed and
    z = 0."""
    points = np.concatenate([s.position for f in frames for s in f.shapes]
                            + [f.outline.vertices for f in frames if f.outline is not None])
    lo, hi = points.min(axis=0), points.max(axis=0)
    hi[2] = max(hi[2], 0.0)
    if context.water_depth is not None:
        lo[2] = min(lo[2], -context.water_depth)
    size = float(max(hi - lo))
    pad = SCENE_MARGIN * (size if size > 0.0 else 1.0)
    return tuple((float(a - pad), float(b + pad)) for a, b in zip(lo, hi))  # type: ignore


def draw_references(side, plan, context: RunContext, xlim: tuple[float, float]) -> None:
    """The seabed and the still water line in the side view; labelled axes in both."""
    side.axhline(0.0, color="C0", lw=0.9, ls="--", label="still water line z = 0")
    if context.water_depth is not None:
        side.axhline(-context.water_depth, color="saddlebrown", lw=1.4,
                     label=f"seabed z = {-context.water_depth:g} m")
    side.set_xlim(*xlim)
    side.set_xlabel("x [m]")
    side.set_ylabel("z [m]")
    plan.set_xlabel("x [m]")
    plan.set_ylabel("y [m]")
    for ax in (side, plan):
        ax.grid(alpha=0.3)
        plain_axes(ax)


def draw_line_shapes(dataset: xr.Dataset, samples: Sequence[int],
                     context: RunContext) -> Figure:
    """Side (x-z) and plan (x-y) views of every line at the shape samples ``samples`` (one
    colour per time), with anchors, touchdown points, the seabed, z = 0 and the body's
    outline at each time (``context.body``).

    Parameters
    ----------
    dataset
        A run's result dataset with line shapes.
    samples
        Indices of the shape samples to draw.
    context
        What the views take from the run's case (:func:`floatmoor.plots.context.run_context`).

    Returns
    -------
    matplotlib.figure.Figure
        The figure (not saved).

    Raises
    ------
    ShapeDataError
        Without shapes.
    FigureDataError
        When a shape is not finite.
    """
    frames = [frame(dataset, k, context) for k in samples]
    xlim, _, zlim = scene_limits(frames, context)
    plt = pyplot()
    fig, (side, plan) = plt.subplots(2, 1, figsize=(9.0, 9.0),
                                     gridspec_kw={"height_ratios": [1.0, 1.3]})
    draw_references(side, plan, context, xlim)
    for i, fr in enumerate(frames):
        colour = f"C{(i + 1) % 10}"
        for j, (shape, td) in enumerate(zip(fr.shapes, fr.touchdowns)):
            label = f"t = {fr.time:g} s" if j == 0 else None
            side.plot(shape.position[:, 0], shape.position[:, 2], color=colour, lw=1.1,
                      label=label)
            plan.plot(shape.position[:, 0], shape.position[:, 1], color=colour, lw=1.1)
            if td is not None:
                tlabel = "touchdown point" if i == 0 and j == 0 else None
                side.plot(td[0], td[2], "x", color="k", ms=6, label=tlabel)
                plan.plot(td[0], td[1], "x", color="k", ms=6)
        if fr.outline is not None:
            body_patch(side, fr.outline, "side", colour=colour,
                       label="body (colour of its time)" if i == 0 else None)
            body_patch(plan, fr.outline, "plan", colour=colour)
        if fr.body is not None:
            side.plot(fr.body[0], fr.body[2], "o", color=colour, ms=5, mfc="none")
            plan.plot(fr.body[0], fr.body[1], "o", color=colour, ms=5, mfc="none")
    anchors = np.array([s.position[0] for s in frames[0].shapes])
    side.plot(anchors[:, 0], anchors[:, 2], "s", color="k", ms=5, label="anchors")
    plan.plot(anchors[:, 0], anchors[:, 1], "s", color="k", ms=5)
    for shape in frames[0].shapes:
        plan.annotate(shape.line, shape.position[0, :2], textcoords="offset points",
                      xytext=(4, 4), fontsize=8)
    side.set_ylim(*zlim)
    plan.set_aspect("equal", adjustable="datalim")
    side.set_title("side view (x-z)" + (", circles: floater reference point"
                                        if frames[0].body is not None else ""), fontsize=10)
    plan.set_title("plan view (x-y)", fontsize=10)
    side.legend(loc="upper left", bbox_to_anchor=(1.005, 1.0), fontsize=8)
    fig.suptitle(figure_title(dataset.attrs.get("title")) + "\nline shapes", fontsize=11)
    fig.tight_layout()
    return fig
