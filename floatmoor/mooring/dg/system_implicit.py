"""The implicit (generalised-alpha) time integration of a DG mooring system: its parameters,
state and work arrays (kernels: ``_system_implicit_kernels``;
docs/theory/dynamic_line.md#mooring-systems).

The sections' nodes and the free points advance together, Newton on the bordered banded
Jacobian of the joined sections; step bound, error estimate and step control are the single
line's (:mod:`floatmoor.mooring.dg.implicit`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import DynamicSettings
from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _system_implicit_kernels as _si
from floatmoor.mooring.dg import _system_kernels as _s
from floatmoor.mooring.dg.cable import IMPLICIT_MAX_STEP
from floatmoor.mooring.dg.implicit import GROW_RATIO, LEVEL_MAX, MAX_ITERATIONS, \
    NEWTON_FRACTION, RHO_INFINITY, implicit_parameters
from floatmoor.mooring.dg.line import SNAP_ERROR_SHARE

__all__ = ["SystemImplicit", "system_integration"]


def system_integration(settings: Sequence[DynamicSettings]) -> str:
    """How a system of sections with these settings steps (its sections advance together):
    "explicit" when any section asks for it (SSP-RK3 at the smallest section's stable step),
    else "implicit" when any asks for it (generalised-alpha, stable for all of them), else
    "auto" (implicit while its steps cost less than the explicit ones, explicit from then on:
    ``resolution.AutoIntegration``, the single line's rule)."""
    modes = {st.time_integration for st in settings}
    for mode in ("explicit", "implicit"):
        if mode in modes:
            return mode
    return "auto"


class SystemImplicit:
    """Generalised-alpha stepping of a :class:`~floatmoor.mooring.dg.system.DynamicSystem`.

    Parameters
    ----------
    system
        The system (its layout, parameters and workspace are read, not kept).
    force_scale
        The tension scale of the step's error control [N] (the largest end force of the
        start state; at least 1 % of a section's weight in water).
    """

    def __init__(self, system: Any, force_scale: float) -> None:
        secs = system.sections
        nodes, P = system.n_nodes, len(system.points)
        kind = system.kind
        #: largest step [s]: the sections' smallest ``max_time_step`` (default IMPLICIT_MAX_STEP)
        self.max_step = min(s.settings.max_time_step if s.settings.max_time_step is not None
                            else IMPLICIT_MAX_STEP for s in secs)
        scale = max([force_scale] + [0.01 * abs(s.properties.submerged_weight)
                                     * s.properties.length for s in secs])
        if not scale > 0.0:
            scale = 1.0  # weightless and unloaded: any scale; Newton's tolerance follows
        accuracy = min(s.settings.accuracy for s in secs)
        #: local error of the end forces allowed per step [N] (the single line's share)
        self.force_tolerance = SNAP_ERROR_SHARE * accuracy * scale
        spacing = min(0.5 * ln.element_length * ln.element.min_spacing
                      / ln.properties.axial_stiffness for ln in system.lines)
        am, af, beta, gamma = _ik.generalised_alpha(RHO_INFINITY)
        self.ip = np.zeros(_ik.IP_N)
        self.ip[_ik.IP_ALPHA_M], self.ip[_ik.IP_ALPHA_F] = am, af
        self.ip[_ik.IP_BETA], self.ip[_ik.IP_GAMMA] = beta, gamma
        self.ip[_ik.IP_NEWTON_TOL] = NEWTON_FRACTION * self.force_tolerance * spacing
        self.ip[_ik.IP_FORCE_TOL] = self.force_tolerance
        self.ip[_ik.IP_MAX_ITER] = MAX_ITERATIONS
        self.ip[_ik.IP_DT_MAX] = self.max_step
        self.ip[_ik.IP_LEVEL_MAX] = LEVEL_MAX
        self.ip[_ik.IP_GROW] = GROW_RATIO
        # a step that jumps over a section end's slack-taut transition is rejected, as on
        # single lines (docs/theory/dynamic_line.md#slack-taut-events-and-seabed-friction)
        self.ip[_ik.IP_FLAG_EVENTS] = 1.0
        #: integrator state (``_implicit_kernels.CS_*``)
        self.cs = np.zeros(_ik.CS_N)
        #: the sections' parameters with damping and contact inside the solve
        self.prm = np.ascontiguousarray(np.stack([implicit_parameters(ln.prm)
                                                  for ln in system.lines]))
        self.fslot = np.full(P, -1, dtype=np.int64)
        free = np.flatnonzero(kind == _s.FREE)
        self.fslot[free] = np.arange(free.size)
        nf = 3 * free.size
        # state: acceleration variables of nodes and points, A of the nodes, F of the points
        self.st = (np.zeros((nodes, 3)), np.zeros((nodes, 3)), np.zeros((P, 3)),
                   np.zeros((P, 3)))
        self._nw = tuple(np.zeros((nodes, 3)) for _ in range(7))
        self._pw = tuple(np.zeros((P, 3)) for _ in range(7))
        self._jw = (np.zeros((nodes, 3, 3)), np.zeros((nodes, 3, 3)))
        sizes = [3 * s.settings.elements * (s.settings.order + 1) * (9 * (s.settings.order + 1)
                                                                     + 2) for s in secs]
        self.boff = np.concatenate(([0], np.cumsum(sizes))).astype(np.int64)
        self.bands = np.zeros(int(self.boff[-1]))
        nmax = max(3 * s.settings.elements * (s.settings.order + 1) for s in secs)
        w = system._w
        # bordered blocks B, C (transposed), W = J^-1 B; right-hand sides; scratch; slack
        self._flat = (np.zeros(18 * nodes), np.zeros(18 * nodes), np.zeros(18 * nodes),
                      np.zeros(3 * nodes), np.zeros(nf), np.zeros(nmax), w.slack)
        self.Spp = np.zeros((nf, nf))
        self.piv = np.zeros(nf, dtype=np.int64)
        self._scratch = (np.zeros((3, 3)), np.zeros(3))

    def invalidate(self) -> None:
        """Forget the accelerations and the factors (the state was replaced)."""
        self.cs[_ik.CS_ACC_VALID] = 0.0
        self.cs[_ik.CS_FACTOR_DT] = 0.0

    def run(self, system: Any, time: NDArray, bpos: NDArray, bvel: NDArray, sf: NDArray,
            ef: NDArray, laid: NDArray, pp: NDArray, steps: NDArray, shape_every: int,
            shape_r: NDArray, shape_t: NDArray) -> tuple[int, int]:
        """``_system_implicit_kernels.dgi_run_path`` on the system's state and workspace."""
        w = system._w
        H, F3 = self._scratch
        return _si.dgi_run_path(
            system.r, system.v, system.x, system.u, time, bpos, bvel, system.sec, self.prm,
            system.prm, system.ops, system.kind, system.body, system.pprm, system.env,
            self.fslot, self.ip, self.cs, self.st, self._nw, self._pw,
            (w.q, w.qt, w.N, w.Nstar, w.faces), self._jw, self.bands, self.boff, self._flat,
            self.Spp, self.piv, H, F3, w.tmp, w.G, w.Zs, sf, ef, laid, pp, steps,
            shape_every, shape_r, shape_t, w.where)

    def state_arrays(self) -> dict[str, NDArray]:
        """The integrator's state for a checkpoint: accelerations, step level and counters,
        and the factors later steps reuse."""
        C, W = self._flat[1:3]
        return {"implicit_acc": self.st[0].copy(), "implicit_An": self.st[1].copy(),
                "implicit_pacc": self.st[2].copy(), "implicit_Fn": self.st[3].copy(),
                "implicit_cs": self.cs.copy(), "implicit_band": self.bands.copy(),
                "implicit_border": np.concatenate([C, W]),
                "implicit_schur": self.Spp.copy(),
                "implicit_pivots": self.piv.astype(np.float64)}

    def set_state_arrays(self, arrays: dict[str, NDArray]) -> None:
        """Restore :meth:`state_arrays`."""
        for a, key in zip(self.st, ("implicit_acc", "implicit_An", "implicit_pacc",
                                    "implicit_Fn")):
            a[...] = arrays[key]
        self.cs[...] = arrays["implicit_cs"]
        self.bands[...] = arrays["implicit_band"]
        n = self._flat[1].size
        self._flat[1][...] = arrays["implicit_border"][:n]
        self._flat[2][...] = arrays["implicit_border"][n:]
        self.Spp[...] = arrays["implicit_schur"]
        self.piv[...] = np.asarray(arrays["implicit_pivots"]).astype(np.int64)
