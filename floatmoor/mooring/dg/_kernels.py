"""Numba kernels of the discontinuous Galerkin (DG) cable (docs/theory/cable.md and docs/theory/dynamic_line.md).

Semi-discretisation (nodal DG on LGL nodes, strong form, Hesthaven & Warburton 2008):

* unknowns per node: position r and velocity v (the cable equation as a first-order system);
* tangent q = dr/ds from r with the trace r* taken from the anchor side of each interface and
  the prescribed anchor / fairlead positions at the ends (the local-DG auxiliary variable of
  MooDy, with alternating fluxes: central traces lose an order at odd p);
* axial force N = T(eps) q / |q|, eps = |q| - 1, T = EA eps (+ c_int d(eps)/dt) for eps > 0 and
  0 in compression (bilinear, docs/theory/cable.md);
* momentum flux: N from the fairlead side (alternating with r*, which makes the interface terms
  conserve energy, Chou, Shu & Xing 2014) plus the local Lax-Friedrichs penalty:
  N* = N+ + (Z / 2) (v+ - v-), with the axial impedance
  Z = m_t c (m_t the tangential mass, c = sqrt(EA / m) the fastest, longitudinal wave speed,
  which bounds the local one); at the ends the exterior
  velocity mirrors the prescribed one, N* = N + Z (v - v_bc) at the anchor and
  N* = N + Z (v_bc - v) at the fairlead;
* (M_eff) dv/dt = dN/ds + f, with dN/ds the DG divergence, f the weight and buoyancy (buoyancy,
  drag and added mass only below z = 0), Morison drag on the velocity relative to a steady
  current, seabed friction, and M_eff = (m + m_at) t t^T + (m + m_an)(I - t t^T) the mass with
  Morison added mass (tangential, normal);
* seabed normal spring-damper (gpc paper eq. 7): explicitly in the right-hand side, or (default)
  implicitly: after each SSP-RK3 step, nodes below the seabed take a backward-Euler step of
  the spring-damper, z1 = z* + dt (v1 - v*), v1 = v* - dt (k (z1 - z_b) + c min(v1, 0)) / m_z,
  which is unconditionally stable, so the axial-wave CFL condition sets the time step;
* slack control: the bending-free cable equation is ill-posed in compression, so elements with
  a node in compression (eps < 0, flagged in the last stage) get an exponential modal filter on
  their velocities after each step (reference.py): a contraction of the kinetic energy, so it
  only dissipates; taut elements are never filtered, so smooth solutions keep their order.

Time integration: SSP-RK3 (Shu & Osher 1988) with stage-consistent boundary data. The fairlead
position and velocity inside an interval come from the cubic Hermite interpolant of their
values at its ends.

Parameters travel in one float64 array ``prm`` indexed by the ``P_*`` constants.

Size: the numba kernels of one DG cable, which share the private operators (tension
field, acceleration, implicit damping) that the system kernels also reuse; the docstring
states the scheme they implement.
"""

from __future__ import annotations

import math

import numpy as np

from floatmoor._numba import jit
from floatmoor.mooring.dg._banded_kernels import band_factor, band_solve
from floatmoor.mooring.dg._friction_kernels import return_map, stick_force

__all__ = ["N_PRM", "dg_rhs", "dg_tension_field", "dg_run_path", "hermite"]

# -- parameter layout -----------------------------------------------------------------------
P_M = 0  #: mass per unstretched length [kg/m]
P_EA = 1  #: axial stiffness [N]
P_D = 2  #: drag diameter [m]
P_AC = 3  #: material area m / rho_c [m^2]
P_RHO_W = 4  #: water density [kg/m^3]
P_G = 5  #: gravity [m/s^2]
P_CDN = 6
P_CDT = 7
P_MAN = 8  #: normal added mass per length when submerged, C_a rho_w A_c [kg/m]
P_MAT = 9  #: tangential added mass per length when submerged [kg/m]
P_CINT = 10  #: internal damping coefficient [N s]
P_WSUB = 11  #: submerged weight per length, for seabed friction [N/m]
P_ZB = 12  #: seabed elevation [m]
P_KB = 13  #: seabed stiffness per length per penetration [N/m^2]
P_CB = 14  #: seabed damping coefficient per length [N s/m^2]
P_MU = 15  #: seabed friction coefficient
P_VC = 16  #: slip speed [m/s]
P_UX = 17  #: current velocity [m/s], 3 entries
P_H = 20  #: element length [m]
P_IMPLICIT_CONTACT = 21  #: 1.0 for the implicit seabed spring-damper
P_FILTER = 22  #: 1.0 to filter slack elements
P_C = 23  #: longitudinal wave speed sqrt(EA / m) [m/s]
P_RELAX = 24  #: relaxation damping rate gamma [1/s]: dv/dt gets -gamma v (settling only; 0)
P_IMPLICIT_DAMPING = 25  #: 1.0: the Kelvin-Voigt term takes a backward-Euler step after each step
P_DAMPING_TOL = 26  #: tangent turn [rad] that makes the factored damping system stale
#: stick stiffness of the stick-spring friction per length [N/m^2]; 0: the regularised
#: Coulomb law (docs/theory/cable.md#seabed-friction)
P_KS = 27
N_PRM = 28

