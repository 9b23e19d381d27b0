"""Energy audit of a coupled run's dynamic lines, step by step (a diagnostic, not on a run's
path): where the energy of a line comes from and where it goes (docs/theory/floater.md,
"Energy audit of the coupling").

Per body step [t_n, t_n + dt] and per dynamic line:

* ``work``: the work the fairlead does on the line as the body's RK4 step counts it,
  W = -dt sum_s b_s F_s . v_s, F_s the force the line exerts on its fairlead at stage s,
  v_s the stage's fairlead velocity, b = (1, 2, 2, 1) / 6 the RK4 weights; it is exactly
  minus the work of the line's force on the body in that step's quadrature;
* ``energy_change``: the change of the line's mechanical energy (kinetic, strain and the
  submerged weight's potential, :meth:`DynamicLine.energy`);
* ``dissipation``: what the line's physics dissipates, Morison drag and seabed friction,
  integrated with the trapezoidal rule from the states at the step's ends;
* ``residual`` = work - energy_change - dissipation: what the numerics dissipate (the
  upwind flux, the slack filter, the seabed's normal damper) when positive; energy created
  by the discretisation or the coupling when negative.

and, per body DOF, ``body_work``: the work the mooring's generalised force does on the body
in the step's quadrature, dt sum_s b_s Q_s[j] x'_s[j]: where the energy of a DOF (roll,
yaw) comes from. With lines solved on their own, the sum over the DOFs is minus the sum of
the lines' ``work`` to round-off: the kinematics hand the lines the power the body loses
(:func:`floatmoor.body.kinematics.generalised_force`). That balance held with the
small-angle identification too; what broke was that the fairlead velocity was not the
derivative of the fairlead position the lines follow (docs/theory/floater.md).

The audit also reports how far two mirror-image lines (mirrored by y -> -y) are from being
mirror images, the measure of a symmetric case's symmetry (:func:`mirror_difference`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.body.kinematics import points_state
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.simulation.coupled import MooredBody

__all__ = ["LineAudit", "StepAudit", "line_energy", "line_dissipation_rate",
           "mirror_difference", "audit_step"]

#: RK4 weights of the four stages.
_RK4_WEIGHTS = (1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0)
_MIRROR = np.array([1.0, -1.0, 1.0])


@dataclass(frozen=True)
class LineAudit:
    """One line's energy balance over one body step [J]."""

    work: float  #: work done on the line by its fairlead (RK4 quadrature of the body)
    energy_change: float  #: change of the line's mechanical energy
    dissipation: float  #: Morison drag and seabed friction (trapezoidal rule)

    @property
    def residual(self) -> float:
        """work - energy_change - dissipation: numerical dissipation (> 0) or energy created
        by the discretisation and the coupling (< 0) [J]."""
        return self.work - self.energy_change - self.dissipation


@dataclass(frozen=True)
class StepAudit:
    """The energy balance of every dynamic line (None for the others) over one body step."""

    time: float  #: time at the end of the step [s]
    lines: list[LineAudit | None]
    #: work of the mooring's generalised force on each body DOF over the step [J]
    body_work: NDArray[np.float64]


def line_energy(line: DynamicLine) -> float:
    """Mechanical energy of ``line`` now [J]: kinetic, strain and the potential of the
    submerged weight (:meth:`DynamicLine.energy`)."""
    return float(sum(line.energy().values()))


def line_dissipation_rate(line: DynamicLine) -> float:
    """Power [W] the line's Morison drag (no current) and seabed Coulomb friction take from
    its nodes in the current state, integrated with the element quadrature (as the kernels'
    right-hand side computes those forces, docs/theory/cable.md)."""
    line.end_forces()  # the tangent field q of the current state
    pr = line.properties
    K = line.settings.elements
    wq = np.tile(line.element.weights * 0.5 * line.element_length, K)
    r = line.r.reshape(-1, 3)
    v = line.v.reshape(-1, 3)
    q = line._work.q.reshape(-1, 3)
    ql = np.linalg.norm(q, axis=1)
    t = np.divide(q, ql[:, None], out=np.zeros_like(q), where=ql[:, None] > 0.0)
    vt = np.sum(v * t, axis=1)
    vn_vec = v - vt[:, None] * t
    vn = np.linalg.norm(vn_vec, axis=1)
    scale = 0.5 * pr.water_density * pr.diameter * np.sqrt(ql)
    drag = scale * (pr.tangential_drag_coefficient * np.abs(vt) ** 3
                    + pr.normal_drag_coefficient * vn ** 3)
    drag = np.where(r[:, 2] < 0.0, drag, 0.0)
    speed = np.hypot(v[:, 0], v[:, 1])
    friction = pr.friction_coefficient * abs(pr.submerged_weight)
    vc = pr.slip_speed
    fric = friction * np.sin(0.5 * math.pi * speed / np.maximum(vc, speed)) * speed
    fric = np.where(r[:, 2] < pr.seabed_z, fric, 0.0)
    return float(np.sum(wq * (drag + fric)))


def mirror_difference(a: DynamicLine, b: DynamicLine) -> float:
    """Largest difference [m] between the nodes of ``a`` and the mirror image (y -> -y) of
    the nodes of ``b``: 0 for mirror-image lines in mirror-image states."""
    return float(np.abs(a.r - b.r * _MIRROR).max())


def audit_step(moored: MooredBody) -> StepAudit:
    """Advance ``moored`` by one body step (:meth:`MooredBody.step`) and return the energy
    balance of each of its dynamic lines over the step (module docstring).

    The stage forces are those the body's step takes (each stage's ``MooredBody.mooring_force``
    observed for the step's duration, its fairlead forces evaluated again by
    ``MooredBody.line_forces``, which gives the same bits without changing a state); the step
    itself is unchanged.
    """
    models = moored.models
    dynamic = [m is not None and m.resolves_dynamics for m in models]
    e0 = [line_energy(m) if d else 0.0 for m, d in zip(models, dynamic)]
    d0 = [line_dissipation_rate(m) if d else 0.0 for m, d in zip(models, dynamic)]
    stages: list[tuple[NDArray[np.float64], NDArray[np.float64]]] = []
    body_power: list[NDArray[np.float64]] = []
    original_mooring = moored.mooring_force

    def observed_mooring(x: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray:
        f = original_mooring(x, v)
        body_power.append(f * v)
        ff, _ = moored.line_forces(x, v)
        _, vel = points_state(x, v, moored.arms, moored.centre)
        stages.append((ff.copy(), vel))
        return f

    dt = moored.body.dt
    moored.mooring_force = observed_mooring  # type: ignore[method-assign]
    try:
        moored.step()
    finally:
        del moored.mooring_force
    if len(stages) != len(_RK4_WEIGHTS) or len(body_power) != len(_RK4_WEIGHTS):
        raise RuntimeError(f"the audit expects the {len(_RK4_WEIGHTS)} stages of an RK4 step, "
                           f"found {len(stages)}")
    out: list[LineAudit | None] = []
    for i, (m, d) in enumerate(zip(models, dynamic)):
        if not d:
            out.append(None)
            continue
        work = -dt * sum(b * float(ff[i] @ vel[i]) for b, (ff, vel) in zip(_RK4_WEIGHTS, stages))
        d1 = line_dissipation_rate(m)
        out.append(LineAudit(work, line_energy(m) - e0[i], 0.5 * dt * (d0[i] + d1)))
    body_work = dt * sum(b * p for b, p in zip(_RK4_WEIGHTS, body_power))
    return StepAudit(moored.body.time, out, np.asarray(body_work, dtype=float))
