"""Run-time validity monitor: says when a run leaves the range of the models it uses.

A run can be numerically sound and still outside what its models represent. The monitor is
given every chunk of recorded samples (vectorised maxima over the chunk, never inside the
numerical kernels) and checks:

* a floater's rotations from equilibrium (roll, pitch, yaw) against
  :data:`ROTATION_LIMIT` (15 deg): the hydrostatics and the radiation and excitation are
  linear about the equilibrium (small-angle linearisation, sin x = x to 1.2 % and
  cos x = 1 to 3.4 % at 15 deg; docs/theory/floater.md#validity-of-a-run);
* its heave from equilibrium against the draft (the bottom leaves the water) and the
  freeboard (the top goes under) when the geometry gives them (a cylinder, the
  surface-piercing columns of a semisubmersible; not a mesh hull);
* a quasi-dynamic line's dimensionless acceleration alpha = omega^2 Z_m / g (quasi-dynamic
  paper, eq. 5) against the 0.1-0.6 of the paper's verification
  (docs/theory/quasi_dynamic.md#assumptions-and-limits), estimated from the fairlead's
  acceleration through the static shapes: the largest vertical acceleration of a point of
  the line's static shape over g, with the shape's response to the fairlead linearised
  about the chunk's mean position (for a harmonic motion this is omega^2 Z_m / g).

Each condition warns once per run (:class:`~floatmoor.errors.ModelValidityWarning`), when
first exceeded; the monitor keeps, per condition, the largest value over the run and when it
occurred, and the run records these messages in its output file (attribute
``validity_warnings``) and prints them in its summary.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import Case, Line
from floatmoor.errors import ModelValidityWarning, SolverError

__all__ = ["ROTATION_LIMIT", "QD_ALPHA_LIMIT", "ValidityMonitor", "condition_of"]

#: Largest roll, pitch and yaw from equilibrium for the linear hydrostatics, radiation and
#: excitation [rad]: 15 deg, where the small-angle linearisation is off by 1.2 % (sin) and
#: 3.4 % (cos) (docs/theory/floater.md#validity-of-a-run).
ROTATION_LIMIT = math.radians(15.0)
#: Largest dimensionless acceleration alpha = omega^2 Z_m / g of a quasi-dynamic line: the
#: top of the quasi-dynamic paper's verification (alpha 0.1 to 0.6, its section 4;
#: docs/theory/quasi_dynamic.md#assumptions-and-limits). The estimate below gives 0.67 to
#: 0.94 times the paper's alpha over the 180 runs of that verification (floatmoor study
#: qd-verification: its Z_m of Table 4 are the extremes of the static shapes, the estimate
#: their linearisation about the mean), so none of them warns; the Lindahl chain at
#: T = 1.25 s gives 1.36 (docs: 1.3) and warns, at T = 3.5 s 0.17.
QD_ALPHA_LIMIT = 0.6
#: Step of the central differences of the static shape with respect to the fairlead
#: position, relative to the line length [-]: far above the catenary's tolerance (1e-12 L,
#: so the differences carry ~1e-8 relative noise) and small against any motion that matters.
SHAPE_DIFFERENCE_STEP = 1e-4
#: Points of the static shape whose vertical motion is followed (evenly spaced over the line).
SHAPE_POINTS = 51

_ROTATIONS = (("roll", 3), ("pitch", 4), ("yaw", 5))
#: A number as the messages print it (``%.3g``, ``%.4g``).
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")


def condition_of(message: str) -> str:
    """The condition a validity message is about: its text before the first ``": "``."""
    return message.split(": ", 1)[0]


class _Condition:
    """One monitored quantity: its largest value over the run, when, and its message."""

    def __init__(self, label: str, limit: float, describe) -> None:
        self.label = label
        self.limit = limit
        self.describe = describe  # (value, time) -> message text after the label
        self.value = -math.inf
        self.time = math.nan
        self.warned = False

    def update(self, value: float, time: float) -> bool:
        """Record a chunk's largest value; True the first time it exceeds the limit."""
        if value > self.value:
            self.value, self.time = value, time
        if self.value > self.limit and not self.warned:
            self.warned = True
            return True
        return False

    @property
    def message(self) -> str:
        return f"{self.label}: {self.describe(self.value, self.time)}"