# -- statuses of dg_run_path ----------------------------------------------------------------
DG_OK = 0
DG_NOT_FINITE = 1
DG_VELOCITY = 2  #: a node moves faster than the longitudinal wave speed
DG_STRAIN = 3  #: strain beyond MAX_STRAIN

#: A cable stretched to twice its length has failed long before; such a strain means the
#: solution has gone unstable, not that the line is loaded.
MAX_STRAIN = 1.0

_ZERO3 = np.zeros(3)  # the anchor's velocity (read-only constant inside the kernels)

#: Default largest turn of a node's tangent [rad] before the factored internal-damping system
#: is rebuilt (``P_DAMPING_TOL``, :func:`_damping_system`). The damping tension's error is then
#: below this fraction of c_int |dv/ds| (1e-3 of the transverse velocity gradient).
DAMPING_TANGENT_TOL = 1e-3


@jit
def hermite(t0: float, t1: float, p0: np.ndarray, v0: np.ndarray, p1: np.ndarray,
            v1: np.ndarray, t: float, pos: np.ndarray, vel: np.ndarray) -> None:
    """Cubic Hermite interpolation of position and its derivative on [t0, t1]."""
    dt = t1 - t0
    x = (t - t0) / dt if dt > 0.0 else 1.0
    x2 = x * x
    x3 = x2 * x
    h00 = 2.0 * x3 - 3.0 * x2 + 1.0
    h10 = x3 - 2.0 * x2 + x
    h01 = -2.0 * x3 + 3.0 * x2
    h11 = x3 - x2
    d00 = (6.0 * x2 - 6.0 * x) / dt if dt > 0.0 else 0.0
    d10 = 3.0 * x2 - 4.0 * x + 1.0
    d01 = -d00
    d11 = 3.0 * x2 - 2.0 * x
    for c in range(3):
        pos[c] = h00 * p0[c] + h10 * dt * v0[c] + h01 * p1[c] + h11 * dt * v1[c]
        vel[c] = d00 * p0[c] + d10 * v0[c] + d01 * p1[c] + d11 * v1[c]


@jit
def _hermite_derivatives(t0: float, t1: float, p0: np.ndarray, v0: np.ndarray, p1: np.ndarray,
                         v1: np.ndarray, t: float, out: np.ndarray) -> None:
    """Position and its first three time derivatives of the cubic Hermite curve at t;
    ``out`` is (4, 3)."""
    dt = t1 - t0
    x = (t - t0) / dt
    x2 = x * x
    basis = (
        (2.0 * x2 * x - 3.0 * x2 + 1.0, dt * (x2 * x - 2.0 * x2 + x), -2.0 * x2 * x + 3.0 * x2,
         dt * (x2 * x - x2)),
        ((6.0 * x2 - 6.0 * x) / dt, 3.0 * x2 - 4.0 * x + 1.0, (-6.0 * x2 + 6.0 * x) / dt,
         3.0 * x2 - 2.0 * x),
        ((12.0 * x - 6.0) / (dt * dt), (6.0 * x - 4.0) / dt, (-12.0 * x + 6.0) / (dt * dt),
         (6.0 * x - 2.0) / dt),
        (12.0 / (dt * dt * dt), 6.0 / (dt * dt), -12.0 / (dt * dt * dt), 6.0 / (dt * dt)),
    )
    for d in range(4):  # rows: the basis of p0, v0, p1, v1 and its time derivatives
        b = basis[d]
        for c in range(3):
            out[d, c] = b[0] * p0[c] + b[1] * v0[c] + b[2] * p1[c] + b[3] * v1[c]


@jit
def _strong_derivative(u: np.ndarray, faces: np.ndarray, D: np.ndarray, LIFT: np.ndarray,
                       jac: float, out: np.ndarray) -> None:
    """Strong-form DG derivative of nodal field u (K, Np, 3) given its face values (K + 1, 3):
    du/ds = jac (D u + M^-1 [e_p (u*_right - u_p) - e_0 (u*_left - u_0)])."""
    K, Np = u.shape[0], u.shape[1]
    # The three components' sums run side by side (each in its own order, so the same
    # numbers): three independent chains of additions instead of one, which is what bounds
    # this loop at small Np (docs/validation/performance.md#line-models).
    for k in range(K):
        jlx = faces[k, 0] - u[k, 0, 0]
        jly = faces[k, 1] - u[k, 0, 1]
        jlz = faces[k, 2] - u[k, 0, 2]
        jrx = faces[k + 1, 0] - u[k, Np - 1, 0]
        jry = faces[k + 1, 1] - u[k, Np - 1, 1]
        jrz = faces[k + 1, 2] - u[k, Np - 1, 2]
        for i in range(Np):
            out[k, i, 0], out[k, i, 1], out[k, i, 2] = _node_derivative(
                u, k, i, D, LIFT, jac, jlx, jly, jlz, jrx, jry, jrz)


