"""A database's state-space realisation: every significant pair of its radiation kernels
fitted, and whether a stored realisation still belongs to the database
(docs/theory/floater.md#radiation-convolution-or-state-space).

:func:`fit_state_space` realises each significant pair (j radiating, i influenced) of the
database's K(t) (:func:`floatmoor.hydro.radiation.radiation_kernel`, indices as the
database's damping) by :func:`floatmoor.hydro.state_space.kernel_fit.fit_kernel`, with its
errors against the BEM values; :func:`stale_reasons` says when a stored realisation no longer
belongs to the database. The other parts of the feature are the package's other modules
(:mod:`floatmoor.hydro.state_space`).

The fit records the K(t) settings it was made from (truncation time, step, tail exponents and
constants of :mod:`floatmoor.hydro.radiation`, the database's inputs hash) and a fingerprint
of K; :func:`stale_reasons` compares them with what the current code computes from the file.
"""

from __future__ import annotations

import datetime as _dt
import math
import time as _time
from dataclasses import replace
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.hydro import radiation as _rad
from floatmoor.hydro.state_space.kernel_fit import (
    HANKEL_ROWS, KERNEL_RTOL, LOW_FREQUENCY_BAND, LOW_FREQUENCY_POINTS, LOW_FREQUENCY_WEIGHT,
    MAX_ORDER, METHOD, fit_kernel,
)
from floatmoor.hydro.state_space.realisation import DOFS, PASSIVITY_POINTS, StateSpaceRadiation
from floatmoor.hydro.state_space.storage import read_state_space

__all__ = ["fit_state_space", "significant_pairs", "kernel_settings", "stale_reasons",
           "low_frequency_transform"]

#: H(i omega) of the low band is integrated with K refined this many times over the first
#: _CUSP_STEPS steps of the K grid: a damping tail B ~ omega^-p with p < 2 gives K a cusp
#: ~ t^(p-1) at t = 0 (DeepCwind surge, p = 1.2) that the grid's Simpson rule integrates
#: 8e4 kg/s off (int K over the K grid against -440 kg/s converged).
_CUSP_REFINEMENT = 50
_CUSP_STEPS = 20
#: Fingerprint of K: recorded moments must match the current code's to this relative
#: precision (far above the round-off of recomputing K, ~1e-15, and below any change that
#: matters to a fit whose own error is :data:`KERNEL_RTOL`).
FINGERPRINT_RTOL = 1e-6


# -- a database's kernels -------------------------------------------------------------------

def significant_pairs(kernel: NDArray[np.float64]) -> list[tuple[int, int]]:
    """(radiating, influenced) pairs of K (m, 6, 6) the convolution sums: peak above
    :data:`floatmoor.hydro.radiation.KERNEL_NEGLIGIBLE` of the largest."""
    peak = np.abs(kernel).max(axis=0)
    top = float(peak.max())
    return [(int(i), int(j)) for i, j in np.argwhere(peak > _rad.KERNEL_NEGLIGIBLE * top)] \
        if top > 0.0 else []


def _fingerprint(time: NDArray[np.float64], kernel: NDArray[np.float64],
                 pairs: list[tuple[int, int]]) -> dict[str, list[float]]:
    """Per pair: K(0), int K dt, sqrt(int K^2 dt) (trapezoidal)."""
    out = {}
    for i, j in pairs:
        k = kernel[:, i, j]
        out[f"{DOFS[i]}-{DOFS[j]}"] = [float(k[0]), float(np.trapezoid(k, time)),
                                        float(math.sqrt(np.trapezoid(k * k, time)))]
    return out


