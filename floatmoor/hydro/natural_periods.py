"""Natural periods of a moored floater from its database, mass properties and a linearised
mooring stiffness.

The mooring stiffness K_moor (6 x 6 about the rotation centre) is the central finite
difference of the total force and moment of the quasi-static catenaries
(:class:`floatmoor.mooring.quasistatic.QuasiStaticLine`) on the body over small rigid-body
displacements: fairlead p = c + x + R(theta) (p0 - c), R = Rz(yaw) Ry(pitch) Rx(roll)
(:func:`floatmoor.rotations.rotation_matrix`).

:func:`natural_periods` (docs/theory/floater.md#natural-periods): per DOF i, the fixed point of
omega = sqrt(C_ii / (M_ii + A_ii(omega))) with C the hydrostatic and gravity stiffness plus
K_moor and M the rigid-body mass matrix about the rotation centre (A interpolated linearly,
held at the end values outside the BEM range).

:func:`coupled_natural_periods`: the modes of the undamped coupled system
det(C - omega^2 (M + A(omega))) = 0, by the same fixed-point iteration, a mode labelled by the
DOF holding the largest share of its kinetic energy. For the semisubmersible the pitch mode
then carries surge along (M15 = m z_G, A15), which shortens it: 25.4 s against 27.4 s
uncoupled (docs/cases/deepcwind.md quotes 26.8 s).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.schema import Case, Floater
from floatmoor.rotations import rotation_matrix
from floatmoor.hydro.radiation import added_mass_at, hydrostatic_stiffness_total

__all__ = ["mooring_stiffness", "mooring_force", "natural_periods", "coupled_natural_periods",
           "DOFS"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
#: Finite-difference step: translations this fraction of the mean line length [-]; the
#: catenary equations hold to 1e-12 L (case/load.py), so the difference quotient is exact to
#: ~1e-8 relative while the curvature error (~step^2) stays below 1e-6.
FD_RELATIVE_STEP = 1e-4
_MAX_ITERATIONS = 100
_FREQUENCY_TOLERANCE = 1e-10


def mooring_force(case: Case, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """Total force and moment about the (displaced) rotation centre of the lines on the body
    displaced by q = (x, y, z, roll, pitch, yaw) [N, N m]."""
    from floatmoor.mooring.quasistatic import QuasiStaticLine

    assert case.floater is not None
    c = np.asarray(case.floater.reference_point, dtype=float)
    rot = rotation_matrix(q[3], q[4], q[5])
    centre = c + q[:3]
    out = np.zeros(6)
    for line in case.lines:
        model = QuasiStaticLine.from_case(line, case.environment, case.seabed)
        p = centre + rot @ (np.asarray(line.fairlead, dtype=float) - c)
        f = model.solve(p).fairlead_force
        out[:3] += f
        out[3:] += np.cross(p - centre, f)
    return out


def mooring_stiffness(case: Case) -> NDArray[np.float64]:
    """K_moor = -dF/dq (6 x 6) at the rest position, central differences."""
    assert case.floater is not None
    lengths = [line.length for line in case.lines]
    if not lengths:
        return np.zeros((6, 6))
    h_t = FD_RELATIVE_STEP * float(np.mean(lengths))
    c = np.asarray(case.floater.reference_point, dtype=float)
    radius = max(float(np.linalg.norm(np.subtract(line.fairlead, c))) for line in case.lines)
    h_r = h_t / max(radius, 1e-9)
    k = np.zeros((6, 6))
    for j in range(6):
        h = h_t if j < 3 else h_r
        dq = np.zeros(6)
        dq[j] = h
        k[:, j] = -(mooring_force(case, dq) - mooring_force(case, -dq)) / (2.0 * h)
    return k


def natural_periods(ds: xr.Dataset, floater: Floater, k_moor: NDArray[np.float64] | None = None
                    ) -> dict[str, float]:
    """Natural period [s] of each DOF alone: omega = sqrt(C_ii / (M_ii + A_ii(omega))).

    Parameters
    ----------
    ds
        The floater's database.
    floater
        Mass properties.
    k_moor
        Mooring stiffness (6 x 6) about the rotation centre, or None for none.
    """
    m, c = _mass_and_stiffness(ds, floater, k_moor)
    out: dict[str, float] = {}
    for i, name in enumerate(DOFS):
        if c[i, i] <= 0.0:
            out[name] = math.inf
            continue
        a_inf = ds["added_mass_infinite"].values[i, i]
        omega = math.sqrt(c[i, i] / (m[i, i] + a_inf))
        for _ in range(_MAX_ITERATIONS):
            new = math.sqrt(c[i, i] / (m[i, i] + added_mass_at(ds, omega)[i, i]))
            done = abs(new - omega) <= _FREQUENCY_TOLERANCE * new
            omega = new
            if done:
                break
        out[name] = 2.0 * math.pi / omega
    return out


def coupled_natural_periods(ds: xr.Dataset, floater: Floater,
                            k_moor: NDArray[np.float64] | None = None) -> dict[str, float]:
    """Natural period [s] of the coupled undamped mode dominated by each DOF."""
    m, c = _mass_and_stiffness(ds, floater, k_moor)
    a_inf = ds["added_mass_infinite"].transpose("radiating_dof", "influenced_dof").values
    out: dict[str, float] = {}
    for i, name in enumerate(DOFS):
        omega = _mode_frequency(c, m + a_inf, i)
        for _ in range(_MAX_ITERATIONS):
            new = _mode_frequency(c, m + added_mass_at(ds, omega), i)
            if not math.isfinite(new) or abs(new - omega) <= _FREQUENCY_TOLERANCE * max(new, 1e-12):
                omega = new
                break
            omega = new
        out[name] = 2.0 * math.pi / omega if omega > 0 and math.isfinite(omega) else math.inf
    return out


def _mass_and_stiffness(ds, floater, k_moor):
    m = floater.mass_matrix()
    c = hydrostatic_stiffness_total(ds, floater)
    if k_moor is not None:
        c = c + k_moor
    return m, c


def _mode_frequency(c: NDArray, mass: NDArray, dof: int) -> float:
    from scipy.linalg import eig

    sym_mass = 0.5 * (mass + mass.T)
    values, vectors = eig(0.5 * (c + c.T), sym_mass)
    values = values.real
    best, share = math.nan, -1.0
    for n in range(6):
        v = vectors[:, n].real
        energy = v * (sym_mass @ v)
        total = float(energy.sum())
        frac = float(energy[dof] / total) if total != 0 else 0.0
        if frac > share:
            share, best = frac, values[n]
    return math.sqrt(best) if best > 0 else 0.0