@jit(inline="always")
def _node_derivative(u, k, i, D, LIFT, jac, jlx, jly, jlz, jrx, jry, jrz):
    """(x, y, z) of :func:`_strong_derivative` at node i of element k, given the element's
    jumps at its left (``jl*``) and right (``jr*``) faces: one place for the operations whose
    order the end forces of ``_batch_kernels`` repeat to the last bit."""
    Np = u.shape[1]
    ax, ay, az = 0.0, 0.0, 0.0
    for j in range(Np):
        d = D[i, j]
        ax += d * u[k, j, 0]
        ay += d * u[k, j, 1]
        az += d * u[k, j, 2]
    l0, l1 = LIFT[i, 0], LIFT[i, 1]
    return (jac * (ax - l0 * jlx + l1 * jrx), jac * (ay - l0 * jly + l1 * jry),
            jac * (az - l0 * jlz + l1 * jrz))


@jit
def _gradient(u: np.ndarray, left: np.ndarray, right: np.ndarray, D: np.ndarray,
              LIFT: np.ndarray, jac: float, faces: np.ndarray, out: np.ndarray) -> None:
    """DG derivative d/ds of nodal field u (K, Np, 3) with interior traces from the anchor
    side (alternating flux) and the given end values (strong form)."""
    K, Np = u.shape[0], u.shape[1]
    for c in range(3):
        faces[0, c] = left[c]
        faces[K, c] = right[c]
    for k in range(1, K):
        for c in range(3):
            faces[k, c] = u[k - 1, Np - 1, c]  # alternating flux: the trace from the anchor side
    _strong_derivative(u, faces, D, LIFT, jac, out)


@jit
def dg_tension_field(r: np.ndarray, v: np.ndarray, anchor: np.ndarray, fpos: np.ndarray,
                     fvel: np.ndarray, prm: np.ndarray, D: np.ndarray, LIFT: np.ndarray,
                     q: np.ndarray, qt: np.ndarray, N: np.ndarray, Nstar: np.ndarray,
                     faces: np.ndarray, slack: np.ndarray) -> None:
    """Tangent q, axial force N at the nodes (with the internal damping) and the
    Lax-Friedrichs face fluxes N*.

    ``slack[k]`` is set to 1.0 when element k has a node in compression.
    """
    _tension_field(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                   slack, prm[P_CINT])


@jit
def _tension_field(r, v, anchor, avel, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
                   cint):
    """:func:`dg_tension_field` with the start end moving at ``avel`` (the anchor's velocity,
    zero for a fixed anchor: then bit-identical, v - 0.0 == v) and the internal damping
    coefficient ``cint`` [N s]."""
    K, Np = r.shape[0], r.shape[1]
    jac = 2.0 / prm[P_H]
    EA = prm[P_EA]
    _gradient(r, anchor, fpos, D, LIFT, jac, faces, q)
    if cint > 0.0:
        _gradient(v, avel, fvel, D, LIFT, jac, faces, qt)
    for k in range(K):
        slack[k] = 0.0
        for i in range(Np):
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            eps = ql - 1.0
            T = 0.0
            if eps > 0.0:
                T = EA * eps
                if cint > 0.0:
                    deps = (q[k, i, 0] * qt[k, i, 0] + q[k, i, 1] * qt[k, i, 1]
                            + q[k, i, 2] * qt[k, i, 2]) / ql
                    T += cint * deps
                    if T < 0.0:
                        T = 0.0
            else:
                slack[k] = 1.0
            scale = T / ql if ql > 0.0 else 0.0
            for c in range(3):
                N[k, i, c] = scale * q[k, i, c]
    # Lax-Friedrichs fluxes with the axial impedance Z = m_t c
    m = prm[P_M]
    c_wave = prm[P_C]
    for f in range(K + 1):
        if f == 0:
            sub = 1.0 if r[0, 0, 2] < 0.0 else 0.0
            Z = (m + sub * prm[P_MAT]) * c_wave
            for c in range(3):
                Nstar[0, c] = N[0, 0, c] + Z * (v[0, 0, c] - avel[c])
        elif f == K:
            sub = 1.0 if r[K - 1, Np - 1, 2] < 0.0 else 0.0
            Z = (m + sub * prm[P_MAT]) * c_wave
            for c in range(3):
                Nstar[K, c] = N[K - 1, Np - 1, c] + Z * (fvel[c] - v[K - 1, Np - 1, c])
        else:
            sub = 1.0 if r[f, 0, 2] + r[f - 1, Np - 1, 2] < 0.0 else 0.0
            Z = (m + sub * prm[P_MAT]) * c_wave
            for c in range(3):
                Nstar[f, c] = N[f, 0, c] + 0.5 * Z * (v[f, 0, c] - v[f - 1, Np - 1, c])


@jit
def dg_rhs(r: np.ndarray, v: np.ndarray, anchor: np.ndarray, fpos: np.ndarray,
           fvel: np.ndarray, prm: np.ndarray, D: np.ndarray, LIFT: np.ndarray, q: np.ndarray,
           qt: np.ndarray, N: np.ndarray, Nstar: np.ndarray, faces: np.ndarray,
           slack: np.ndarray, dv: np.ndarray, fa: np.ndarray | None = None) -> None:
    """Acceleration dv/dt of every node (dr/dt = v needs no computation); without the
    internal damping when it is implicit (``P_IMPLICIT_DAMPING``, :func:`_implicit_damping`);
    ``fa`` the friction anchors (K, Np, 2) of the stick-spring law (``P_KS`` > 0)."""
    cint = prm[P_CINT] if prm[P_IMPLICIT_DAMPING] == 0.0 else 0.0
    _tension_field(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                   slack, cint)
    _acceleration(r, v, prm, D, LIFT, q, N, Nstar, dv, fa)


