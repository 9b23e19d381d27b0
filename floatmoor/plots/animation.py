"""Animation of a run's line shapes and floater: side (x-z) and plan (x-y) views, one frame
per chosen shape sample, written by matplotlib's animation writers (GIF through Pillow, MP4
through ffmpeg when it is installed).

The floater is drawn as its outline (:mod:`floatmoor.plots.body_outline`, placed by its 6-DOF
motion at each frame) and its reference point displaced by surge, sway and heave, joined by
thin spokes to the line fairleads (body-fixed points, so the spokes turn with the body); the
body of a ``[motion] kind = "body"`` run as the polygon through its body-carried points.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Sequence

import numpy as np
import xarray as xr

from floatmoor.errors import FloatmoorError
from floatmoor.io.output_files import atomic_target
from floatmoor.plots.body_outline import body_patch, update_body_patch
from floatmoor.plots.context import RunContext, run_context
from floatmoor.plots.shapes import draw_references, frame, scene_limits
from floatmoor.plots.style import figure_title, pyplot

__all__ = ["AnimationWriterError", "ANIMATION_WRITERS", "animation_writer", "animate_run"]

#: Output suffix -> matplotlib writer name.
ANIMATION_WRITERS = {".gif": "pillow", ".mp4": "ffmpeg"}
#: Resolution of animation frames [dots per inch] (a 9 x 7.5 inch figure: 720 x 600 pixels).
ANIMATION_DPI = 80


class AnimationWriterError(FloatmoorError, ValueError):
    """The animation's file type is not supported, or its writer is not installed."""


def animation_writer(path: str | Path, fps: float):
    """The matplotlib writer for ``path`` (by suffix) at ``fps`` frames per second.

    Raises
    ------
    AnimationWriterError
        For another suffix, or when the writer's program (ffmpeg for .mp4) is missing.
    """
    pyplot()
    from matplotlib import animation

    suffix = Path(path).suffix.lower()
    if suffix not in ANIMATION_WRITERS:
        raise AnimationWriterError(f"-o/--output: expected an animation file ("
                                   + ", ".join(ANIMATION_WRITERS) + f"), found '{path}'")
    name = ANIMATION_WRITERS[suffix]
    if not animation.writers.is_available(name):
        raise AnimationWriterError(f"-o/--output: {suffix} files need matplotlib's '{name}' "
                                   f"writer (the {name} program), which is not installed; "
                                   "write a .gif instead (Pillow, installed with matplotlib)")
    return animation.writers[name](fps=fps)


