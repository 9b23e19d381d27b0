"""Cheap checks of a hydrodynamic database's values that no case may accept away.

The recorded inputs hash says which inputs a database was built from, not that its numbers
are still the ones the BEM solver wrote: a file edited afterwards (or damaged in a way that
keeps it readable) can hold negative damping, a zero volume or values so large that the
equations of motion overflow. :mod:`floatmoor.hydro.checks` measures the accuracy of a
database, and a case may accept its failures (``[hydro] accept_failed_checks``); the checks
here test what must hold for any body at all, so a run never uses a database failing them:

* every matrix finite and below :data:`MAX_HYDRO_MAGNITUDE` (products stay finite);
* displaced volume, waterplane area and heave stiffness C33 positive (a floating body);
* A_inf symmetric and positive semidefinite (it is the kinetic energy of the fluid with a
  rigid free surface), and M + A_inf positive definite (the body's inertia);
* every diagonal radiation damping B_ii(omega) not negative beyond
  :data:`~floatmoor.hydro.checks.PSD_TOLERANCE` of its peak (a body radiates energy).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray

__all__ = ["value_problems", "MAX_HYDRO_MAGNITUDE", "VALUE_SYMMETRY_TOLERANCE",
           "VALUE_SIGN_TOLERANCE"]

#: Largest magnitude of any database value (SI units). The largest floating structures have
#: masses ~1e9 kg and inertias ~1e13 kg m^2, so 1e30 is far beyond any physical value and far
#: below the square root of the largest double (1e154), so products of two values stay finite.
MAX_HYDRO_MAGNITUDE = 1e30
#: |A_inf - A_inf^T| relative to max |A_inf|: ten times the accuracy check's reciprocity
#: tolerance (floatmoor.hydro.checks.RECIPROCITY_TOLERANCE = 1 %), so only a matrix that is
#: not a BEM result at all fails here.
VALUE_SYMMETRY_TOLERANCE = 0.1
#: Negative eigenvalues of A_inf, and of each B_ii(omega), relative to the largest magnitude
#: are tolerated down to this (the accuracy check's PSD_TOLERANCE, 1 %): discretisation error.
VALUE_SIGN_TOLERANCE = 0.01

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
_MATRICES = ("added_mass", "added_mass_infinite", "radiation_damping",
             "hydrostatic_stiffness", "excitation_force")


def _square(ds: xr.Dataset, name: str) -> NDArray[np.float64]:
    return ds[name].transpose(..., "radiating_dof", "influenced_dof").values.astype(float) \
        if "radiating_dof" in ds[name].dims else ds[name].values.astype(float)


def value_problems(ds: xr.Dataset, mass_matrix: NDArray[np.float64] | None = None) -> list[str]:
    """What is physically impossible in the database's values (empty when nothing is).

    Parameters
    ----------
    ds
        A database read by :func:`floatmoor.hydro.database.read_database`.
    mass_matrix
        The body's 6x6 rigid-body mass matrix [kg, kg m, kg m^2], for the M + A_inf check
        (skipped without it).

    Returns
    -------
    list of str
        One short sentence per problem.
    """
    problems: list[str] = []
    for name in _MATRICES:
        if name not in ds.variables:
            continue
        values = np.asarray(ds[name].values, dtype=float)
        if not np.all(np.isfinite(values)):
            problems.append(f"{name} holds non-finite values")
        elif values.size and np.abs(values).max() > MAX_HYDRO_MAGNITUDE:
            problems.append(f"{name} holds values up to {np.abs(values).max():.3g} (more than "
                            f"{MAX_HYDRO_MAGNITUDE:g} in SI units)")
    if problems:  # the remaining checks need finite, moderate values
        return problems
    for name in ("disp_volume", "waterplane_area"):
        value = float(ds[name].values)
        if not value > 0.0:
            problems.append(f"{name} is {value:g}, not positive")
    c = ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values
    if not c[2, 2] > 0.0:
        problems.append(f"heave hydrostatic stiffness C33 is {c[2, 2]:g} N/m, not positive")
    a_inf = _square(ds, "added_mass_infinite")
    scale = float(np.abs(a_inf).max())
    if scale > 0.0:
        asym = float(np.abs(a_inf - a_inf.T).max()) / scale
        if asym > VALUE_SYMMETRY_TOLERANCE:
            problems.append(f"added_mass_infinite is not symmetric (|A - A^T| up to "
                            f"{asym:.3g} of its largest value)")
        lowest = float(np.linalg.eigvalsh(0.5 * (a_inf + a_inf.T)).min())
        if lowest < -VALUE_SIGN_TOLERANCE * scale:
            problems.append(f"added_mass_infinite is not positive semidefinite (eigenvalue "
                            f"{lowest:.3g})")
    if mass_matrix is not None:
        total = np.asarray(mass_matrix, dtype=float) + 0.5 * (a_inf + a_inf.T)
        try:
            np.linalg.cholesky(total)
        except np.linalg.LinAlgError:
            lowest = float(np.linalg.eigvalsh(total).min())
            problems.append(f"M + added_mass_infinite is not positive definite (eigenvalue "
                            f"{lowest:.3g}): the body would have no inertia in some motion")
    b = _square(ds, "radiation_damping")
    for i in range(6):
        diagonal = b[:, i, i]
        peak = float(np.abs(diagonal).max())
        if peak > 0.0 and diagonal.min() < -VALUE_SIGN_TOLERANCE * peak:
            j = int(np.argmin(diagonal))
            problems.append(f"radiation_damping {_DOFS[i]}-{_DOFS[i]} is negative "
                            f"({diagonal[j]:.3g} at omega = {float(ds['omega'].values[j]):.4g} "
                            "rad/s): the body would gain energy from radiating waves")
            break
    return problems