@jit
def _acceleration(r, v, prm, D, LIFT, q, N, Nstar, dv, fa=None):
    """dv/dt from the tangent q, nodal force N and face fluxes N* of :func:`_tension_field`
    (the part of :func:`dg_rhs` after the tension field; ``dv`` may not alias them). Seabed
    friction: the stick-spring law on the anchors ``fa`` (K, Np, 2) when given and
    ``prm[P_KS]`` > 0 (``_friction_kernels``), else the regularised Coulomb law."""
    K, Np = r.shape[0], r.shape[1]
    jac = 2.0 / prm[P_H]
    m = prm[P_M]
    g = prm[P_G]
    rho_w = prm[P_RHO_W]
    buoyancy = rho_w * prm[P_AC] * g
    drag = 0.5 * rho_w * prm[P_D]
    cdn, cdt = prm[P_CDN], prm[P_CDT]
    zb = prm[P_ZB]
    explicit_contact = prm[P_IMPLICIT_CONTACT] == 0.0
    friction = prm[P_MU] * prm[P_WSUB]
    vc = prm[P_VC]
    relax = prm[P_RELAX]
    ks = prm[P_KS]
    mu_kb = prm[P_MU] * prm[P_KB]
    # inverse lumped masses (dry; wet normal and tangential), hoisted out of the node loop
    imn_dry = 1.0 / m
    imn_wet = 1.0 / (m + prm[P_MAN])
    imt_wet = 1.0 / (m + prm[P_MAT])
    _strong_derivative(N, Nstar, D, LIFT, jac, dv)  # dN/ds, the fluxes as face values
    for k in range(K):
        for i in range(Np):
            fx = dv[k, i, 0]
            fy = dv[k, i, 1]
            fz = dv[k, i, 2] - m * g
            z = r[k, i, 2]
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            tx, ty, tz = 0.0, 0.0, 0.0
            if ql > 0.0:
                iql = 1.0 / ql
                tx, ty, tz = q[k, i, 0] * iql, q[k, i, 1] * iql, q[k, i, 2] * iql
            submerged = z < 0.0
            if submerged:
                fz += buoyancy
                # Morison drag on the velocity relative to the current, with sqrt(1 + eps)
                vrx = prm[P_UX] - v[k, i, 0]
                vry = prm[P_UX + 1] - v[k, i, 1]
                vrz = prm[P_UX + 2] - v[k, i, 2]
                vt = vrx * tx + vry * ty + vrz * tz
                vnx, vny, vnz = vrx - vt * tx, vry - vt * ty, vrz - vt * tz
                vn = math.sqrt(vnx * vnx + vny * vny + vnz * vnz)
                scale = drag * math.sqrt(ql)
                fx += scale * (cdt * abs(vt) * vt * tx + cdn * vn * vnx)
                fy += scale * (cdt * abs(vt) * vt * ty + cdn * vn * vny)
                fz += scale * (cdt * abs(vt) * vt * tz + cdn * vn * vnz)
            if z < zb:
                stick = False
                if fa is not None:
                    stick = ks > 0.0
                vx, vy = v[k, i, 0], v[k, i, 1]
                speed = 0.0
                if stick:
                    if mu_kb > 0.0:  # stick spring to the anchor, capped at mu N
                        sx, sy = stick_force(fa[k, i, 0] - r[k, i, 0], fa[k, i, 1] - r[k, i, 1],
                                             mu_kb * (zb - z), ks)
                        fx += sx
                        fy += sy
                else:
                    # Coulomb friction, ramped in up to the slip speed (docs/theory/cable.md)
                    speed = math.sqrt(vx * vx + vy * vy)
                if speed > 0.0:
                    if speed >= vc:  # sin(pi / 2) is 1.0 in floating point: no sin to call
                        mag = friction / speed
                    else:
                        mag = friction * math.sin(0.5 * math.pi * speed / vc) / speed
                    fx -= mag * vx
                    fy -= mag * vy
                if explicit_contact:
                    fz += -prm[P_KB] * (z - zb) - prm[P_CB] * min(v[k, i, 2], 0.0)
            # invert the added-mass-augmented mass
            imn = imn_wet if submerged else imn_dry
            imt = imt_wet if submerged else imn_dry
            ft = fx * tx + fy * ty + fz * tz
            dv[k, i, 0] = (fx - ft * tx) * imn + ft * tx * imt - relax * v[k, i, 0]
            dv[k, i, 1] = (fy - ft * ty) * imn + ft * ty * imt - relax * v[k, i, 1]
            dv[k, i, 2] = (fz - ft * tz) * imn + ft * tz * imt - relax * v[k, i, 2]


