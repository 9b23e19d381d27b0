"""Excitation force transfer functions X(omega, beta) of a database, at any frequency and
direction in range (the force time series a run makes of them:
:mod:`floatmoor.waves.excitation_series`).

X is complex, per unit wave amplitude, capytaine's e^{-i omega t} convention: the force of a
wave of amplitude a is Re{X a e^{-i omega t}}. Interpolation acts on the real and imaginary
parts: linear in frequency (the BEM grid is dense), and in direction a cubic spline
(not-a-knot) through the BEM directions when there are at least four, linear otherwise. At
short waves X turns quickly with direction: on the DeepCwind database, the spline through
every other direction (30 degree steps) errs at the left-out directions by at most 1.5 % of
max |X| for wave periods of 9 s and more, but by 7 % at 7 s and 16 % at 5 s
(tests/hydro/test_excitation.py); the shipped 15 degree steps halve that step. Off-grid
directions of short waves need a finer direction grid.
Requests outside the computed frequency range or directions (modulo 360 degrees) raise
ValueError: the transfer functions are not extrapolated.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.hydro.database import (
    HydroDatabaseError, database_source, merge_complex, source_files,
)
from floatmoor.terminal_text import shown

__all__ = ["ExcitationInterpolator", "CUBIC_MIN_DIRECTIONS", "no_excitation_message"]

#: Directions needed for the cubic spline in direction (not-a-knot needs four points).
CUBIC_MIN_DIRECTIONS = 4


class ExcitationInterpolator:
    """Interpolate ``excitation_force`` (or another force variable) of a database.

    Parameters
    ----------
    ds
        The database.
    variable
        ``excitation_force``, ``Froude_Krylov_force`` or ``diffraction_force``.

    Raises
    ------
    HydroDatabaseError
        The database holds no such forces (imported from files without them).
    """

    def __init__(self, ds: xr.Dataset, variable: str = "excitation_force") -> None:
        if variable not in ds.variables:
            raise HydroDatabaseError(no_excitation_message(ds, variable))
        x = merge_complex(ds, variable).transpose("omega", "wave_direction", "influenced_dof")
        self.omega = np.asarray(ds["omega"].values, dtype=float)
        self.directions = np.asarray(ds["wave_direction"].values, dtype=float)
        self.values = np.asarray(x.values, dtype=complex)  # (omega, direction, dof)

    def __call__(self, omega: ArrayLike, direction: float = 0.0) -> NDArray[np.complex128]:
        """X at ``omega`` [rad/s] (scalar or array) and one direction [rad]; shape (..., 6)."""
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        tol = 1e-9 * self.omega[-1]
        if np.any(w < self.omega[0] - tol) or np.any(w > self.omega[-1] + tol):
            raise ValueError(f"frequency outside the database range [{self.omega[0]:g}, "
                             f"{self.omega[-1]:g}] rad/s")
        column = self._at_direction(float(direction))  # (omega, dof)
        out = np.zeros(w.shape + (6,), dtype=complex)
        for k in range(6):
            out[..., k] = (np.interp(w, self.omega, column[:, k].real)
                           + 1j * np.interp(w, self.omega, column[:, k].imag))
        return out if np.ndim(omega) else out[0]

    def _at_direction(self, beta: float) -> NDArray[np.complex128]:
        d = self.directions
        # directions are angles: a request is taken modulo 2 pi into the database's range
        # (an imported file turned by 180 deg holds -180 to 0 deg; waves towards 180 deg)
        turns = np.round((d[[0, -1]] - beta) / (2.0 * np.pi))
        for k in np.unique(turns):
            shifted = beta + 2.0 * np.pi * k
            if d[0] - 1e-9 <= shifted <= d[-1] + 1e-9:
                beta = float(np.clip(shifted, d[0], d[-1]))
                break
        hit = np.nonzero(np.abs(d - beta) < 1e-9)[0]
        if len(hit):
            return self.values[:, int(hit[0]), :]
        if len(d) < 2 or beta < d[0] or beta > d[-1]:
            raise ValueError(f"wave direction {np.degrees(beta):g} deg outside the database "
                             f"directions ({', '.join(f'{v:g}' for v in np.degrees(d))} deg)")
        if len(d) >= CUBIC_MIN_DIRECTIONS:
            from scipy.interpolate import CubicSpline

            spline = CubicSpline(d, self.values, axis=1)
            return spline(beta)
        j = int(np.searchsorted(d, beta))
        frac = (beta - d[j - 1]) / (d[j] - d[j - 1])
        return (1.0 - frac) * self.values[:, j - 1, :] + frac * self.values[:, j, :]


def no_excitation_message(ds: xr.Dataset, variable: str = "excitation_force") -> str:
    """``PATH: the hydrodynamic database has no excitation forces ...``, saying where it came
    from and what runs it serves."""
    where = ds.attrs.get("path", ds.attrs.get("database", "the database"))
    source = database_source(ds)
    origin = (f"imported from {source} files ({', '.join(_file_names(ds))}) that give none"
              if source != "capytaine" else "built without them")
    what = "excitation forces" if variable == "excitation_force" else variable
    return (f"{where}: the hydrodynamic database has no {what} ({origin}); a run with waves "
            "needs them: import the excitation too (WAMIT .3, or a BEMIO file with "
            "excitation), or run in still water or wind only")


def _file_names(ds: xr.Dataset) -> list[str]:
    return [shown(f.get("path"), 200) for f in source_files(ds)] or ["not recorded"]
