"""The state-space radiation of a body at its time step: the realisations of the
database's K_ij(t) (identified and stored by :mod:`floatmoor.hydro.state_space`) packed for
the compiled stage kernel (:mod:`floatmoor.body._state_space_radiation_kernels`), the
time-domain side of the state-space radiation.

Modes too fast for the body step are residualised: a mode r e^{lambda t} with
|lambda| dt > :data:`RESOLVED_POLE_STEP` is replaced by its static contribution, a
feedthrough D = -r / lambda (the integral of its impulse response), so the force it gives is
int r e^{lambda s} v(t - s) ds ~ D v(t). The error this makes on the mode's force at a motion
frequency omega is of relative size omega / |lambda| < omega dt, which the body step must keep
small anyway; without it such modes (the cusp of DeepCwind's surge kernel at t = 0 needs
poles near 27 1/s) would leave the RK4 stability region at the 0.1 s step.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["RadiationStates", "RESOLVED_POLE_STEP", "rk4_amplification"]

#: Largest |lambda| dt of a mode integrated as a state: RK4's one-step factor of a decaying
#: mode is then within 2 % of e^{lambda dt} (0.375 against 0.368 at lambda dt = -1; at -2 it
#: is 0.333 against 0.135, beyond -2.79 the scheme is unstable).
RESOLVED_POLE_STEP = 1.0


def rk4_amplification(z: NDArray[np.complex128]) -> NDArray[np.complex128]:
    """R(z) = 1 + z + z^2 / 2 + z^3 / 6 + z^4 / 24, RK4's factor per step of y' = lambda y,
    z = lambda dt."""
    z = np.asarray(z, complex)
    return 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0)))


@dataclass
class RadiationStates:
    """Packed radiation states (see :mod:`floatmoor.body._state_space_radiation_kernels`).

    Attributes
    ----------
    a : (S, w)
        Block rows of the state matrices [1/s].
    b, c : (S,)
    offsets : (P + 1,) int64
    radiating, influenced : (P,) int64
    feedthrough : (6, 6)
        D of the residualised modes, indices (influenced, radiating).
    residualised : int
        Number of modes (real poles or complex pairs) replaced by feedthrough.
    poles : (S,) complex
        Eigenvalues of the kept states.
    """

    a: NDArray[np.float64]
    b: NDArray[np.float64]
    c: NDArray[np.float64]
    offsets: NDArray[np.int64]
    radiating: NDArray[np.int64]
    influenced: NDArray[np.int64]
    feedthrough: NDArray[np.float64]
    residualised: int
    poles: NDArray[np.complex128]

    @property
    def n_states(self) -> int:
        """S"""
        return int(self.b.size)

    @classmethod
    def from_pairs(cls, pairs: Sequence[tuple[int, int, NDArray, NDArray, NDArray]], dt: float,
                   resolved_pole_step: float = RESOLVED_POLE_STEP) -> "RadiationStates":
        """Pack realisations (radiating, influenced, A, b, c), each rebuilt in real modal form
        from its poles and residues, the modes with |lambda| dt > ``resolved_pole_step``
        residualised into the feedthrough."""
        from floatmoor.hydro.state_space.modal_form import modal_realisation, modes

        blocks = []
        feed = np.zeros((6, 6))
        residualised = 0
        for rad, inf, a, b, c in pairs:
            lam, res = modes(a, b, c)
            scale = np.maximum(np.abs(lam), 1e-300)
            real = np.abs(lam.imag) <= 1e-9 * scale
            poles, coef = [], []
            for k in np.argsort(np.abs(lam), kind="stable"):
                p, r = lam[k], res[k]
                if not real[k] and p.imag < 0.0:
                    continue  # the conjugate's partner carries the pair
                fast = abs(p) * dt > resolved_pole_step
                if real[k]:
                    if fast:
                        feed[inf, rad] += float(np.real(-r / p.real))
                    else:
                        poles.append(complex(p.real, 0.0))
                        coef.append(float(np.real(r)))
                else:
                    if fast:  # 2 Re(r e^{lambda t}) integrates to -2 Re(r / lambda)
                        feed[inf, rad] += float(-2.0 * np.real(r / p))
                    else:
                        poles.append(complex(p))
                        coef.extend([2.0 * float(np.real(r)), -2.0 * float(np.imag(r))])
                residualised += int(fast)
            if poles:
                am, bm, cm = modal_realisation(np.array(poles), np.array(coef))
                blocks.append((rad, inf, am, bm, cm))
        n = sum(blk[3].size for blk in blocks)
        width = max((blk[3].size for blk in blocks), default=1)
        a_rows = np.zeros((n, width))
        b_all = np.zeros(n)
        c_all = np.zeros(n)
        offsets = np.zeros(len(blocks) + 1, dtype=np.int64)
        poles_all = []
        k = 0
        for p, (_, _, am, bm, cm) in enumerate(blocks):
            m = bm.size
            a_rows[k:k + m, :m] = am
            b_all[k:k + m] = bm
            c_all[k:k + m] = cm
            poles_all.append(np.linalg.eigvals(am))
            k += m
            offsets[p + 1] = k
        return cls(a_rows, b_all, c_all, offsets,
                   np.array([blk[0] for blk in blocks], dtype=np.int64),
                   np.array([blk[1] for blk in blocks], dtype=np.int64), feed, residualised,
                   np.concatenate(poles_all) if poles_all else np.zeros(0, complex))

    def max_amplification(self, dt: float) -> float:
        """Largest |R(lambda dt)| over the kept states (< 1: RK4 stable at ``dt``)."""
        if self.poles.size == 0:
            return 0.0
        return float(np.abs(rk4_amplification(self.poles * dt)).max())