@jit
def _implicit_contact(r: np.ndarray, v: np.ndarray, prm: np.ndarray, dt: float) -> None:
    """Backward-Euler seabed spring-damper for nodes below the seabed after a step."""
    K, Np = r.shape[0], r.shape[1]
    zb, kb, cb = prm[P_ZB], prm[P_KB], prm[P_CB]
    mz = prm[P_M] + prm[P_MAN]
    for k in range(K):
        for i in range(Np):
            z = r[k, i, 2]
            if z >= zb:
                continue
            vs = v[k, i, 2]
            # z1 = z + dt (v1 - vs); m v1 = m vs - dt (kb (z1 - zb) + cb min(v1, 0))
            num = mz * vs - dt * kb * (z - dt * vs - zb)
            v1 = num / (mz + dt * cb + dt * dt * kb)
            if v1 >= 0.0:
                v1 = num / (mz + dt * dt * kb)
            r[k, i, 2] = z + dt * (v1 - vs)
            v[k, i, 2] = v1


@jit
def _damping_system(r, anchor, fpos, prm, D, LIFT, dt, q, faces, tng, minv, cn, flags, Y, band,
                    info):
    """Keep the backward-Euler system of the Kelvin-Voigt term factored for the state (r).

    With the tangents t, the taut set and the Morison masses frozen, the damping tension
    s = c_int t . dv/ds (taut nodes; 0 in compression) and its force d(s t)/ds, discretised
    exactly as in the explicit right-hand side (the derivative of v with traces from the anchor
    side, the divergence with traces from the fairlead side), make the step
    v1 = v* + dt M_eff^-1 Div(t s), s = C t . Grad(v1) a linear system for s:

        (I - dt C T^T Grad0 M_eff^-1 Div T) s = C T^T Grad(v*),

    banded with 2 Np - 1 sub- and Np super-diagonals (``band``, row-wise: entry (i, j) at
    ``band[i, 2 Np - 1 + j - i]``), LU-factored in place without pivoting (the identity plus
    dt times a dissipative operator).

    The factors are kept while they stay valid for the state: same dt, same taut and
    submerged nodes (``flags``), and no tangent turned by more than ``prm[P_DAMPING_TOL]``
    (default ``DAMPING_TANGENT_TOL``; 0 rebuilds every step) since they were made. The frozen
    operator is dissipative whatever the tangents it was built with (the same T on both
    sides), so reuse cannot destabilise; its error is that of the tangents' directions. ``info`` holds (valid, dt, any node taut, factorisations).
    Returns whether any node is taut.
    """
    K, Np = r.shape[0], r.shape[1]
    n = K * Np
    jac = 2.0 / prm[P_H]
    cint = prm[P_CINT]
    m = prm[P_M]
    kl, ku = 2 * Np - 1, Np
    _gradient(r, anchor, fpos, D, LIFT, jac, faces, q)
    stale = info[0] == 0.0 or info[1] != dt or prm[P_DAMPING_TOL] <= 0.0
    if not stale:
        tol2 = prm[P_DAMPING_TOL] * prm[P_DAMPING_TOL]
        for k in range(K):
            for i in range(Np):
                ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
                flag = (1.0 if ql > 1.0 else 0.0) + (2.0 if r[k, i, 2] < 0.0 else 0.0)
                if flag != flags[k, i]:
                    stale = True
                    break
                if ql > 0.0:
                    d2 = 0.0
                    for c in range(3):
                        d2 += (q[k, i, c] / ql - tng[k, i, c]) ** 2
                    if d2 > tol2:
                        stale = True
                        break
            if stale:
                break
    if not stale:
        return info[2] != 0.0
    info[0] = 1.0
    info[1] = dt
    info[3] += 1.0
    any_taut = False
    for k in range(K):
        for i in range(Np):
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            for c in range(3):
                tng[k, i, c] = q[k, i, c] / ql if ql > 0.0 else 0.0
            sub = r[k, i, 2] < 0.0
            flags[k, i] = (1.0 if ql > 1.0 else 0.0) + (2.0 if sub else 0.0)
            if ql > 1.0:
                cn[k, i] = cint
                any_taut = True
            else:
                cn[k, i] = 0.0
            mn = m + (prm[P_MAN] if sub else 0.0)
            mt = m + (prm[P_MAT] if sub else 0.0)
            minv[k, i, 0] = 1.0 / mn
            minv[k, i, 1] = 1.0 / mt - 1.0 / mn
    info[2] = 1.0 if any_taut else 0.0
    if not any_taut:
        return False
    # Y = M_eff^-1 Div T: rows of element k, columns (k, j) for j < Np and (k + 1, 0) as j = Np
    for k in range(K):
        for i in range(Np):
            a0, a1 = minv[k, i, 0], minv[k, i, 1]
            tx, ty, tz = tng[k, i, 0], tng[k, i, 1], tng[k, i, 2]
            for j in range(Np + 1):
                px, py, pz = 0.0, 0.0, 0.0
                if j < Np:
                    coef = jac * D[i, j]
                    if j == Np - 1 and k < K - 1:
                        coef -= jac * LIFT[i, 1]
                    px, py, pz = coef * tng[k, j, 0], coef * tng[k, j, 1], coef * tng[k, j, 2]
                elif k < K - 1:
                    coef = jac * LIFT[i, 1]
                    px, py = coef * tng[k + 1, 0, 0], coef * tng[k + 1, 0, 1]
                    pz = coef * tng[k + 1, 0, 2]
                dot = a1 * (tx * px + ty * py + tz * pz)
                Y[k, i, j, 0] = a0 * px + dot * tx
                Y[k, i, j, 1] = a0 * py + dot * ty
                Y[k, i, j, 2] = a0 * pz + dot * tz
    # I - dt C T^T Grad0 Y, Grad0: traces from the anchor side, zero end values
    for row in range(n):
        for col in range(kl + ku + 1):
            band[row, col] = 0.0
    for k in range(K):
        for i in range(Np):
            row = k * Np + i
            band[row, kl] = 1.0
            c = cn[k, i]
            if c == 0.0:
                continue
            tx, ty, tz = tng[k, i, 0], tng[k, i, 1], tng[k, i, 2]
            f = -dt * c * jac
            for j in range(Np + 1):
                if j == Np and k == K - 1:
                    break
                gx, gy, gz = 0.0, 0.0, 0.0
                for l in range(Np):
                    d = D[i, l]
                    gx += d * Y[k, l, j, 0]
                    gy += d * Y[k, l, j, 1]
                    gz += d * Y[k, l, j, 2]
                # left face: + LIFT_i0 (u_k0 - u_left), u_left the last node of element k - 1
                l0 = LIFT[i, 0]
                gx += l0 * Y[k, 0, j, 0]
                gy += l0 * Y[k, 0, j, 1]
                gz += l0 * Y[k, 0, j, 2]
                if j == 0 and k >= 1:  # column (k, 0) in row (k - 1, Np - 1) of Y
                    gx -= l0 * Y[k - 1, Np - 1, Np, 0]
                    gy -= l0 * Y[k - 1, Np - 1, Np, 1]
                    gz -= l0 * Y[k - 1, Np - 1, Np, 2]
                if k == K - 1:  # fairlead face, zero end value: + LIFT_i1 (0 - u_last)
                    l1 = LIFT[i, 1]
                    gx -= l1 * Y[k, Np - 1, j, 0]
                    gy -= l1 * Y[k, Np - 1, j, 1]
                    gz -= l1 * Y[k, Np - 1, j, 2]
                col = k * Np + j
                band[row, kl + col - row] += f * (tx * gx + ty * gy + tz * gz)
            if k >= 1:  # columns of element k - 1 through the left trace
                l0 = LIFT[i, 0]
                for j in range(Np):
                    col = (k - 1) * Np + j
                    g = (tx * Y[k - 1, Np - 1, j, 0] + ty * Y[k - 1, Np - 1, j, 1]
                         + tz * Y[k - 1, Np - 1, j, 2])
                    band[row, kl + col - row] -= f * l0 * g
    # banded LU without pivoting, in place (a zero pivot leaves factors that solve to
    # non-finite velocities, which the step's check reports)
    band_factor(band, n, kl, ku)
    return True