def animate_run(dataset: xr.Dataset, path: str | Path, samples: Sequence[int], *,
                fps: float = 10.0,
                progress: Callable[[int, int], None] | None = None,
                context: RunContext | None = None) -> int:
    """Write the animation of the shape samples ``samples`` to ``path``; returns the number
    of frames written.

    Parameters
    ----------
    dataset
        A run's result dataset with line shapes.
    path
        The animation file (``.gif``, or ``.mp4`` with ffmpeg).
    samples
        Indices of the shape samples, one frame each.
    fps
        Frames per second.
    progress
        Called with (done, total) after each frame.
    context
        What the views take from the run's case (default: :func:`run_context` of
        ``dataset``).

    Returns
    -------
    int
        The number of frames written.

    Raises
    ------
    AnimationWriterError
        When ``path`` cannot be written by any installed writer (checked first).
    ShapeDataError, FigureDataError
        Without shapes, or with a shape that is not finite.
    OutputWriteError
        When the file cannot be written (written atomically: an old file is kept).
    """
    writer = animation_writer(path, fps)

    context = run_context(dataset) if context is None else context
    frames = [frame(dataset, k, context) for k in samples]
    xlim, _, zlim = scene_limits(frames, context)
    fairleads = None
    if frames[0].body is not None:
        fairleads = np.asarray(dataset["fairlead_position"].transpose("time", "line",
                                                                      "component").values)
    times = np.asarray(dataset["time"].values, dtype=float)
    plt = pyplot()
    fig, (side, plan) = plt.subplots(1, 2, figsize=(11.0, 5.0), dpi=ANIMATION_DPI,
                                     gridspec_kw={"width_ratios": [1.4, 1.0]})
    draw_references(side, plan, context, xlim)
    side.set_ylim(*zlim)
    _, ylim, _ = scene_limits(frames, context)
    plan.set_xlim(*xlim)
    plan.set_ylim(*ylim)
    plan.set_aspect("equal", adjustable="box")
    n_lines = len(frames[0].shapes)
    side_lines = [side.plot([], [], lw=1.3, color=f"C{j + 1}", label=str(s.line))[0]
                  for j, s in enumerate(frames[0].shapes)]
    plan_lines = [plan.plot([], [], lw=1.3, color=f"C{j + 1}")[0] for j in range(n_lines)]
    side_td = side.plot([], [], "x", color="k", ms=6, label="touchdown point")[0]
    plan_td = plan.plot([], [], "x", color="k", ms=6)[0]
    side_body = plan_body = None
    if fairleads is not None:
        side_body = side.plot([], [], "o-", color="0.3", ms=6, mfc="none", lw=0.6,
                              label="floater: reference point, fairleads")[0]
        plan_body = plan.plot([], [], "o-", color="0.3", ms=6, mfc="none", lw=0.6)[0]
    side_patch = plan_patch = None
    if frames[0].outline is not None:
        side_patch = body_patch(side, frames[0].outline, "side", label="body")
        plan_patch = body_patch(plan, frames[0].outline, "plan")
    side.legend(loc="lower left", fontsize=7, ncol=2)
    clock = fig.suptitle("", fontsize=10)
    title = figure_title(dataset.attrs.get("title"))

    def draw(i: int):
        fr = frames[i]
        for j, shape in enumerate(fr.shapes):
            side_lines[j].set_data(shape.position[:, 0], shape.position[:, 2])
            plan_lines[j].set_data(shape.position[:, 0], shape.position[:, 1])
        tds = np.array([td for td in fr.touchdowns if td is not None]).reshape(-1, 3)
        side_td.set_data(tds[:, 0], tds[:, 2])
        plan_td.set_data(tds[:, 0], tds[:, 1])
        if side_body is not None and plan_body is not None and fr.body is not None:
            fl = fairleads[int(np.argmin(np.abs(times - fr.time)))]
            spokes = np.concatenate([[fr.body, p] for p in fl]).reshape(-1, 3)
            side_body.set_data(spokes[:, 0], spokes[:, 2])
            plan_body.set_data(spokes[:, 0], spokes[:, 1])
        if side_patch is not None and plan_patch is not None and fr.outline is not None:
            update_body_patch(side_patch, fr.outline, "side")
            update_body_patch(plan_patch, fr.outline, "plan")
        clock.set_text(f"{title}\nt = {fr.time:.3f} s")
        return side_lines + plan_lines

    moving = [a for a in (*side_lines, *plan_lines, side_td, plan_td, side_body, plan_body,
                          side_patch, plan_patch, clock) if a is not None]
    try:
        if ANIMATION_WRITERS[Path(path).suffix.lower()] == "pillow":
            _write_gif(fig, moving, draw, len(frames), path, fps, progress)
        else:
            from matplotlib.animation import FuncAnimation

            anim = FuncAnimation(fig, draw, frames=len(frames), blit=False, repeat=False)
            callback = (lambda i, n: progress(i + 1, n)) if progress is not None else None
            with atomic_target(path, suffix=Path(path).suffix) as tmp:
                anim.save(str(tmp), writer=writer, dpi=ANIMATION_DPI,
                          progress_callback=callback)
    finally:
        plt.close(fig)
    return len(frames)


def _write_gif(fig, moving: list, draw: Callable[[int], object], n: int, path: str | Path,
               fps: float, progress: Callable[[int, int], None] | None) -> None:
    """Write ``n`` frames of ``fig`` as a GIF through Pillow, blitting: the still parts
    (axes, ticks, seabed, legend) are drawn once, and each frame restores that background and
    draws only the ``moving`` artists, which ``draw(i)`` updates. Drawing the whole figure
    per frame (matplotlib's writers, twice per frame) took 0.4 s a frame, nearly all in the
    axes' ticks and labels. Frames share the first frame's palette."""
    from PIL import Image

    canvas = fig.canvas
    for artist in moving:
        artist.set_animated(True)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)

    def image(i: int):
        draw(i)
        canvas.restore_region(background)
        for artist in moving:
            fig.draw_artist(artist)
        rgb = Image.fromarray(np.asarray(canvas.buffer_rgba())[..., :3])
        if progress is not None:
            progress(i + 1, n)
        return rgb

    first = image(0).quantize(colors=256, dither=Image.Dither.NONE)
    rest = (image(i).quantize(palette=first, dither=Image.Dither.NONE) for i in range(1, n))
    with atomic_target(path, suffix=Path(path).suffix) as tmp:
        first.save(tmp, format="GIF", save_all=True, append_images=rest, loop=0,
                   duration=max(int(round(1000.0 / fps)), 10))
