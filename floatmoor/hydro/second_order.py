"""Second-order wave load coefficients of a database, at the sea's frequencies and direction
(the lookup beside :class:`~floatmoor.hydro.excitation_transfer.ExcitationInterpolator`; the
forces are in floatmoor.waves.second_order; theory:
docs/theory/hydrodynamics.md#second-order-wave-loads).

Mean drift D(omega, beta) (``mean_drift_far_field``, ``mean_drift_near_field``; N/m^2,
N m/m^2 per unit wave amplitude squared): the route the case chooses
(``[waves] drift_coefficients``) gives

* ``"far_field"``: Surge, Sway, Yaw from the far field (momentum); Heave, Roll, Pitch from the
  near field when the database holds it, zero otherwise (a WAMIT .8 alone has none);
* ``"near_field"``: all six DOFs from the near field (pressure integration).

Interpolated like the excitation: linear in frequency, a cubic spline in direction through
four or more directions (linear through fewer); zero for a component outside the database's
frequencies (the excitation is too); a direction outside the database's is an error.

Difference-frequency QTF (``qtf_difference``: complex, qtf_direction, qtf_omega_1,
qtf_omega_2, influenced_dof): taken at the sea's direction (same rule in direction); the
force module interpolates it bilinearly on (qtf_omega_1, qtf_omega_2).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from floatmoor.hydro.excitation_transfer import ExcitationInterpolator

__all__ = ["DriftLookup", "QTFLookup", "DirectionError", "drift_source", "missing_coefficients",
           "route_text", "FAR_FIELD_DOFS", "QTF_VARIABLE", "DRIFT_VARIABLE"]

#: The DOFs the far field (momentum) route gives: Surge, Sway, Yaw.
FAR_FIELD_DOFS = (0, 1, 5)
#: Database variable of each route.
DRIFT_VARIABLE = {"far_field": "mean_drift_far_field", "near_field": "mean_drift_near_field"}
#: Database variable of the difference-frequency QTF.
QTF_VARIABLE = "qtf_difference"


class DirectionError(ValueError):
    """A wave direction outside the directions of the coefficients."""


def _column(lookup: ExcitationInterpolator, beta: float) -> NDArray:
    try:
        return lookup._at_direction(beta)
    except ValueError as err:
        raise DirectionError(str(err)) from None


def drift_source(ds: xr.Dataset) -> str:
    """Where the database's second-order coefficients come from: its ``drift_source``
    attribute ("floatmoor", "wamit", "bemio"); a database built by ``hydro build --drift``
    before that attribute existed is "floatmoor" (it records ``drift_inputs_hash``)."""
    source = ds.attrs.get("drift_source")
    if isinstance(source, str) and source:
        return source
    return "floatmoor" if "drift_inputs_hash" in ds.attrs else "not recorded"


def missing_coefficients(ds: xr.Dataset, model: str, route: str) -> str | None:
    """What the database lacks for ``second_order = model`` with ``drift_coefficients =
    route`` (None when it has it)."""
    if model == "none":
        return None
    if model == "full":
        return None if QTF_VARIABLE in ds.variables else \
            f"no difference-frequency QTF ({QTF_VARIABLE})"
    name = DRIFT_VARIABLE[route]
    if name in ds.variables:
        return None
    held = [r for r, v in DRIFT_VARIABLE.items() if v in ds.variables]
    if held:
        return f"no {route.replace('_', ' ')} mean drift ({name}; it holds the " \
               f"{held[0].replace('_', ' ')} only)"
    return "no mean drift coefficients (mean_drift_far_field, mean_drift_near_field)"


def route_text(ds: xr.Dataset, model: str, route: str) -> str:
    """How the run's coefficients are made up, for the result's attributes."""
    if model == "full":
        source = ds[QTF_VARIABLE].attrs.get("qtf_source", "not recorded")
        return f"{QTF_VARIABLE} (qtf_source: {source})"
    if route == "near_field":
        return "mean_drift_near_field, all six DOFs"
    vertical = "mean_drift_near_field" if DRIFT_VARIABLE["near_field"] in ds.variables else \
        "zero (the database has no near field)"
    return f"mean_drift_far_field for Surge, Sway, Yaw; Heave, Roll, Pitch: {vertical}"


class DriftLookup(ExcitationInterpolator):
    """Mean drift coefficients of one route, at any frequency and direction in range.

    Parameters
    ----------
    ds
        The database (holding the route's variable: :func:`missing_coefficients`).
    route
        ``"far_field"`` or ``"near_field"`` (module docstring).
    """

    def __init__(self, ds: xr.Dataset, route: str) -> None:  # noqa: super() not called
        def table(name: str) -> NDArray[np.float64]:
            return np.asarray(ds[name].transpose("omega", "wave_direction",
                                                 "influenced_dof").values, dtype=float)

        values = table(DRIFT_VARIABLE[route])
        if route == "far_field":
            vertical = (table(DRIFT_VARIABLE["near_field"])
                        if DRIFT_VARIABLE["near_field"] in ds.variables
                        else np.zeros_like(values))
            others = [k for k in range(6) if k not in FAR_FIELD_DOFS]
            values = values.copy()
            values[:, :, others] = vertical[:, :, others]
        self.omega = np.asarray(ds["omega"].values, dtype=float)
        self.directions = np.asarray(ds["wave_direction"].values, dtype=float)
        self.values = values  # (omega, direction, dof)

    def covers(self, omega: ArrayLike) -> NDArray[np.bool_]:
        """Whether each frequency [rad/s] is inside the database's."""
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        return (w >= self.omega[0]) & (w <= self.omega[-1])

    def column(self, direction: float) -> NDArray[np.float64]:
        """D on the database's frequencies (:attr:`omega`) at ``direction`` [rad], shape
        (n_omega, 6) (may hold NaN where the database does).

        Raises
        ------
        DirectionError
            A direction outside the database's.
        """
        return np.asarray(_column(self, float(direction)), dtype=float)

    def at(self, omega: ArrayLike, direction: ArrayLike) -> NDArray[np.float64]:
        """D at each component (frequency [rad/s], direction [rad]), shape (N, 6); zero for a
        frequency outside the database's.

        Raises
        ------
        DirectionError
            A direction outside the database's.
        ValueError
            Coefficients that are not finite where the sea needs them (naming the
            frequency).
        """
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        beta = np.broadcast_to(np.asarray(direction, dtype=float), w.shape)
        out = np.zeros((w.size, 6))
        inside = self.covers(w)
        for b in np.unique(beta):
            sel = inside & (beta == b)
            if not np.any(sel):
                continue
            column = _column(self, float(b))  # (omega, dof)
            for k in range(6):
                out[sel, k] = np.interp(w[sel], self.omega, column[:, k])
        bad = ~np.all(np.isfinite(out), axis=1)
        if np.any(bad):
            raise ValueError(f"drift coefficients not finite at {w[bad][0]:g} rad/s")
        return out


class QTFLookup(ExcitationInterpolator):
    """The difference-frequency QTF of a database at one direction.

    Parameters
    ----------
    ds
        The database (holding ``qtf_difference``).
    """

    def __init__(self, ds: xr.Dataset) -> None:  # noqa: super() not called
        """Raises ValueError for a QTF whose two frequency axes differ or do not ascend."""
        da = ds[QTF_VARIABLE]
        w1 = np.asarray(ds["qtf_omega_1"].values, dtype=float)
        w2 = np.asarray(ds["qtf_omega_2"].values, dtype=float)
        if w1.size < 2 or not np.array_equal(w1, w2) or np.any(np.diff(w1) <= 0.0):
            raise ValueError("qtf_omega_1 and qtf_omega_2 must be the same two or more "
                             "ascending frequencies")
        labels = [str(v) for v in da["complex"].values] if "complex" in da.coords else []
        real, imag = ("re", "im") if "re" in labels else ("real", "imag")
        values = (da.sel(complex=real, drop=True) + 1j * da.sel(complex=imag, drop=True))
        values = values.transpose("qtf_omega_1", "qtf_direction", "qtf_omega_2",
                                  "influenced_dof")
        self.grid = np.asarray(ds["qtf_omega_1"].values, dtype=float)
        m = self.grid.size
        self.omega = self.grid
        self.directions = np.asarray(ds["qtf_direction"].values, dtype=float)
        # (omega_1, direction, omega_2 x dof): the excitation's direction rule applies as is
        self.values = np.asarray(values.values, dtype=complex).reshape(
            m, self.directions.size, -1)

    def at(self, direction: float) -> NDArray[np.complex128]:
        """Q on the grid at ``direction`` [rad], shape (M, M, 6).

        Raises
        ------
        DirectionError
            A direction outside the database's QTF directions.
        ValueError
            A QTF that is not finite there.
        """
        m = self.grid.size
        q = np.asarray(_column(self, float(direction))).reshape(m, m, -1)
        if not np.all(np.isfinite(q)):
            raise ValueError("QTF not finite on its grid")
        return q
