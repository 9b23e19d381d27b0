"""Plain NumPy reference of the DG cable right-hand side, independent of the numba kernels.

Written from docs/theory/cable.md and docs/theory/dynamic_line.md and the semi-discretisation stated in the docstring of
:mod:`floatmoor.mooring.dg._kernels` (nodal DG on Legendre-Gauss-Lobatto nodes, strong form,
Hesthaven & Warburton 2008, chapter 3), vectorised over elements and nodes, without numba and
without :mod:`floatmoor.mooring.dg.reference`:

* the reference-element operators are built from the Lagrange basis in barycentric form
  (Berrut & Trefethen 2004) instead of the Legendre Vandermonde matrix, and the mass matrix by
  Gauss-Legendre quadrature of the Lagrange products, so the kernels' operators can be
  checked against these;
* the right-hand side takes the operators as arguments, so the kernels' arithmetic can be
  checked with identical operators to roundoff.

Conventions (unstretched arc length s from the anchor, s = 0, to the fairlead, s = L; z up;
arrays of shape (K, Np, 3) for K elements of Np = p + 1 nodes):

* strong-form DG derivative of a nodal field u with face values u* (per element, jac = 2 / h):
  ``du/ds = jac (D u + M^-1 [e_p (u*_right - u_p) - e_0 (u*_left - u_0)])``;
* tangent q = du/ds of r with u* = r- (the trace from the anchor side) inside, the anchor and the
  fairlead positions at the ends; strain eps = |q| - 1;
* tension T = EA eps + c_int d(eps)/dt for eps > 0 (d(eps)/dt = t . q_t, q_t the same DG
  derivative of v with the anchor at rest and the fairlead velocity at the ends), clipped at
  0; T = 0 for eps <= 0 (bilinear: a chain cannot push). Axial force N = T q / |q|;
* momentum flux N* = N_right + (Z / 2)(v_right - v_left) inside (alternating with u*, plus
  the local Lax-Friedrichs penalty); at the
  anchor N* = N + Z (v - 0), at the fairlead N* = N + Z (v_fairlead - v). The impedance is
  Z = m_t c, with c = sqrt(EA / m) the dry longitudinal wave speed (an upper bound of every
  wave speed of the line) and m_t = m + m_at when the face is submerged (mean z of the traces
  < 0), m otherwise;
* external force per unstretched length: weight -m g e_z; below z = 0 buoyancy
  rho_w A_c g e_z and Morison drag 0.5 rho_w d sqrt(1 + eps) (C_dt |v_rt| v_rt + C_dn |v_rn| v_rn)
  on v_r = U_current - v; below the seabed z_b Coulomb friction of magnitude mu w_sub (the
  submerged weight per length) ramped in with sin(pi/2 |v_h| / max(v_c, |v_h|)) against the
  horizontal velocity v_h, and, with explicit contact, the normal spring-damper
  -k (z - z_b) - c min(v_z, 0) (damping only while moving down into the seabed);
* acceleration a = M_eff^-1 f, M_eff = m_t t t^T + m_n (I - t t^T), t = q / |q|, with the
  Morison added masses m_n, m_t only below z = 0 (a = f / m_n where |q| = 0).

Units SI. The parameters are given as keyword arguments, not in the kernels' packed layout.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre as npl
from numpy.typing import NDArray

Array = NDArray[np.float64]


# -- reference element, built from the Lagrange basis -------------------------------------------
def lgl_nodes(p: int) -> tuple[Array, Array]:
    """LGL nodes (roots of (1 - x^2) P_p'(x)) by Newton from Chebyshev-Gauss-Lobatto guesses, and
    the weights 2 / (p (p + 1) P_p(x)^2)."""
    x = -np.cos(np.pi * np.arange(p + 1) / p)
    cp = np.zeros(p + 1)
    cp[p] = 1.0
    d1 = npl.legder(cp)
    d2 = npl.legder(cp, 2)
    inner = x[1:-1].copy()
    for _ in range(100):
        step = npl.legval(inner, d1) / npl.legval(inner, d2)
        inner -= step
        if np.max(np.abs(step), initial=0.0) < 1e-16:
            break
    x[1:-1] = inner
    w = 2.0 / (p * (p + 1) * npl.legval(x, cp) ** 2)
    return x, w


def barycentric_weights(x: Array) -> Array:
    diff = x[:, None] - x[None, :]
    np.fill_diagonal(diff, 1.0)
    return 1.0 / np.prod(diff, axis=1)


def lagrange_matrix(x: Array, y: Array) -> Array:
    """L[a, j] = l_j(y_a), the Lagrange basis on nodes x evaluated at y (barycentric form of
    the second kind; rows of points that coincide with a node are unit vectors)."""
    lam = barycentric_weights(x)
    diff = y[:, None] - x[None, :]
    hit = diff == 0.0
    c = lam[None, :] / np.where(hit, 1.0, diff)
    out = c / np.sum(c, axis=1, keepdims=True)
    rows = hit.any(axis=1)
    out[rows] = hit[rows].astype(float)
    return out


def differentiation_matrix(x: Array) -> Array:
    """D[i, j] = l_j'(x_i): the classical barycentric formula, diagonal by negative sum."""
    lam = barycentric_weights(x)
    diff = x[:, None] - x[None, :]
    np.fill_diagonal(diff, 1.0)
    D = (lam[None, :] / lam[:, None]) / diff
    np.fill_diagonal(D, 0.0)
    np.fill_diagonal(D, -np.sum(D, axis=1))
    return D


def mass_matrix(x: Array) -> Array:
    """M[i, j] = int_{-1}^{1} l_i l_j, by Gauss-Legendre quadrature exact for degree 2p + 2."""
    g, wg = npl.leggauss(x.size + 2)
    Lg = lagrange_matrix(x, g)
    return Lg.T @ (wg[:, None] * Lg)


@dataclass(frozen=True)
class Operators:
    """Reference-element operators on [-1, 1]."""

    nodes: Array
    weights: Array
    D: Array  #: differentiation
    M: Array  #: exact mass matrix
    LIFT: Array  #: (Np, 2) = M^-1 [e_0, e_p]


def operators(p: int) -> Operators:
    x, w = lgl_nodes(p)
    M = mass_matrix(x)
    E = np.zeros((p + 1, 2))
    E[0, 0] = 1.0
    E[p, 1] = 1.0
    return Operators(x, w, differentiation_matrix(x), M, np.linalg.solve(M, E))


# -- semi-discrete operator ---------------------------------------------------------------------
def dg_derivative(u: Array, left: Array, right: Array, D: Array, LIFT: Array, h: float) -> Array:
    """Strong-form DG derivative of u (K, Np, 3) with anchor-side interior traces and the given
    end values."""
    faces = np.empty((u.shape[0] + 1, 3))
    faces[0], faces[-1] = left, right
    faces[1:-1] = u[:-1, -1]
    jump_left = faces[:-1] - u[:, 0]  # u* - u at the left face of each element
    jump_right = faces[1:] - u[:, -1]
    du = np.einsum("ij,kjc->kic", D, u)
    du += LIFT[None, :, 1, None] * jump_right[:, None, :]
    du -= LIFT[None, :, 0, None] * jump_left[:, None, :]
    return (2.0 / h) * du


@dataclass(frozen=True)
class Fields:
    q: Array  #: tangent dr/ds (K, Np, 3)
    N: Array  #: axial force at the nodes (K, Np, 3)
    Nstar: Array  #: face fluxes (K + 1, 3)
    slack: Array  #: 1.0 for elements with a node at eps <= 0


def tension_field(r: Array, v: Array, anchor: Array, fpos: Array, fvel: Array, *, D: Array,
                  LIFT: Array, h: float, m: float, EA: float, c_int: float = 0.0,
                  m_at: float = 0.0, avel: Array | None = None,
                  flux_velocities: tuple[Array, Array] | None = None) -> Fields:
    """Tangent, axial force and Lax-Friedrichs fluxes; ``avel`` the start end's velocity
    (default at rest), ``flux_velocities`` (start, end) the end velocities of the end fluxes
    when they differ from those of the strain rate (a section's end at a free point)."""
    avel = np.zeros(3) if avel is None else np.asarray(avel, dtype=float)
    va, vf = (avel, fvel) if flux_velocities is None else flux_velocities
    q = dg_derivative(r, anchor, fpos, D, LIFT, h)
    ql = np.linalg.norm(q, axis=-1)
    eps = ql - 1.0
    taut = eps > 0.0
    T = np.where(taut, EA * eps, 0.0)
    if c_int > 0.0:
        qt = dg_derivative(v, avel, fvel, D, LIFT, h)
        with np.errstate(invalid="ignore", divide="ignore"):
            eps_t = np.sum(q * qt, axis=-1) / ql
        T = np.where(taut, np.maximum(T + c_int * np.where(taut, eps_t, 0.0), 0.0), 0.0)
    with np.errstate(invalid="ignore", divide="ignore"):
        N = np.where(ql[..., None] > 0.0, (T / np.where(ql > 0.0, ql, 1.0))[..., None] * q, 0.0)
    slack = np.any(~taut, axis=1).astype(float)

    c = math.sqrt(EA / m)
    z_face = np.concatenate(([r[0, 0, 2]], 0.5 * (r[:-1, -1, 2] + r[1:, 0, 2]), [r[-1, -1, 2]]))
    Z = (m + np.where(z_face < 0.0, m_at, 0.0)) * c
    Nstar = np.empty((r.shape[0] + 1, 3))
    Nstar[0] = N[0, 0] + Z[0] * (v[0, 0] - va)
    Nstar[-1] = N[-1, -1] + Z[-1] * (vf - v[-1, -1])
    Nstar[1:-1] = N[1:, 0] + 0.5 * Z[1:-1, None] * (v[1:, 0] - v[:-1, -1])
    return Fields(q, N, Nstar, slack)


def rhs(r: Array, v: Array, anchor: Array, fpos: Array, fvel: Array, *, D: Array, LIFT: Array,
        h: float, m: float, EA: float, d: float, A_c: float, rho_w: float, g: float,
        cdn: float = 0.0, cdt: float = 0.0, m_an: float = 0.0, m_at: float = 0.0,
        c_int: float = 0.0, w_sub: float = 0.0, z_b: float = -1e300, k_b: float = 0.0,
        c_b: float = 0.0, mu: float = 0.0, v_c: float = 0.01,
        current: tuple[float, float, float] = (0.0, 0.0, 0.0),
        explicit_contact: bool = False, relax: float = 0.0, avel: Array | None = None,
        flux_velocities: tuple[Array, Array] | None = None) -> tuple[Array, Fields]:
    """Acceleration dv/dt of every node, and the fields it came from (``relax``: the settling
    damping rate gamma, dv/dt -= gamma v; ``avel``, ``flux_velocities``: as
    :func:`tension_field`)."""
    fl = tension_field(r, v, anchor, fpos, fvel, D=D, LIFT=LIFT, h=h, m=m, EA=EA, c_int=c_int,
                       m_at=m_at, avel=avel, flux_velocities=flux_velocities)
    q, N, Nstar = fl.q, fl.N, fl.Nstar
    # divergence of N with the face fluxes
    jump_left = Nstar[:-1] - N[:, 0]
    jump_right = Nstar[1:] - N[:, -1]
    f = np.einsum("ij,kjc->kic", D, N)
    f += LIFT[None, :, 1, None] * jump_right[:, None, :]
    f -= LIFT[None, :, 0, None] * jump_left[:, None, :]
    f *= 2.0 / h

    ql = np.linalg.norm(q, axis=-1)
    t = np.where(ql[..., None] > 0.0, q / np.where(ql > 0.0, ql, 1.0)[..., None], 0.0)
    z = r[..., 2]
    wet = z < 0.0

    f[..., 2] -= m * g
    f[..., 2] += np.where(wet, rho_w * A_c * g, 0.0)

    vr = np.asarray(current, dtype=float) - v
    vrt = np.sum(vr * t, axis=-1)
    vrn = vr - vrt[..., None] * t
    vrn_abs = np.linalg.norm(vrn, axis=-1)
    drag = (0.5 * rho_w * d * np.sqrt(ql))[..., None] * (
        cdt * (np.abs(vrt) * vrt)[..., None] * t + cdn * vrn_abs[..., None] * vrn)
    f += np.where(wet[..., None], drag, 0.0)

    bed = z < z_b
    vh = v[..., :2]
    speed = np.linalg.norm(vh, axis=-1)
    moving = bed & (speed > 0.0)
    safe = np.where(moving, speed, 1.0)
    mag = mu * w_sub * np.sin(0.5 * np.pi * safe / np.maximum(v_c, safe))
    f[..., :2] -= np.where(moving[..., None], (mag / safe)[..., None] * vh, 0.0)
    if explicit_contact:
        f[..., 2] += np.where(bed, -k_b * (z - z_b) - c_b * np.minimum(v[..., 2], 0.0), 0.0)

    mn = m + np.where(wet, m_an, 0.0)
    mt = m + np.where(wet, m_at, 0.0)
    ft = np.sum(f * t, axis=-1)
    a = (f - ft[..., None] * t) / mn[..., None] + (ft / mt)[..., None] * t - relax * v
    return a, fl


def damping_acceleration(v: Array, r: Array, anchor: Array, fpos: Array, fvel: Array, *,
                         D: Array, LIFT: Array, h: float, m: float, c_int: float,
                         m_an: float = 0.0, m_at: float = 0.0,
                         avel: Array | None = None) -> Array:
    """The acceleration of the Kelvin-Voigt term alone at velocities v, linear in v for the
    geometry r: damping tension s = c_int t . q_t on taut nodes (eps > 0, not clipped),
    force d(s t)/ds with traces from the fairlead side (N* = N of the fairlead-side node
    inside, the node's own at both ends: the explicit fluxes without the elastic part and
    the penalty), divided by the Morison-augmented mass; ``avel`` the start end's velocity
    (default at rest)."""
    q = dg_derivative(r, anchor, fpos, D, LIFT, h)
    ql = np.linalg.norm(q, axis=-1)
    t = np.where(ql[..., None] > 0.0, q / np.where(ql > 0.0, ql, 1.0)[..., None], 0.0)
    qt = dg_derivative(v, np.zeros(3) if avel is None else avel, fvel, D, LIFT, h)
    s = np.where(ql > 1.0, c_int * np.sum(t * qt, axis=-1), 0.0)
    N = s[..., None] * t
    Nstar = np.empty((r.shape[0] + 1, 3))
    Nstar[0], Nstar[-1], Nstar[1:-1] = N[0, 0], N[-1, -1], N[1:, 0]
    f = np.einsum("ij,kjc->kic", D, N)
    f += LIFT[None, :, 1, None] * (Nstar[1:] - N[:, -1])[:, None, :]
    f -= LIFT[None, :, 0, None] * (Nstar[:-1] - N[:, 0])[:, None, :]
    f *= 2.0 / h
    wet = r[..., 2] < 0.0
    mn = m + np.where(wet, m_an, 0.0)
    mt = m + np.where(wet, m_at, 0.0)
    ft = np.sum(f * t, axis=-1)
    return (f - ft[..., None] * t) / mn[..., None] + (ft / mt)[..., None] * t


def implicit_damping_step(v: Array, r: Array, anchor: Array, fpos: Array, fvel: Array,
                          dt: float, **params: float) -> Array:
    """Backward Euler of the Kelvin-Voigt term, v1 = v + dt a_d(v1), with the geometry r fixed:
    a dense (3 K Np)^2 solve of the affine map, built column by column."""
    shape = v.shape
    n = v.size

    def a(x: Array, vel: Array) -> Array:
        return damping_acceleration(x.reshape(shape), r, anchor, fpos, vel, **params).ravel()

    b = a(np.zeros(n), fvel)  # the fairlead velocity's part
    A = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = 1.0
        A[:, j] = a(e, np.zeros(3))
    return np.linalg.solve(np.eye(n) - dt * A, v.ravel() + dt * b).reshape(shape)


def _morison_inverse(f: Array, r: Array, t: Array, m: float, m_an: float, m_at: float) -> Array:
    """M_eff^-1 f at the nodes (tangents t, Morison masses below z = 0)."""
    wet = r[..., 2] < 0.0
    mn = m + np.where(wet, m_an, 0.0)
    mt = m + np.where(wet, m_at, 0.0)
    ft = np.sum(f * t, axis=-1)
    return (f - ft[..., None] * t) / mn[..., None] + (ft / mt)[..., None] * t


def system_damping_step(sections: list[dict], x: Array, velocities: Array, free: Array,
                        point_mass: Array, dt: float) -> tuple[list[Array], Array]:
    """Backward Euler of the Kelvin-Voigt terms of sections joined at points, with the free
    points' velocities among the unknowns (the step after SSP-RK3 of
    ``_system_kernels._damping_phase``), as one dense solve of the affine map, built column by
    column, without the kernels' cached responses or banded factors.

    The unknowns are every section's node velocities v and every free point's velocity u:

    * v = v* + dt a_d(v; u_start, u_end) + dt M_eff^-1 lift(Z (u - u*)) for each section:
      the damping acceleration (:func:`damping_acceleration`, the end values of its strain
      rate the end points' velocities) and, at a free end, the change of the Lax-Friedrichs
      end flux N* by Z (u - u*) (sign of the face: -Z du at the start, + Z du at the end)
      lifted into the end element as in the divergence;
    * (M_eff + dt sum_j Z_j)(u - u*) = dt sum_j (+-) t s_j for each free point, s_j the damping
      tension c_int t . q_t of the section's end node at the point (taut nodes), + at a
      section's start, - at its end.

    ``sections``: dicts of r, v (K, Np, 3), start, end (point indices), D, LIFT, h, m, EA,
    c_int, m_an, m_at; ``x``, ``velocities`` (points, 3): positions and velocities of every
    point (free points: u*); ``free`` (points,) bool; ``point_mass``: M_eff of the points.
    Returns the sections' v and the points' velocities after the step.
    """
    free_idx = np.flatnonzero(free)
    sizes = [sec["v"].size for sec in sections]
    n = sum(sizes) + 3 * free_idx.size
    slot = {int(p): sum(sizes) + 3 * i for i, p in enumerate(free_idx)}
    geo = []
    for sec in sections:
        q = dg_derivative(sec["r"], x[sec["start"]], x[sec["end"]], sec["D"], sec["LIFT"],
                          sec["h"])
        ql = np.linalg.norm(q, axis=-1)
        t = q / ql[..., None]
        c = math.sqrt(sec["EA"] / sec["m"])
        Z = [(sec["m"] + (sec["m_at"] if sec["r"][i][2] < 0.0 else 0.0)) * c
             for i in ((0, 0), (-1, -1))]
        geo.append((t, ql, Z))

    def unpack(X: Array) -> tuple[list[Array], Array]:
        vs, o = [], 0
        for sec, size in zip(sections, sizes):
            vs.append(X[o:o + size].reshape(sec["v"].shape))
            o += size
        u = velocities.copy()
        for p, o in slot.items():
            u[p] = X[o:o + 3]
        return vs, u

    def residual(X: Array) -> Array:
        vs, u = unpack(X)
        out = np.zeros(n)
        du = u - velocities
        force = np.zeros_like(u)
        o = 0
        for sec, v, (t, ql, Z), size in zip(sections, vs, geo, sizes):
            a, b = sec["start"], sec["end"]
            acc = damping_acceleration(v, sec["r"], x[a], x[b], u[b], D=sec["D"],
                                       LIFT=sec["LIFT"], h=sec["h"], m=sec["m"],
                                       c_int=sec["c_int"], m_an=sec["m_an"], m_at=sec["m_at"],
                                       avel=u[a])
            flux = np.zeros_like(v)
            jac = 2.0 / sec["h"]
            if free[a]:
                flux[0] += jac * sec["LIFT"][:, 0, None] * Z[0] * du[a]
            if free[b]:
                flux[-1] += jac * sec["LIFT"][:, 1, None] * Z[1] * du[b]
            lift = _morison_inverse(flux, sec["r"], t, sec["m"], sec["m_an"], sec["m_at"])
            out[o:o + size] = (v - sec["v"] - dt * acc - dt * lift).ravel()
            o += size
            qt = dg_derivative(v, u[a], u[b], sec["D"], sec["LIFT"], sec["h"])
            s = np.where(ql > 1.0, sec["c_int"] * np.sum(t * qt, axis=-1), 0.0)
            force[a] += t[0, 0] * s[0, 0] - Z[0] * du[a]
            force[b] += -t[-1, -1] * s[-1, -1] - Z[1] * du[b]
        for p, o in slot.items():
            out[o:o + 3] = point_mass[p] * du[p] - dt * force[p]
        return out

    b0 = residual(np.zeros(n))
    A = np.empty((n, n))
    for j in range(n):
        e = np.zeros(n)
        e[j] = 1.0
        A[:, j] = residual(e) - b0
    return unpack(np.linalg.solve(A, -b0))


def hermite(t0: float, t1: float, p0: Array, v0: Array, p1: Array, v1: Array,
            t: float) -> tuple[Array, Array]:
    """Cubic Hermite interpolant of (p, v) on [t0, t1]: the cubic matching p and dp/dt at
    both ends, as a polynomial in t solved for directly (4 x 4 system per component)."""
    A = np.array([[1.0, t0, t0**2, t0**3], [0.0, 1.0, 2 * t0, 3 * t0**2],
                  [1.0, t1, t1**2, t1**3], [0.0, 1.0, 2 * t1, 3 * t1**2]])
    coef = np.linalg.solve(A, np.vstack([p0, v0, p1, v1]))
    pos = np.array([1.0, t, t * t, t**3]) @ coef
    vel = np.array([0.0, 1.0, 2 * t, 3 * t * t]) @ coef
    return pos, vel
