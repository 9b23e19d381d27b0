"""Prescribed motions evaluated: where the case's ``[motion]`` puts the fairleads and body
points at any time, for the case's cross-checks and the runs alike
(docs/theory/mooring_systems.md#prescribed-motion-of-the-body-points).

The case declares a motion (its dataclasses in :mod:`floatmoor.case.schema`, its tables read
by :mod:`floatmoor.case.motion_table` and :mod:`floatmoor.case.motion_body`); this package
evaluates it:

* :mod:`~floatmoor.motion.fairlead`: the ramp, the cubic spline of a table, and the
  translational motions of one fairlead (circular, harmonic, table);
* :mod:`~floatmoor.motion.rigid_body`: the 6-DOF motion of the body points
  (``kind = "body"``), any motion's fairlead path, and the pose a run starts its lines in;
* :mod:`~floatmoor.motion.frequency`: the frequency the fairleads are driven at, which the
  dynamic line's numerics are chosen for.

It sits in the case layer (docs/development.md#1-package-layout-and-import-order): the case's
cross-checks (:mod:`floatmoor.case.system_checks`) follow the paths it evaluates, and the
reader records the motion's frequency on the lines.
"""

__all__: list[str] = []