def kernel_settings(ds: xr.Dataset, kernel: _rad.RadiationKernel | None = None
                    ) -> dict[str, Any]:
    """What a fit of ``ds`` depends on besides the BEM data: the K(t) grid and tail, the
    constants of :mod:`floatmoor.hydro.radiation`, the negligible-pair threshold, the
    database's inputs hash, and a fingerprint of K over the significant pairs."""
    k = kernel if kernel is not None else _rad.radiation_kernel(ds)
    pairs = significant_pairs(k.kernel)
    return {
        "truncation_time": float(k.truncation_time), "time_step": float(k.time[1]),
        "samples": int(k.time.size), "tail_exponent": "fitted",
        "tail_exponents": np.round(k.tail_exponent, 6).tolist(),
        "tail_extent": _rad.TAIL_EXTENT, "tail_range": [_rad.TAIL_MIN, _rad.TAIL_MAX],
        "default_tail_exponent": _rad.TAIL_EXPONENT,
        "tail_points_per_decade": _rad._TAIL_POINTS_PER_DECADE,
        "negligible": _rad.KERNEL_NEGLIGIBLE, "inputs_hash": ds.attrs.get("inputs_hash", ""),
        "fingerprint": _fingerprint(k.time, k.kernel, pairs),
    }


def _damping(ds: xr.Dataset) -> NDArray[np.float64]:
    return ds["radiation_damping"].transpose("omega", "radiating_dof", "influenced_dof").values


