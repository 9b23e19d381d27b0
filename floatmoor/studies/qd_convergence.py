"""Convergence of the quasi-dynamic study's dynamic reference (docs/validation/notes.md).

:func:`reference_change` compares two study datasets computed at two dynamic resolutions
(``floatmoor study qd-verification --dynamic-elements N``, optionally on the same
``--amplitudes`` / ``--alphas`` subset): how much each statistic the study judges moves, and
which runs change class (docs/validation/notes.md#convergence-of-the-stored-dynamic-references).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["JUDGED", "CLASS_LIMITS", "reference_change"]

#: The judged statistics of :func:`reference_change` (peak_qd: max(e_Tmin, e_Tmax)).
JUDGED = ("rmse_qd", "rmse_s", "e_tmin", "e_tmax", "peak_qd")
#: The class limits the study judges the statistics by (section 4.2: under 10 %, under 20 %).
CLASS_LIMITS = (0.10, 0.20)


def reference_change(coarse, fine) -> dict[str, dict]:
    """Change of each judged statistic from the study dataset ``coarse`` to ``fine`` (two
    dynamic resolutions) over the runs both hold and both completed: the largest change
    (absolute, in the statistic's units, with its run), the median, and the runs whose class
    (under 10 %, under 20 %, above) changes."""
    import xarray as xr

    a, b = xr.align(coarse, fine, join="inner")
    out = {}
    for name in JUDGED:
        va, vb = (np.fmax(d["e_tmin"].values, d["e_tmax"].values) if name == "peak_qd"
                  else d[name].values for d in (a, b))
        ok = np.isfinite(va) & np.isfinite(vb)
        change = np.abs(vb - va)
        labels = [f"{c} {n} alpha {float(al):g}" for c in a["config"].values
                  for n in a["amplitude_name"].values for al in a["alpha"].values]
        flat, cflat, okflat = change.ravel(), va.ravel(), ok.ravel()
        worst = int(np.argmax(np.where(okflat, flat, -1.0))) if okflat.any() else None
        moved = [labels[k] for k in np.flatnonzero(okflat) if
                 np.searchsorted(CLASS_LIMITS, cflat[k], side="right")
                 != np.searchsorted(CLASS_LIMITS, vb.ravel()[k], side="right")]
        out[name] = {"runs": int(okflat.sum()),
                     "max": float(flat[worst]) if worst is not None else math.nan,
                     "max_run": labels[worst] if worst is not None else "",
                     "median": float(np.median(flat[okflat])) if okflat.any() else math.nan,
                     "class_changes": moved}
    return out