@jit
def _damping_solve(v, fvel, prm, D, LIFT, dt, qt, N, faces, tng, minv, cn, band, e):
    """The backward-Euler velocity update of the Kelvin-Voigt term with the factored system of
    :func:`_damping_system` (its frozen tangents, taut set and masses)."""
    _damping_solve_ends(v, _ZERO3, fvel, prm, D, LIFT, dt, qt, N, faces, tng, minv, cn, band, e)


@jit
def _damping_solve_ends(v, avel, fvel, prm, D, LIFT, dt, qt, N, faces, tng, minv, cn, band, e):
    """:func:`_damping_solve` with the start end moving at ``avel``."""
    K, Np = v.shape[0], v.shape[1]
    n = K * Np
    jac = 2.0 / prm[P_H]
    kl, ku = 2 * Np - 1, Np
    _gradient(v, avel, fvel, D, LIFT, jac, faces, qt)
    for k in range(K):
        for i in range(Np):
            e[k * Np + i] = cn[k, i] * (tng[k, i, 0] * qt[k, i, 0] + tng[k, i, 1] * qt[k, i, 1]
                                        + tng[k, i, 2] * qt[k, i, 2])
    band_solve(band, n, kl, ku, e)
    _damping_apply(v, prm, D, LIFT, dt, qt, N, faces, tng, minv, e)


@jit
def _damping_apply(v, prm, D, LIFT, dt, qt, N, faces, tng, minv, e):
    """v += dt M_eff^-1 Div(t s) for the damping tension s = ``e`` at the nodes, the
    divergence with traces from the fairlead side (each end face the end node's own): the
    second half of :func:`_damping_solve_ends`, also the DG system's (``_system_kernels``)."""
    K, Np = v.shape[0], v.shape[1]
    jac = 2.0 / prm[P_H]
    for k in range(K):
        for i in range(Np):
            s = e[k * Np + i]
            for c in range(3):
                N[k, i, c] = tng[k, i, c] * s
    for f in range(K):
        for c in range(3):
            faces[f, c] = N[f, 0, c]
    for c in range(3):
        faces[K, c] = N[K - 1, Np - 1, c]
    _strong_derivative(N, faces, D, LIFT, jac, qt)
    for k in range(K):
        for i in range(Np):
            ax, ay, az = qt[k, i, 0], qt[k, i, 1], qt[k, i, 2]
            dot = minv[k, i, 1] * (tng[k, i, 0] * ax + tng[k, i, 1] * ay + tng[k, i, 2] * az)
            v[k, i, 0] += dt * (minv[k, i, 0] * ax + dot * tng[k, i, 0])
            v[k, i, 1] += dt * (minv[k, i, 0] * ay + dot * tng[k, i, 1])
            v[k, i, 2] += dt * (minv[k, i, 0] * az + dot * tng[k, i, 2])


