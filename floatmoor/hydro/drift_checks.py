"""The ``drift`` row of ``floatmoor hydro check``: far-field against near-field mean drift
(docs/guide/hydro_databases.md#mean-drift).

Surge and sway are compared against the peak far-field force drift, yaw against its own peak
when it is not negligible; frequencies where the near field is ill-conditioned (its terms
cancel to less than 1/:data:`DRIFT_CONDITIONING` of their magnitudes, near a lightly damped
resonance) are left out and named, and so are the frequencies where the row fails (the
difference over the tolerance). Imported drift (WAMIT .8 and .9, BEMIO) is compared the
same way when both routes were imported (without the near field's terms, every frequency is
compared); with one route the row is not applicable. A run's second-order loads use the
coefficients whatever this row says (their route is the case's choice), so it is not among the
checks a run enforces (:func:`floatmoor.hydro.checks.run_checks`).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

from floatmoor.hydro.checks import CheckResult, _frequency_list

__all__ = ["DRIFT_TOLERANCE", "DRIFT_CONDITIONING", "NEGLIGIBLE_YAW_DRIFT",
           "drift_conditioning", "drift_differences", "drift_by_frequency", "check_drift"]

#: Far-field against near-field mean drift in Surge, Sway and Yaw: within 5 % of the peak
#: (docs/guide/hydro_databases.md#mean-drift).
DRIFT_TOLERANCE = 0.05
#: The yaw drift is compared when its peak is at least this fraction of the peak force drift
#: times the waterplane's length scale sqrt(A_wp) (a body heading into waves has none).
NEGLIGIBLE_YAW_DRIFT = 1e-3
#: The near field is compared only where its terms cancel to no less than 1/10 of the sum of
#: their magnitudes: a 0.5 % error in the terms is then at most 5 % of the drift. Near a
#: lightly damped resonance the terms grow with the motions while the drift does not (the
#: buoy's pitch at 5.3-6.5 rad/s: 1/15 to 1/150).
DRIFT_CONDITIONING = 10.0

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


def drift_conditioning(ds: xr.Dataset) -> np.ndarray:
    """Per (omega, wave_direction, DOF): the near field's sum of |terms| over |their sum|,
    its loss to cancellation (an error e in the terms is e times this in the drift)."""
    terms = ds["mean_drift_near_field_terms"].transpose(
        "drift_term", "omega", "wave_direction", "influenced_dof").values
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.abs(terms).sum(axis=0) / np.abs(terms.sum(axis=0))


def drift_by_frequency(ds: xr.Dataset, *, left_out_too: bool = False
                       ) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Per compared DOF, max over directions of |far - near| / peak at each frequency (NaN
    where left out, unless ``left_out_too``), and the frequencies left out
    (:func:`drift_differences`)."""
    return _differences(ds, left_out_too)


def drift_differences(ds: xr.Dataset) -> tuple[dict[str, float], np.ndarray]:
    """max |far - near| / peak |far| of the mean drift per compared DOF (Surge and Sway
    against the peak far-field force drift of the two, Yaw against its own peak when not
    negligible), over the frequencies where the near field is well conditioned
    (:data:`DRIFT_CONDITIONING` at every direction and compared DOF where the drift matters);
    and the frequencies left out."""
    per_omega, left_out = _differences(ds)
    out = {k: float(np.nanmax(v)) if np.any(np.isfinite(v)) else math.nan
           for k, v in per_omega.items()}
    return out, left_out


def _differences(ds: xr.Dataset, left_out_too: bool = False
                 ) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """:func:`drift_by_frequency`."""
    near = ds["mean_drift_near_field"].transpose("omega", "wave_direction",
                                                 "influenced_dof").values
    far = ds["mean_drift_far_field"].transpose("omega", "wave_direction",
                                               "influenced_dof").values
    conditioning = drift_conditioning(ds) if "mean_drift_near_field_terms" in ds.variables \
        else np.ones_like(near)
    force_peak = float(np.abs(far[..., :2]).max())
    yaw_peak = float(np.abs(far[..., 5]).max())
    length = math.sqrt(max(float(ds["waterplane_area"].values), 0.0))
    compared = [i for i in (0, 1) if force_peak > 0.0]
    if yaw_peak > NEGLIGIBLE_YAW_DRIFT * force_peak * length:
        compared.append(5)
    peaks = {0: force_peak, 1: force_peak, 5: yaw_peak}
    bad = np.zeros(near.shape[0], bool)
    for i in compared:
        matters = np.maximum(np.abs(near[..., i]), np.abs(far[..., i])) > 0.01 * peaks[i]
        bad |= np.any(matters & ~(conditioning[..., i] <= DRIFT_CONDITIONING), axis=1)
    out: dict[str, np.ndarray] = {}
    for i in compared:
        diff = np.abs(far[..., i] - near[..., i]).max(axis=1) / peaks[i]
        out[_DOFS[i]] = diff if left_out_too else np.where(bad, np.nan, diff)
    return out, ds["omega"].values[bad]


def check_drift(ds: xr.Dataset) -> CheckResult:
    """Far-field against near-field mean drift (``hydro check``; not a run's check: a run
    uses the route its case chooses).

    Parameters
    ----------
    ds
        A database with mean drift (:func:`floatmoor.hydro.drift_build.add_drift`).

    Returns
    -------
    CheckResult
        The ``drift`` row."""
    held = [v for v in ("mean_drift_far_field", "mean_drift_near_field") if v in ds.variables]
    if not held:
        return CheckResult.not_applicable("drift", DRIFT_TOLERANCE, "no mean drift "
                                          "coefficients (hydro build --drift adds them)")
    if len(held) == 1:
        route = "far field (momentum)" if held[0] == "mean_drift_far_field" else \
            "near field (pressure)"
        source = ds.attrs.get("drift_source")  # file text: quoted only when a known value
        source = source if source in ("wamit", "bemio") else "its source"
        return CheckResult.not_applicable(
            "drift", DRIFT_TOLERANCE, f"only the {route} mean drift (imported from "
            f"{source} files): nothing to compare it with")
    per_omega, left_out = drift_by_frequency(ds)
    errors, _ = drift_differences(ds)
    if not errors:
        return CheckResult.not_applicable("drift", DRIFT_TOLERANCE, "no horizontal drift")
    worst = max(errors.values())
    detail = "far vs near field, of the peak: " + ", ".join(
        f"{k} {v:.2%}" for k, v in errors.items())
    over = np.zeros(ds.sizes["omega"], bool)
    for v in per_omega.values():
        over |= np.nan_to_num(v) > DRIFT_TOLERANCE
    if np.any(over):
        detail += (f"; over {DRIFT_TOLERANCE:.0%} at {_frequency_list(ds['omega'].values[over])}"
                   " rad/s")
    if len(left_out):
        every, _ = drift_by_frequency(ds, left_out_too=True)
        there = max(float(np.nanmax(v[np.isin(ds["omega"].values, left_out)]))
                    for v in every.values())
        detail += (f"; {len(left_out)} of {ds.sizes['omega']} frequencies left out, where the "
                   f"near field cancels to less than 1/{DRIFT_CONDITIONING:g} of its terms "
                   f"(resonant motions, or the waterline and velocity terms of short waves): "
                   f"{_frequency_list(left_out)} rad/s, far vs near {there:.2%} there")
    return CheckResult("drift", bool(worst <= DRIFT_TOLERANCE), worst, DRIFT_TOLERANCE,
                       detail)
