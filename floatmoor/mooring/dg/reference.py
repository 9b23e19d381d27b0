"""Reference-element operators of the nodal discontinuous Galerkin cable (pure NumPy, built once).

The element is [-1, 1] with the p + 1 Legendre-Gauss-Lobatto (LGL) nodes; the solution is the
polynomial of degree p interpolating the nodal values, equivalent to a Legendre modal expansion
through the Vandermonde matrix V (orthonormal Legendre polynomials at the nodes). The operators
follow Hesthaven & Warburton, *Nodal Discontinuous Galerkin Methods* (2008), chapter 3:

* mass matrix M = (V V^T)^-1 (exact for degree-2p integrands, no lumping);
* differentiation D = V_r V^-1;
* surface lift LIFT = M^-1 [e_0, e_p] (the end-node columns);
* exponential modal filter F = V diag(sigma) V^-1, sigma_n = exp(-alpha ((n - n_c)/(p - n_c))^s)
  for n > n_c, 1 below (section 5.3).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre as npl
from numpy.typing import NDArray

__all__ = ["ReferenceElement", "lgl_nodes", "legendre_vandermonde", "reference_element",
           "STABLE_STEP_FACTOR"]

#: Largest stable SSP-RK3 step of the linearised scheme, dt_max = factor * h / c, for order p.
#: From the eigenvalues of the semi-discrete operator of a taut line's longitudinal waves
#: (alternating traces with the Lax-Friedrichs penalty, fixed ends, 8 elements): the largest dt
#: keeping every lambda dt inside the RK3 stability region |1 + z + z^2/2 + z^3/6| <= 1.
#: ``tests/mooring/dg/test_mooring_dg_stability.py`` recomputes them (5 significant digits). They fall like ~0.6 / (2p + 1).
STABLE_STEP_FACTOR = {1: 0.42547, 2: 0.21063, 3: 0.12383, 4: 0.080103,
                      5: 0.056071, 6: 0.041434, 7: 0.031859, 8: 0.025255}


def lgl_nodes(p: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """LGL nodes and quadrature weights on [-1, 1] for order p >= 1.

    The interior nodes are the roots of P_p'; the weights are 2 / (p (p + 1) P_p(x)^2).
    """
    if p < 1:
        raise ValueError("order p must be >= 1")
    coeffs = np.zeros(p + 1)
    coeffs[p] = 1.0
    interior = npl.legroots(npl.legder(coeffs)) if p > 1 else np.array([])
    x = np.concatenate(([-1.0], np.sort(np.real(interior)), [1.0]))
    w = 2.0 / (p * (p + 1) * npl.legval(x, coeffs) ** 2)
    return x, w


def legendre_vandermonde(x: NDArray[np.float64], p: int) -> tuple[NDArray[np.float64],
                                                                   NDArray[np.float64]]:
    """Orthonormal Legendre polynomials (and their derivatives) of degree 0..p at x."""
    V = np.zeros((x.size, p + 1))
    Vr = np.zeros((x.size, p + 1))
    for n in range(p + 1):
        c = np.zeros(n + 1)
        c[n] = np.sqrt((2 * n + 1) / 2.0)
        V[:, n] = npl.legval(x, c)
        Vr[:, n] = npl.legval(x, npl.legder(c)) if n > 0 else 0.0
    return V, Vr


@dataclass(frozen=True)
class ReferenceElement:
    """Operators of the order-p element (arrays are C-contiguous float64)."""

    order: int
    nodes: NDArray[np.float64]  #: LGL nodes on [-1, 1]
    weights: NDArray[np.float64]  #: LGL quadrature weights
    vandermonde: NDArray[np.float64]  #: V[i, n] = P_n(x_i), orthonormal Legendre
    mass: NDArray[np.float64]  #: exact mass matrix on [-1, 1]
    differentiation: NDArray[np.float64]  #: D = V_r V^-1
    lift: NDArray[np.float64]  #: (p+1, 2): M^-1 e_0 and M^-1 e_p
    filter: NDArray[np.float64]  #: modal filter matrix

    @property
    def min_spacing(self) -> float:
        """Smallest node spacing on [-1, 1]."""
        return float(np.min(np.diff(self.nodes)))


def reference_element(p: int, filter_strength: float = 36.0, filter_order: int = 8,
                      filter_cutoff: int | None = None) -> ReferenceElement:
    """Build the operators of the order-p LGL element.

    Parameters
    ----------
    p
        Polynomial order (1 to 8 in practice).
    filter_strength
        alpha of the exponential filter; 36 damps the highest mode to machine epsilon.
    filter_order
        s of the exponential filter (even); higher leaves more low modes untouched.
    filter_cutoff
        Modes n <= cutoff are not filtered (default: p // 2).
    """
    x, w = lgl_nodes(p)
    V, Vr = legendre_vandermonde(x, p)
    Vinv = np.linalg.inv(V)
    mass = np.linalg.inv(V @ V.T)
    D = Vr @ Vinv
    minv = V @ V.T
    lift = np.ascontiguousarray(minv[:, [0, p]])
    cutoff = p // 2 if filter_cutoff is None else filter_cutoff
    sigma = np.ones(p + 1)
    for n in range(cutoff + 1, p + 1):
        eta = (n - cutoff) / (p - cutoff)
        sigma[n] = np.exp(-filter_strength * eta ** filter_order)
    F = V @ np.diag(sigma) @ Vinv
    return ReferenceElement(order=p, nodes=x, weights=w, vandermonde=V, mass=mass,
                            differentiation=np.ascontiguousarray(D), lift=lift,
                            filter=np.ascontiguousarray(F))