class ValidityMonitor:
    """Checks a run's recorded samples against the validity of its models.

    Parameters
    ----------
    case
        The case run: its floater's geometry, its quasi-dynamic lines.
    body
        Whether the run records a floater's displacement (a coupled run).
    carried
        Messages an interrupted run already recorded (its output file's
        ``validity_warnings``), kept and not warned again when it is resumed.
    """

    def __init__(self, case: Case, *, body: bool, carried: list[str] | None = None) -> None:
        self.case = case
        self._carried = {condition_of(m): m for m in (carried or [])}
        self._conditions: list[_Condition] = []
        self._body: list[tuple[int, float, _Condition]] = []  # (dof, sign, condition)
        if body:
            self._add_body_conditions(case)
        self._lines: dict[int, _Condition] = {}
        for i, line in enumerate(case.lines):
            if line.model == "quasi-dynamic":
                self._lines[i] = self._add(
                    f"line '{line.name}' (quasi-dynamic)", QD_ALPHA_LIMIT,
                    lambda v, t: (f"dimensionless acceleration {v:.3g} at t = {t:.6g} s "
                                  "(alpha = omega^2 Z_m / g), beyond the "
                                  f"{QD_ALPHA_LIMIT:g} of the model's verification "
                                  "(docs/theory/quasi_dynamic.md#assumptions-and-limits): the "
                                  "line no longer follows its static shape; use the dynamic "
                                  "model"))
        self._tail_time: NDArray[np.float64] = np.zeros(0)
        self._tail_position: NDArray[np.float64] = np.zeros((len(case.lines), 0, 3))

    def _add(self, label: str, limit: float, describe) -> _Condition:
        condition = _Condition(label, limit, describe)
        if label in self._carried:
            condition.warned = True  # already recorded (and warned) before the resume
        self._conditions.append(condition)
        return condition

    def _add_body_conditions(self, case: Case) -> None:
        limit_deg = math.degrees(ROTATION_LIMIT)
        for name, dof in _ROTATIONS:
            self._body.append((dof, 0.0, self._add(
                f"floater {name}", ROTATION_LIMIT,
                lambda v, t, name=name: (f"{math.degrees(v):.3g} deg from equilibrium at "
                                         f"t = {t:.6g} s, beyond the {limit_deg:g} deg of "
                                         "linear hydrostatics and radiation (small-angle "
                                         "linearisation; docs/theory/floater.md"
                                         "#validity-of-a-run)"))))
        draft, freeboard = _draft_and_freeboard(case)
        if draft is not None:
            self._body.append((2, 1.0, self._add(
                "floater heave up", draft,
                lambda v, t: (f"{v:.4g} m at t = {t:.6g} s, beyond the draft of {draft:.4g} m: "
                              "the hull leaves the water, outside linear hydrostatics "
                              "(docs/theory/floater.md#validity-of-a-run)"))))
        if freeboard is not None:
            self._body.append((2, -1.0, self._add(
                "floater heave down", freeboard,
                lambda v, t: (f"{v:.4g} m at t = {t:.6g} s, beyond the freeboard of "
                              f"{freeboard:.4g} m: the hull goes under, outside linear "
                              "hydrostatics (docs/theory/floater.md#validity-of-a-run)"))))

    # -- checking ------------------------------------------------------------------------------
    def check(self, time: NDArray[np.float64], fairlead_position: NDArray[np.float64],
              body_displacement: NDArray[np.float64] | None = None) -> None:
        """Check one chunk of samples, consecutive with the previous chunk's.

        Parameters
        ----------
        time
            Sample times [s], (n,).
        fairlead_position
            Fairlead positions of every line [m], (lines, n, 3).
        body_displacement
            The floater's displacement from equilibrium (n, 6) [m, rad], coupled runs.
        """
        time = np.asarray(time, dtype=float)
        if time.size == 0:
            return
        if body_displacement is not None:
            for dof, sign, condition in self._body:
                x = sign * body_displacement[:, dof] if sign else \
                    np.abs(body_displacement[:, dof])
                k = int(np.argmax(x))
                self._update(condition, float(x[k]), float(time[k]))
        if self._lines:
            self._check_lines(time, np.asarray(fairlead_position, dtype=float))

    def _check_lines(self, time: NDArray[np.float64], position: NDArray[np.float64]) -> None:
        """alpha of each quasi-dynamic line over the chunk (with the two samples before it)."""
        t = np.concatenate((self._tail_time, time))
        p = np.concatenate((self._tail_position, position), axis=1)
        self._tail_time, self._tail_position = t[-2:].copy(), p[:, -2:].copy()
        if t.size < 3:
            return
        h1, h2 = np.diff(t)[:-1], np.diff(t)[1:]
        g = self.case.environment.gravity
        for i, condition in self._lines.items():
            x = p[i]
            v1 = (x[1:-1] - x[:-2]) / h1[:, None]
            v2 = (x[2:] - x[1:-1]) / h2[:, None]
            acc = (v2 - v1) / (0.5 * (h1 + h2))[:, None]  # at t[1:-1]
            jacobian = _vertical_shape_jacobian(self.case, self.case.lines[i],
                                                x.mean(axis=0))
            if jacobian is None:
                continue  # no static shape near the mean position: nothing to estimate
            alpha = np.abs(acc @ jacobian.T).max(axis=1) / g
            k = int(np.argmax(alpha))
            self._update(condition, float(alpha[k]), float(t[1 + k]))

    def _update(self, condition: _Condition, value: float, time: float) -> None:
        if condition.update(value, time):
            warnings.warn(ModelValidityWarning(condition.message))

    # -- results -------------------------------------------------------------------------------
    def messages(self) -> list[str]:
        """One message per condition exceeded so far (its largest value and when), and those
        carried from before a resume."""
        out = dict(self._carried)
        for c in self._conditions:
            if c.value > c.limit and not (c.label in out and
                                          _value_of(out[c.label]) >= _value_of(c.message)):
                out[c.label] = c.message  # the larger of the resumed run's and the carried
        return list(out.values())