@jit
def _filter_slack(u: np.ndarray, F: np.ndarray, slack: np.ndarray, tmp: np.ndarray) -> None:
    K, Np = u.shape[0], u.shape[1]
    for k in range(K):
        if slack[k] == 0.0:
            continue
        for c in range(3):
            for i in range(Np):
                acc = 0.0
                for j in range(Np):
                    acc += F[i, j] * u[k, j, c]
                tmp[i] = acc
            for i in range(Np):
                u[k, i, c] = tmp[i]


@jit
def _ssp_rk3_step(r, v, t, dt, t0, t1, p0, w0, p1, w1, anchor, prm, D, LIFT, F, work3, q, qt,
                  N, Nstar, faces, slack, fpos, fvel, tmp, bcd, damp, fa):
    """One SSP-RK3 step of (r, v) from t to t + dt, then contact, internal damping (when
    implicit) and slack filtering; the stick-spring friction's anchors ``fa`` (or None) are
    held through the stages and committed after the step (``_friction_kernels.return_map``).
    ``damp`` holds the work arrays of the damping system (tangents, inverse masses,
    coefficients, Y, band, right-hand side), or is None when the line has no implicit internal
    damping."""
    r1, v1, r2, v2, a = work3[0], work3[1], work3[2], work3[3], work3[4]
    K, Np = r.shape[0], r.shape[1]
    # Stage-consistent fairlead data (Carpenter, Gottlieb, Abarbanel & Don 1995): the SSP-RK3
    # stages approximate u(t + dt) to first and u(t + dt/2) to second order, so they take the
    # matching Taylor polynomials of the boundary data, not its exact values, which would
    # reduce the accuracy of the end force to first order.
    g = bcd
    _hermite_derivatives(t0, t1, p0, w0, p1, w1, t, g)
    # dg_rhs's two parts called here, not dg_rhs: a kernel in between would compile and
    # optimise both once more (docs/validation/performance.md#first-run)
    cint = prm[P_CINT] if prm[P_IMPLICIT_DAMPING] == 0.0 else 0.0
    # stage 1: data at t
    for c in range(3):
        fpos[c] = g[0, c]
        fvel[c] = g[1, c]
    _tension_field(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                   slack, cint)
    _acceleration(r, v, prm, D, LIFT, q, N, Nstar, a, fa)
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                r1[k, i, c] = r[k, i, c] + dt * v[k, i, c]
                v1[k, i, c] = v[k, i, c] + dt * a[k, i, c]
    # stage 2: g + dt g'
    for c in range(3):
        fpos[c] = g[0, c] + dt * g[1, c]
        fvel[c] = g[1, c] + dt * g[2, c]
    _tension_field(r1, v1, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                   slack, cint)
    _acceleration(r1, v1, prm, D, LIFT, q, N, Nstar, a, fa)
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                r2[k, i, c] = 0.75 * r[k, i, c] + 0.25 * (r1[k, i, c] + dt * v1[k, i, c])
                v2[k, i, c] = 0.75 * v[k, i, c] + 0.25 * (v1[k, i, c] + dt * a[k, i, c])
    # stage 3: g + dt/2 g' + dt^2/4 g''
    for c in range(3):
        fpos[c] = g[0, c] + 0.5 * dt * g[1, c] + 0.25 * dt * dt * g[2, c]
        fvel[c] = g[1, c] + 0.5 * dt * g[2, c] + 0.25 * dt * dt * g[3, c]
    _tension_field(r2, v2, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                   slack, cint)
    _acceleration(r2, v2, prm, D, LIFT, q, N, Nstar, a, fa)
    third, two_thirds = 1.0 / 3.0, 2.0 / 3.0
    for k in range(K):
        for i in range(Np):
            for c in range(3):
                r[k, i, c] = third * r[k, i, c] + two_thirds * (r2[k, i, c] + dt * v2[k, i, c])
                v[k, i, c] = third * v[k, i, c] + two_thirds * (v2[k, i, c] + dt * a[k, i, c])
    if prm[P_IMPLICIT_CONTACT] != 0.0:
        _implicit_contact(r, v, prm, dt)
    # damp is None for a line without implicit damping: numba prunes the branch at compile
    # time, and its kernels (most of this step's compile time) are not compiled
    if damp is not None and prm[P_IMPLICIT_DAMPING] != 0.0 and prm[P_CINT] > 0.0:
        hermite(t0, t1, p0, w0, p1, w1, t + dt, fpos, fvel)
        tng, minv, cn, flags, Y, band, e, info = damp
        if _damping_system(r, anchor, fpos, prm, D, LIFT, dt, q, faces, tng, minv, cn, flags,
                           Y, band, info):
            _damping_solve(v, fvel, prm, D, LIFT, dt, qt, N, faces, tng, minv, cn, band, e)
    if prm[P_FILTER] != 0.0:
        _filter_slack(v, F, slack, tmp)
    if fa is not None:
        return_map(r, fa, prm[P_KS], prm[P_MU] * prm[P_KB], prm[P_ZB])


@jit
def _record(r, v, anchor, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack, weights,
            fair_out, anch_out):
    """End forces at the current state; returns the laid length [m]."""
    return _record_ends(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces,
                        slack, weights, fair_out, anch_out)


