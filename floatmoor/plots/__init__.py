"""Figures and animations of one run's result dataset (matplotlib, Agg; imported only when a
picture is asked for).

One module per kind of view: :mod:`~floatmoor.plots.tensions` (end tension histories and the
tension along the lines), :mod:`~floatmoor.plots.motions` (floater motions),
:mod:`~floatmoor.plots.shapes` (line shapes in side and plan views),
:mod:`~floatmoor.plots.animation` (line shapes and body over time) and
:mod:`~floatmoor.plots.run_figures` (every view that applies to a run, for ``floatmoor run
--plot``); :mod:`~floatmoor.plots.rao` draws a floater's RAOs (``floatmoor rao --plot``).
Shared styling, units and the atomic save are in :mod:`~floatmoor.plots.style`,
the check of every plotted series in :mod:`~floatmoor.plots.series`, what the views take from
the run's case in :mod:`~floatmoor.plots.context`; the body drawn with the lines in
:mod:`~floatmoor.plots.body_surface` (its panels at rest), :mod:`~floatmoor.plots.body_pose`
(placed at a time) and :mod:`~floatmoor.plots.body_outline` (its patch in a view);
the ``floatmoor animate`` and ``floatmoor vtk`` commands are in :mod:`floatmoor.cli.plots`.
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "plot_run": "floatmoor.plots.run_figures",
    "animate_run": "floatmoor.plots.animation",
    "draw_tensions": "floatmoor.plots.tensions",
    "draw_tension_along_line": "floatmoor.plots.tensions",
    "draw_body_motions": "floatmoor.plots.motions",
    "draw_line_shapes": "floatmoor.plots.shapes",
    "run_context": "floatmoor.plots.context",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
