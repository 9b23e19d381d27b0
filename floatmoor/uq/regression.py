"""Sparse gPC coefficients by least-angle regression, for one output or thousands.

Least-angle regression (LAR, Efron et al. 2004) on the hyperbolic basis, each step's active set
refitted by least squares and the step of smallest corrected leave-one-out error kept (Blatman &
Sudret 2011, the UQLab method of the gpc paper section 3.2): OpenTURNS'
``LeastSquaresMetaModelSelectionFactory(LARS(), CorrectedLeaveOneOut())``.

Many outputs (a time series) are first reduced: the centred output matrix Y - mean (n runs x m
outputs) is split by SVD into modes U S V^T, the leading modes that together hold all but
:data:`DROPPED_ENERGY` of its sum of squares are fitted one by one (at most n fits whatever m),
and the outputs' coefficients are the modes' recombined, C = sum_k c_k V_k^T (plus the mean on
the constant): exact for a linear recombination, so the statistics and Sobol indices computed
from C are those of the recombined surrogate; fitting by modes is what makes a time series of
thousands of outputs affordable (timings in docs/validation/notes.md).

Validation error of each output: the leave-one-out residuals of the modes, each mode's scaled by
the square root of its correction factor T(P_k, n) = n / (n - P_k) (1 + tr(C_k^-1) / n),
C_k = A_k^T A_k / n on its P_k selected polynomials (Chapelle et al. 2002, as OpenTURNS'
``CorrectedLeaveOneOut``), recombined with V, plus the part of the dropped modes, summed in
squares over the runs and divided by the output's sum of squares about its mean. For one mode it
is the corrected LOO relative error of that fit.

OpenTURNS stops the LAR path once the error exceeds twice its minimum so far
(``LeastSquaresMetaModelSelection-MaximumErrorFactor`` = 2); here the path goes on to its end
(min(P, n) steps, the UQLab way), as a sparse model's exact set can come after such a rise: with
the stop a 7-term polynomial in 3 inputs was not recovered from 61 runs (error 1e-3), without it
it was (error 1e-27).
"""

from __future__ import annotations

import contextlib
from typing import Iterator

import numpy as np
import openturns as ot
from numpy.typing import NDArray

from floatmoor.uq.basis import PolynomialBasis

__all__ = ["DROPPED_ENERGY", "lar_fit"]

#: Share of the centred outputs' sum of squares that the modes dropped by the SVD reduction may
#: hold: an RMS error of sqrt(1e-12) = 1e-6 of the outputs' spread, below any surrogate's error,
#: while the modes of round-off (~1e-32 of it) go.
DROPPED_ENERGY = 1e-12


#: OpenTURNS' key for the early stop of the LAR path, and the value that lets it run to its end.
_STOP_KEY = "LeastSquaresMetaModelSelection-MaximumErrorFactor"
_NO_STOP = 1e300


@contextlib.contextmanager
def _whole_lar_path() -> Iterator[None]:
    """Run OpenTURNS' LAR without its early stop (module docstring), restoring the setting."""
    before = ot.ResourceMap.GetAsScalar(_STOP_KEY)
    ot.ResourceMap.SetAsScalar(_STOP_KEY, _NO_STOP)
    try:
        yield
    finally:
        ot.ResourceMap.SetAsScalar(_STOP_KEY, before)


def _modes(centred: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Mode scores (n, r) and shapes (r, m) of the centred outputs, r the modes kept."""
    u, s, vt = np.linalg.svd(centred, full_matrices=False)
    energy = np.cumsum(s**2)
    if energy.size == 0 or energy[-1] == 0.0:
        return np.zeros((centred.shape[0], 0)), np.zeros((0, centred.shape[1]))
    kept = int(np.searchsorted(energy, (1.0 - DROPPED_ENERGY) * energy[-1])) + 1
    return u[:, :kept] * s[:kept], vt[:kept]


def _lar_one(basis: PolynomialBasis, factory: ot.OrthogonalProductPolynomialFactory,
             size: int, x: NDArray[np.float64],
             y: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Selected basis ranks and their coefficients for one output column y (n,)."""
    selection = ot.LeastSquaresMetaModelSelectionFactory(ot.LARS(), ot.CorrectedLeaveOneOut())
    algo = ot.FunctionalChaosAlgorithm(ot.Sample(x), ot.Sample(y[:, None]), basis.distribution,
                                       ot.FixedStrategy(factory, size),
                                       ot.LeastSquaresStrategy(selection))
    with _whole_lar_path():
        algo.run()
    result = algo.getResult()
    return (np.array(result.getIndices(), dtype=np.int64),
            np.array(result.getCoefficients(), dtype=float)[:, 0])


def _corrected_loo(design: NDArray[np.float64], y: NDArray[np.float64],
                   coefficients: NDArray[np.float64]) -> NDArray[np.float64]:
    """Leave-one-out residuals of a least-squares fit, scaled by sqrt(T(P, n)); inf where
    they are not defined (no more runs than polynomials, a run that alone fixes a
    coefficient)."""
    n, p = design.shape
    if n <= p:
        return np.full(n, np.inf)
    q, _ = np.linalg.qr(design)
    leverage = np.sum(q**2, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):  # a run of leverage 1: LOO error inf
        loo = (y - design @ coefficients) / (1.0 - leverage)
    gram = design.T @ design / n
    correction = n / (n - p) * (1.0 + np.trace(np.linalg.inv(gram)) / n)
    return np.sqrt(correction) * loo


def lar_fit(basis: PolynomialBasis, order: int, q_norm: float, x: NDArray[np.float64],
            y: NDArray[np.float64]) -> tuple[NDArray[np.int64], NDArray[np.float64],
                                             NDArray[np.float64]]:
    """LAR coefficients of outputs y (n, m) run at x (n, d), all finite.

    Returns
    -------
    multi_indices, coefficients, validation_error
        The polynomials selected for any output (the constant first), (P, d); their
        coefficients (P, m); the corrected LOO relative error (m,) (module docstring; NaN
        for an output that does not vary over the runs, inf for one that a mode without a
        LOO error reaches).
    """
    candidates = basis.multi_indices(order, q_norm)
    factory = basis.ot_factory(q_norm)
    mean = y.mean(axis=0)
    centred = y - mean
    scores, shapes = _modes(centred)
    psi = basis.design_matrix(x, candidates)
    selected = [np.zeros(1, dtype=np.int64)]
    fits = []
    residual = centred - scores @ shapes
    unvalidated = np.zeros(y.shape[1], dtype=bool)
    for k in range(scores.shape[1]):
        ranks, coefficients = _lar_one(basis, factory, len(candidates), x, scores[:, k])
        fits.append((ranks, coefficients))
        selected.append(ranks)
        loo = _corrected_loo(psi[:, ranks], scores[:, k], coefficients)
        if np.all(np.isfinite(loo)):
            residual += np.outer(loo, shapes[k])
        else:
            unvalidated |= shapes[k] != 0.0
    union = np.unique(np.concatenate(selected))
    position = {rank: i for i, rank in enumerate(union)}
    combined = np.zeros((union.size, y.shape[1]))
    combined[position[0]] += mean
    for (ranks, coefficients), shape in zip(fits, shapes):
        rows = [position[r] for r in ranks]
        combined[rows] += np.outer(coefficients, shape)
    spread = np.sum(centred**2, axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        error = np.where(spread > 0.0, np.sum(residual**2, axis=0) / spread, np.nan)
    error[unvalidated] = np.inf
    return candidates[union], combined, error