@jit
def _record_ends(r, v, anchor, avel, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
                 weights, fair_out, anch_out):
    """:func:`_record` with the start end moving at ``avel``."""
    _tension_field(r, v, anchor, avel, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar, faces, slack,
                   prm[P_CINT])
    K, Np = r.shape[0], r.shape[1]
    for c in range(3):
        fair_out[c] = -Nstar[K, c]
        anch_out[c] = Nstar[0, c]
    laid = 0.0
    threshold = prm[P_ZB] + 0.1 * prm[P_D]
    for k in range(K):
        for i in range(Np):
            if r[k, i, 2] <= threshold:
                laid += 0.5 * prm[P_H] * weights[i]
    return laid


@jit
def _check(r, v, q, prm, where):
    """Status of the state; ``where`` gets (element, node) of the first problem."""
    K, Np = r.shape[0], r.shape[1]
    vmax = prm[P_C]
    for k in range(K):
        for i in range(Np):
            s = 0.0
            for c in range(3):
                s += r[k, i, c] + v[k, i, c]
            if not math.isfinite(s):
                where[0], where[1] = k, i
                return DG_NOT_FINITE
            speed = math.sqrt(v[k, i, 0] ** 2 + v[k, i, 1] ** 2 + v[k, i, 2] ** 2)
            if speed > vmax:
                where[0], where[1] = k, i
                return DG_VELOCITY
            ql = math.sqrt(q[k, i, 0] ** 2 + q[k, i, 1] ** 2 + q[k, i, 2] ** 2)
            if ql - 1.0 > MAX_STRAIN:
                where[0], where[1] = k, i
                return DG_STRAIN
    return DG_OK


@jit
def _record_shape(r, N, shape_r, shape_t, index):
    """Node positions and tensions |N| of the state as shape sample ``index``."""
    K, Np = r.shape[0], r.shape[1]
    for k in range(K):
        for i in range(Np):
            node = k * Np + i
            shape_t[index, node] = math.sqrt(N[k, i, 0] ** 2 + N[k, i, 1] ** 2
                                             + N[k, i, 2] ** 2)
            for c in range(3):
                shape_r[index, node, c] = r[k, i, c]


@jit
def dg_run_path(r, v, time, path, velocity, anchor, prm, D, LIFT, F, weights, dt_max,
                fair_force, anch_force, laid, steps, shape_every, shape_r, shape_t, work3, q,
                qt, N, Nstar, faces, slack, fpos, fvel, tmp, bcd, where, damp, fa=None):
    """Advance the line along a fairlead path and record its end forces at every sample.

    ``time`` (n,), ``path`` and ``velocity`` (n, 3) give the fairlead at the output times;
    the state (r, v) must be the one at ``time[0]``. Sample 0 is recorded from it, then each
    interval is split into equal steps no longer than ``dt_max``. Every ``shape_every``-th
    sample (if > 0) the node positions and tensions go to ``shape_r``/``shape_t``. ``fa``:
    the friction anchors (K, Np, 2) of the stick-spring law (``P_KS`` > 0), updated at
    every step, or None.

    Returns
    -------
    (status, index)
        ``DG_OK`` and n, or the first failing status and the sample where it occurred
        (``where`` holds the element and node).
    """
    n = time.shape[0]
    K, Np = r.shape[0], r.shape[1]
    for c in range(3):
        fpos[c] = path[0, c]
        fvel[c] = velocity[0, c]
    # _record_ends, not its one-line wrapper _record: each kernel between two others compiles
    # (and optimises) everything below it once more (docs/validation/performance.md#first-run)
    laid[0] = _record_ends(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N, Nstar,
                           faces, slack, weights, fair_force[0], anch_force[0])
    steps[0] = 0.0
    n_shape = np.int64(0)  # not the literal 0: _record_shape compiles for int64 only
    for s in range(n):
        if shape_every > 0 and s % shape_every == 0:
            # N holds the axial force of the state at sample s (from its _record)
            _record_shape(r, N, shape_r, shape_t, n_shape)
            n_shape += 1
        if s == n - 1:
            break
        t0, t1 = time[s], time[s + 1]
        n_sub = int(math.ceil((t1 - t0) / dt_max * (1.0 - 1e-12)))
        if n_sub < 1:
            n_sub = 1
        dt = (t1 - t0) / n_sub
        for j in range(n_sub):
            _ssp_rk3_step(r, v, t0 + j * dt, dt, t0, t1, path[s], velocity[s], path[s + 1],
                          velocity[s + 1], anchor, prm, D, LIFT, F, work3, q, qt, N, Nstar,
                          faces, slack, fpos, fvel, tmp, bcd, damp, fa)
        for c in range(3):
            fpos[c] = path[s + 1, c]
            fvel[c] = velocity[s + 1, c]
        laid[s + 1] = _record_ends(r, v, anchor, _ZERO3, fpos, fvel, prm, D, LIFT, q, qt, N,
                                   Nstar, faces, slack, weights, fair_force[s + 1],
                                   anch_force[s + 1])
        steps[s + 1] = n_sub
        status = _check(r, v, q, prm, where)
        if status != DG_OK:
            return status, s + 1
    return DG_OK, n
