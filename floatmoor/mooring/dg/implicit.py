"""The implicit (generalised-alpha) time integration of a DG line: its parameters, state and
work arrays (kernels: ``_implicit_kernels``).

An explicit DG step is bounded by the axial wave crossing the smallest node spacing
(``reference.STABLE_STEP_FACTOR``): 9 us on the tank chains of the moored buoy, whose
fairlead moves on a 10 ms body step. The implicit step is bounded by accuracy instead: at most
``max_step``, and halved where the estimated error of the fairlead force exceeds
``force_tolerance`` (snap loads), doubled again where it is well inside.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.mooring.dg import _implicit_kernels as _ik
from floatmoor.mooring.dg import _kernels as _k

__all__ = ["ImplicitIntegrator", "ImplicitSettings", "RHO_INFINITY", "NEWTON_FRACTION",
           "LEVEL_MAX", "GROW_RATIO", "MAX_ITERATIONS"]

#: Spectral radius of the generalised-alpha step at infinite frequency: a wave resolved by
#: the step keeps its amplitude to second order, an unresolved axial wave (the stiff chains'
#: 240 Hz and up on a 1 ms step) loses half its amplitude per step instead of ringing on at a
#: frequency the step cannot represent. 0.5 is the middle of the range structural codes use
#: (0.3 to 0.9).
RHO_INFINITY = 0.5
#: Newton stops when its last position correction would move the end force by less than this
#: fraction of the force tolerance (through the axial stiffness EA / smallest node spacing).
#: 0.1 against 0.01: DeepCwind lines on their recorded paths 15 % faster, STD and max the same
#: to 1e-4. Not looser: 0.3 cost DeepCwind line 2 on its LC34 path (600 s, 8 x p3) 11 % less
#: CPU time, STD and max the same to 0.03 %, but single snap peaks of the Lindahl chain
#: (implicit, T = 1.25 s) came out up to 5 % above the explicit steps' (0.1: within 1.4 %).
NEWTON_FRACTION = 0.1
#: Most halvings of one sample interval (2^24 steps: below any snap's resolution need).
LEVEL_MAX = 24
#: An error below this fraction of the tolerance counts towards doubling the step: the local
#: error scales as dt^3, so a doubled step stays inside the tolerance (2^3 x 0.1 < 1). The step
#: doubles after ``_implicit_kernels.GOOD_STEPS`` such steps in a row, 4: every change of the
#: step refactors the Jacobian, and a doubled step that fails is redone. 4 against 2: DeepCwind
#: line 2 on its LC34 path (600 s, 8 x p3) 8 % less CPU time (29 % fewer rejections, 19 % fewer
#: factorisations), STD and max the same to 0.03 % (6 and 8, with a looser Newton and error
#: share, no cheaper than 4). 0.05 and 0.2 against 0.1 (with 2 steps): 4 % and 6 % dearer.
GROW_RATIO = 0.1
#: Newton iterations per attempt of a step.
MAX_ITERATIONS = 8
#: Rebuild the Jacobian whenever a node changes state (taut, on the seabed, submerged): off.
#: A stale Jacobian is rebuilt anyway when Newton's correction stops halving; rebuilding on
#: every change cost DeepCwind line 2 (10 x p5, 0.1 s steps) 29 % more factorisations for the
#: same tension statistics.
REFACTOR_ON_STATE_CHANGE = False


@dataclass(frozen=True)
class ImplicitSettings:
    """What the implicit step needs beyond the line's properties."""

    max_step: float  #: largest step [s]
    #: local error of the fairlead force allowed per step near slack, and of Newton's and the
    #: slack-taut events' tests [N]
    force_tolerance: float
    rho_infinity: float = RHO_INFINITY
    #: local error of the fairlead force allowed per step away from slack [N] (None: as near)
    smooth_force_tolerance: float | None = None
    #: how long after the fairlead end node was last slack a step keeps the tolerance of
    #: snaps [s]
    snap_window: float = 0.0
    #: the fairlead end node's strain at or below which it counts as slack (near a snap)
    slack_strain: float = 0.0


#: the kernel records the first sample (the current state) too, as ``solve_path`` asks
_RECORD_FIRST = np.bool_(True)


