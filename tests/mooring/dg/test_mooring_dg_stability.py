"""The DG time-step limits: STABLE_STEP_FACTOR recomputed from the spectrum of the linearised
scheme, and confirmed on the compiled kernels (stable just below, unstable just above)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.schema import DynamicSettings
from floatmoor.errors import SolverError
from floatmoor.mooring.dg.line import CableProperties, DynamicLine
from floatmoor.mooring.dg.reference import STABLE_STEP_FACTOR, reference_element
from floatmoor.mooring.dg.stability import linear_operator, stable_step_factor

#: The table is rounded to 5 significant digits.
FACTOR_RTOL = 1e-4


def _linear_operator(p: int, K: int = 8) -> np.ndarray:
    """Semi-discrete operator of longitudinal waves on a taut line (h = c = m = 1), built in
    plain NumPy from the scheme's definition (alternating traces: positions from the anchor
    side, axial force from the fairlead side, plus the Lax-Friedrichs penalty; fixed ends)."""
    e = reference_element(p)
    Np, n = p + 1, K * (p + 1)
    D, LIFT, jac = e.differentiation, e.lift, 2.0

    def strong(u, faces):
        return jac * (u @ D.T - np.outer(faces[:-1] - u[:, 0], LIFT[:, 0])
                      + np.outer(faces[1:] - u[:, -1], LIFT[:, 1]))

    def rhs(r, v):
        r, v = r.reshape(K, Np), v.reshape(K, Np)
        faces = np.zeros(K + 1)
        faces[1:K] = r[:-1, -1]
        N = strong(r, faces)
        flux = np.zeros(K + 1)
        flux[0] = N[0, 0] + v[0, 0]
        flux[K] = N[-1, -1] - v[-1, -1]
        flux[1:K] = N[1:, 0] + 0.5 * (v[1:, 0] - v[:-1, -1])
        return strong(N, flux).reshape(-1)

    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    for j in range(n):
        x = np.zeros(n)
        x[j] = 1.0
        A[n:, j] = rhs(x, np.zeros(n))
        A[n:, n + j] = rhs(np.zeros(n), x)
    return A


def _rk3_limit(eigenvalues: np.ndarray) -> float:
    def stable(dt):
        z = eigenvalues * dt
        return np.all(np.abs(1 + z + z ** 2 / 2 + z ** 3 / 6) <= 1 + 1e-10)

    lo, hi = 0.0, 10.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
    return lo


@pytest.mark.parametrize("p", sorted(STABLE_STEP_FACTOR))
def test_stable_step_factor_from_the_spectrum(p):
    eig = np.linalg.eigvals(_linear_operator(p))
    assert eig.real.max() < 1e-12  # the semi-discrete scheme itself is stable (LF dissipates)
    assert STABLE_STEP_FACTOR[p] == pytest.approx(_rk3_limit(eig), rel=FACTOR_RTOL)
    # the package's operator (which also carries damping) is this one without damping
    np.testing.assert_allclose(linear_operator(p), _linear_operator(p), atol=1e-12)
    assert stable_step_factor(p) == pytest.approx(STABLE_STEP_FACTOR[p], rel=FACTOR_RTOL)


def test_internal_damping_tightens_the_limit():
    """Kelvin-Voigt damping is diffusive: the limit falls as the damping number grows."""
    factors = [stable_step_factor(5, nu) for nu in (0.0, 0.01, 0.1, 1.0)]
    print(f"p = 5, damping numbers 0, 0.01, 0.1, 1: {factors}")
    assert all(a > b for a, b in zip(factors, factors[1:]))
    assert factors[-1] < 0.1 * factors[0]


def _taut_line(p: int, cfl: float, internal_damping: float = 0.0,
               method: str = "explicit") -> DynamicLine:
    props = CableProperties(length=10.0, mass_per_length=1.0, axial_stiffness=1.0e4,
                            diameter=0.01, material_density=7800.0, water_density=0.0,
                            gravity=0.0, internal_damping=internal_damping)
    settings = DynamicSettings(elements=6, order=p, cfl=cfl, max_time_step=None,
                               slack_filter=False, seabed_contact="implicit",
                               internal_damping=method)
    line = DynamicLine(props, settings, np.zeros(3), np.array([10.1, 0.0, 0.0]), name="x")
    rng = np.random.default_rng(p)
    line.v[..., 0] = 1e-3 * rng.standard_normal(line.v.shape[:2])  # excite every mode
    return line


@pytest.mark.parametrize("p, damping, method", [
    (2, 0.0, "explicit"), (5, 0.0, "explicit"), (5, 100.0, "explicit"),
    (5, 100.0, "implicit"), (5, 1.0e4, "implicit")])
def test_kernel_is_stable_below_and_unstable_above_the_limit(p, damping, method):
    """The limits match the compiled scheme, with and without internal damping: 0.95 of the
    limit stays bounded for 400 steps, 1.3 of it grows (or trips the instability check).
    With the damping implicit (backward Euler), the limit is the undamped one whatever the
    damping: damping numbers 0.1 and 10 (where the explicit limit would be 20 times lower)."""
    results = {}
    for cfl in (0.95, 1.3):
        line = _taut_line(p, cfl, damping, method)
        if method == "implicit":
            assert line.time_step == pytest.approx(_taut_line(p, cfl).time_step, rel=1e-14)
        initial = float(np.abs(line.v).max())
        n = 400
        time = np.arange(n + 1) * line.time_step
        fair = np.tile([10.1, 0.0, 0.0], (n + 1, 1))
        out = [np.zeros((n + 1, 3)), np.zeros((n + 1, 3)), np.zeros(n + 1), np.zeros(n + 1)]
        try:
            line.solve_path(time, fair, np.zeros_like(fair), *out)
            results[cfl] = float(np.abs(line.v).max()) / initial
        except SolverError as err:  # the instability check stopped it, and says where
            message = str(err)
            assert "line 'x' (dynamic)" in message and "t = " in message
            assert "arc length s = " in message and ("velocity" in message or "moves" in message
                                                     or "strain" in message or "finite" in message)
            assert 0 < line.failed_index <= n
            assert np.all(np.isfinite(out[0][:line.failed_index]))
            results[cfl] = math.inf
    print(f"p = {p}, damping {damping} ({method}): max |v| after 400 steps / initial "
          f"{results}")
    assert results[0.95] < 1.0  # bounded (the LF penalty and damping only dissipate)
    assert results[1.3] > 10.0  # growing
