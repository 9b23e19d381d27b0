"""Plain Python/NumPy reference of rainflow counting, independent of the numba kernel.

A different algorithm from :mod:`floatmoor.post.rainflow` (the ASTM E1049 three-point method):
the four-point method (Amzallag et al. 1994, "Standardization of the rainflow counting method
for fatigue analysis", Int. J. Fatigue 16(4)): with four consecutive reversals A, B, C, D on
the stack, the inner range B-C is a closed cycle when min(B, C) >= min(A, D) and
max(B, C) <= max(A, D); it is counted as one cycle and B, C are removed. What remains (the
residue) is counted as half cycles, one per range between consecutive residue points. On
complete records both methods give the same ranges and counts.

Reversals are found with a plain loop over the samples (plateaus collapse to one point; the
first and last samples are reversals), not with the array expressions of the module.
"""

from __future__ import annotations

import numpy as np


def reversals(values) -> list[float]:
    """Peaks, valleys and the two end points, by a sample-by-sample scan."""
    out: list[float] = []
    for v in (float(s) for s in values):
        if out and v == out[-1]:
            continue
        if len(out) >= 2 and (out[-1] - out[-2]) * (v - out[-1]) > 0.0:
            out[-1] = v  # still rising (or falling): the previous point was no reversal
        else:
            out.append(v)
    return out


def four_point_cycles(values) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Ranges, means and counts by the four-point method with a half-cycle residue."""
    ranges: list[float] = []
    means: list[float] = []
    counts: list[float] = []
    stack: list[float] = []
    for p in reversals(values):
        stack.append(p)
        while len(stack) >= 4:
            a, b, c, d = stack[-4:]
            if min(b, c) >= min(a, d) and max(b, c) <= max(a, d):
                ranges.append(abs(b - c))
                means.append(0.5 * (b + c))
                counts.append(1.0)
                del stack[-3:-1]
            else:
                break
    for a, b in zip(stack[:-1], stack[1:]):
        ranges.append(abs(b - a))
        means.append(0.5 * (a + b))
        counts.append(0.5)
    return np.array(ranges), np.array(means), np.array(counts)