class ImplicitIntegrator:
    """Generalised-alpha stepping of one DG line (shapes (K, Np, 3) of its state).

    Parameters
    ----------
    elements, nodes
        K and Np = p + 1 of the line.
    settings
        Step bound and force tolerance.
    axial_stiffness, min_spacing
        EA [N] and the smallest node spacing [m], which turn the force tolerance into
        Newton's position tolerance.
    """

    def __init__(self, elements: int, nodes: int, settings: ImplicitSettings,
                 axial_stiffness: float, min_spacing: float) -> None:
        K, Np = elements, nodes
        self.settings = settings
        am, af, beta, gamma = _ik.generalised_alpha(settings.rho_infinity)
        self.ip = np.zeros(_ik.IP_N)
        self.ip[_ik.IP_ALPHA_M], self.ip[_ik.IP_ALPHA_F] = am, af
        self.ip[_ik.IP_BETA], self.ip[_ik.IP_GAMMA] = beta, gamma
        self.ip[_ik.IP_NEWTON_TOL] = (NEWTON_FRACTION * settings.force_tolerance * min_spacing
                                      / axial_stiffness)
        self.ip[_ik.IP_FORCE_TOL] = settings.force_tolerance
        self.ip[_ik.IP_SMOOTH_TOL] = (settings.force_tolerance
                                      if settings.smooth_force_tolerance is None
                                      else settings.smooth_force_tolerance)
        self.ip[_ik.IP_SNAP_WINDOW] = settings.snap_window
        self.ip[_ik.IP_SLACK_STRAIN] = settings.slack_strain
        self.ip[_ik.IP_MAX_ITER] = MAX_ITERATIONS
        self.ip[_ik.IP_DT_MAX] = settings.max_step
        self.ip[_ik.IP_LEVEL_MAX] = LEVEL_MAX
        self.ip[_ik.IP_GROW] = GROW_RATIO
        self.ip[_ik.IP_FLAG_REFACTOR] = 1.0 if REFACTOR_ON_STATE_CHANGE else 0.0
        self.ip[_ik.IP_FLAG_EVENTS] = 1.0
        #: integrator state (``_implicit_kernels.CS_*``): step level, factor validity, counters
        self.cs = np.zeros(_ik.CS_N)
        self.acc = np.zeros((K, Np, 3))  #: the method's acceleration variable [m/s^2]
        self.An = np.zeros((K, Np, 3))  #: the cable's acceleration in the current state
        n = 3 * K * Np
        self.band = np.zeros((n, 9 * Np + 2))
        self._x = np.zeros(n)
        self._blocks = (np.zeros((K, Np, 3, 3)), np.zeros((K, Np, 3, 3)))
        self._fields = tuple(np.zeros((K, Np, 3)) for _ in range(7))
        #: node states (taut, seabed, submerged) the factored Jacobian was built with
        self.flags = np.zeros((K, Np))
        self.invalidate()

    def invalidate(self) -> None:
        """Forget the acceleration and the factors (the state was replaced)."""
        self.cs[_ik.CS_ACC_VALID] = 0.0
        self.cs[_ik.CS_FACTOR_DT] = 0.0
        self.cs[_ik.CS_SLACK_TIME] = _ik.SLACK_UNKNOWN  # (near slack at the next step)

    def run(self, r: NDArray, v: NDArray, time: NDArray, path: NDArray, velocity: NDArray,
            anchor: NDArray, prm: NDArray, element, work, fair_force: NDArray,
            anch_force: NDArray, laid: NDArray, steps: NDArray, shape_every: int,
            shape_r: NDArray, shape_t: NDArray, fa: NDArray) -> tuple[int, int]:
        """``_implicit_kernels.dg_run_path_implicit`` on the line's state and workspace;
        ``fa`` the line's friction anchors (K, Np, 2)."""
        w = work
        r0, v0, a0, An0, A1, R, MR = self._fields
        E, Dg = self._blocks
        return _ik.dg_run_path_implicit(
            r, v, self.acc, self.An, time, path, velocity, anchor, prm,
            element.differentiation, element.lift, element.filter, element.weights, self.ip,
            self.cs, fair_force, anch_force, laid, steps, shape_every, shape_r, shape_t, w.q,
            w.qt, w.N, w.Nstar, w.faces, w.slack, w.fpos, w.fvel, w.tmp, w.where, r0, v0, a0,
            An0, A1, R, MR, E, Dg, self.band, self._x, self.flags, _RECORD_FIRST, fa)

    def state_arrays(self) -> dict[str, NDArray]:
        """The integrator's state for a checkpoint: its acceleration variable, the state's
        acceleration, the step level and counters, and the factored Jacobian (reused by
        later steps: a state restored without it refactors earlier, and continues to other
        last bits)."""
        return {"implicit_acc": self.acc.copy(), "implicit_An": self.An.copy(),
                "implicit_cs": self.cs.copy(), "implicit_band": self.band.copy(),
                "implicit_flags": self.flags.copy()}

    def set_state_arrays(self, arrays: dict[str, NDArray]) -> None:
        """Restore :meth:`state_arrays`."""
        self.acc[...] = arrays["implicit_acc"]
        self.An[...] = arrays["implicit_An"]
        self.cs[...] = arrays["implicit_cs"]
        self.band[...] = arrays["implicit_band"]
        self.flags[...] = arrays["implicit_flags"]


def implicit_parameters(prm: NDArray[np.float64]) -> NDArray[np.float64]:
    """The kernels' parameter vector for the implicit step: seabed contact and internal
    damping in the right-hand side (inside the implicit solve), not as after-step corrections."""
    out = prm.copy()
    out[_k.P_IMPLICIT_CONTACT] = 0.0
    out[_k.P_IMPLICIT_DAMPING] = 0.0
    return out