def low_frequency_transform(ds: xr.Dataset, kernel: _rad.RadiationKernel,
                            omega: NDArray[np.float64]) -> NDArray[np.complex128]:
    """int_0^T K(t) e^{-i omega t} dt (n, 6, 6) of the database's truncated K, by Simpson's
    rule on the K grid, refined near t = 0 (see :data:`_CUSP_REFINEMENT`)."""
    from scipy.integrate import simpson

    t = kernel.time
    split = min(_CUSP_STEPS, (t.size - 1) // 2 * 2)
    fine = np.linspace(0.0, float(t[split]), split * _CUSP_REFINEMENT + 1)
    damping = _damping(ds)
    k_fine = _rad.impulse_response(ds["omega"].values, damping, fine,
                                   tail_exponent=kernel.tail_exponent)
    out = np.empty((len(omega), 6, 6), complex)
    for n, w in enumerate(np.asarray(omega, float)):
        head = simpson(k_fine * np.exp(-1j * w * fine)[:, None, None], x=fine, axis=0)
        rest = simpson(kernel.kernel[split:] * np.exp(-1j * w * t[split:])[:, None, None],
                       x=t[split:], axis=0)
        out[n] = head + rest
    return out


def fit_state_space(ds: xr.Dataset, *, rtol: float = KERNEL_RTOL, max_order: int = MAX_ORDER,
                    hankel_rows: int = HANKEL_ROWS,
                    kernel: _rad.RadiationKernel | None = None) -> StateSpaceRadiation:
    """Realise every significant K_ij(t) of a database (K on the database's default grid,
    :func:`floatmoor.hydro.radiation.radiation_kernel`), diagonal pairs passive, with each
    pair's damping error against the BEM B(omega) over the band."""
    start = _time.perf_counter()
    k = kernel if kernel is not None else _rad.radiation_kernel(ds)
    omega = ds["omega"].values
    bem = _damping(ds)
    added = ds["added_mass"].transpose("omega", "radiating_dof", "influenced_dof").values
    peak = np.abs(np.diagonal(bem, axis1=1, axis2=2)).max(axis=0)
    peak_a = np.abs(np.diagonal(added, axis1=1, axis2=2)).max(axis=0)
    low = np.linspace(0.0, LOW_FREQUENCY_BAND * float(omega[0]), LOW_FREQUENCY_POINTS)
    target = low_frequency_transform(ds, k, low)
    fits = []
    for i, j in significant_pairs(k.kernel):
        fit = fit_kernel(k.time, k.kernel[:, i, j], rtol=rtol, max_order=max_order,
                         passive=i == j, zero_dc=True, low_frequency=(low, target[:, i, j]),
                         hankel_rows=hankel_rows)
        h = fit.transfer(omega)
        scale = math.sqrt(peak[i] * peak[j])
        err = float(np.abs(h.real - bem[:, i, j]).max() / scale) if scale > 0.0 else math.nan
        # A(omega) - A_inf of the fit, A_inf the mean the band implies (as the body's)
        shape = h.imag / omega
        implied = float(np.mean(added[:, i, j] - shape))
        scale_a = math.sqrt(peak_a[i] * peak_a[j])
        err_a = float(np.abs(implied + shape - added[:, i, j]).max() / scale_a) \
            if scale_a > 0.0 else math.nan
        fits.append(replace(fit, radiating=i, influenced=j, damping_error=err,
                            added_mass_error=err_a))
    settings = {"method": METHOD, "kernel_rtol": rtol, "max_order": max_order,
                "hankel_rows": hankel_rows, "passivity_points": PASSIVITY_POINTS,
                "zero_frequency_damping": 0.0,
                "low_frequency_band": [0.0, float(low[-1]), LOW_FREQUENCY_POINTS],
                "low_frequency_weight": LOW_FREQUENCY_WEIGHT,
                "cusp_refinement": [_CUSP_REFINEMENT, _CUSP_STEPS]}
    created = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    out = StateSpaceRadiation(tuple(fits), settings, kernel_settings(ds, k), created,
                              _time.perf_counter() - start)
    return replace(out, matrix_min_damping=out.matrix_passivity())


# -- staleness ------------------------------------------------------------------------------

def _close(a: Any, b: Any, rtol: float) -> bool:
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_close(x, y, rtol) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and \
            not isinstance(a, bool) and not isinstance(b, bool):
        return abs(a - b) <= rtol * max(abs(a), abs(b)) or a == b
    return a == b


def stale_reasons(ds: xr.Dataset, realisation: StateSpaceRadiation | None = None,
                  kernel: _rad.RadiationKernel | None = None) -> list[str]:
    """Why the stored realisation no longer belongs to the database's K(t) (empty when it
    does): the K settings it was fitted with differ from the current code's, or K itself
    (fingerprint) differs.

    ``kernel`` is the database's default K (:func:`floatmoor.hydro.radiation.
    radiation_kernel`) when the caller has it.
    """
    realisation = realisation if realisation is not None else read_state_space(ds)
    if realisation is None:
        return ["no state-space realisation"]
    recorded = realisation.kernel_settings
    current = kernel_settings(ds, kernel)
    reasons = []
    for key in sorted(set(recorded) | set(current)):
        if key == "fingerprint":
            continue
        if key == "tail_exponents":
            same = _close(recorded.get(key), current.get(key), 0.0) or (
                np.shape(recorded.get(key)) == np.shape(current.get(key))
                and np.allclose(recorded.get(key), current.get(key), rtol=0.0, atol=2e-6))
        else:
            same = _close(recorded.get(key), current.get(key), 1e-12)
        if not same:
            reasons.append(f"{key} was {recorded.get(key)!r}, now {current.get(key)!r}")
    old, new = recorded.get("fingerprint", {}), current["fingerprint"]
    if set(old) != set(new):
        reasons.append(f"significant pairs were {sorted(old)}, now {sorted(new)}")
    else:
        for name in sorted(new):
            # K(0) and ||K|| relative to themselves, int K (near zero: B(0) = 0) to its
            # Cauchy-Schwarz bound sqrt(T) ||K||
            k0, integral, norm = new[name]
            scales = (abs(k0), norm * math.sqrt(current["truncation_time"]), norm)
            if len(old[name]) != 3 or any(abs(x - y) > FINGERPRINT_RTOL * s for x, y, s
                                          in zip(old[name], new[name], scales)):
                reasons.append(f"K {name} differs from the one fitted (K(0), int K, "
                               f"||K||: {old[name]} then, {new[name]} now)")
    return reasons