def _value_of(message: str) -> float:
    """The value a validity message gives (its first number after the condition: every
    message of a condition states it first, in the same unit)."""
    match = _NUMBER.search(message.split(": ", 1)[-1])
    return float(match.group()) if match else -math.inf


def _draft_and_freeboard(case: Case) -> tuple[float | None, float | None]:
    """The floater's draft and freeboard at rest [m] when its geometry gives them: a
    cylinder's, or the smallest over the columns piercing the surface; None for a mesh."""
    floater = case.floater
    geometry = floater.geometry if floater is not None else None
    if geometry is None:
        return None, None
    if geometry.kind == "cylinder":
        return geometry.draft, geometry.height - geometry.draft
    columns = [c for c in getattr(geometry, "columns", ()) if c.z_bottom < 0.0 < c.z_top]
    if geometry.kind == "mesh" or not columns:
        return None, None
    return min(-c.z_bottom for c in columns), min(c.z_top for c in columns)


def _vertical_shape_jacobian(case: Case, line: Line, fairlead: NDArray[np.float64]
                             ) -> NDArray[np.float64] | None:
    """d z / d fairlead (SHAPE_POINTS, 3) of the points of a line's static shape (evenly
    spaced over its length) at the fairlead position ``fairlead``, by central differences;
    None when a static shape has no solution there."""
    from floatmoor.mooring._catenary_profile import catenary_profile_3d
    from floatmoor.mooring.catenary import solve_catenary

    lt = line.line_type
    weight = lt.weight_in_water(case.environment)
    friction = case.seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
    anchor = np.asarray(line.anchor, dtype=float)
    seabed_z = case.environment.seabed_z
    s = np.linspace(0.0, line.length, SHAPE_POINTS)
    step = SHAPE_DIFFERENCE_STEP * line.length
    positions, tension = np.empty((s.size, 3)), np.empty(s.size)
    jacobian = np.empty((s.size, 3))
    try:
        for axis in range(3):
            z = []
            for sign in (1.0, -1.0):
                point = fairlead.copy()
                point[axis] += sign * step
                sol = solve_catenary(anchor, point, line.length, lt.axial_stiffness, weight,
                                     friction, seabed_z=seabed_z,
                                     tol=line.quasi_static.tolerance,
                                     max_iter=line.quasi_static.max_iterations)
                hf, vf = sol.warm_start
                catenary_profile_3d(anchor, point, line.length, lt.axial_stiffness, weight,
                                    friction, seabed_z, hf, vf, s, positions, tension)
                z.append(positions[:, 2].copy())
            jacobian[:, axis] = (z[0] - z[1]) / (2.0 * step)
    except SolverError:
        return None
    return jacobian if np.all(np.isfinite(jacobian)) else None
