"""Figures and animations of one run's result dataset (matplotlib, Agg; imported only when a
picture is asked for).

One module per kind of view: :mod:`~floatmoor.plots.tensions` (end tension histories and the
tension along the lines), :mod:`~floatmoor.plots.motions` (floater motions),
:mod:`~floatmoor.plots.shapes` (line shapes in side and plan views),
:mod:`~floatmoor.plots.animation` (line shapes and body over time) and
:mod:`~floatmoor.plots.run_figures` (every view that applies to a run, for ``floatmoor run
--plot``). Shared styling, units and the atomic save are in :mod:`~floatmoor.plots.style`,
the check of every plotted series in :mod:`~floatmoor.plots.series`, what the views take from
the run's case in :mod:`~floatmoor.plots.context`; the body drawn with the lines in
:mod:`~floatmoor.plots.body_surface` (its panels at rest), :mod:`~floatmoor.plots.body_pose`
(placed at a time) and :mod:`~floatmoor.plots.body_outline` (its patch in a view);
the ``floatmoor animate`` and ``floatmoor vtk`` commands are in :mod:`floatmoor.cli.plots`.
"""
