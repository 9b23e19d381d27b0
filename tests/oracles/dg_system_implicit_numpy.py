"""Plain NumPy reference of one implicit (generalised-alpha) step of a DG mooring system.

Written from the method as :mod:`floatmoor.mooring.dg._system_implicit_kernels` states it:
the sections' right-hand sides of :mod:`tests.oracles.dg_numpy` with their ends at the points
(free points' state velocities in the end fluxes), a free point's force the sum of its end
fluxes, weight, buoyancy, drag and seabed contact and friction, and the force-interpolating
generalised-alpha residual on the nodes' and free points' acceleration variables; Newton on a
dense Jacobian by central differences (no analytic derivative, no band storage, no Schur
complement): an independent route to the same step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from tests.oracles import dg_numpy as oracle
from tests.oracles.dg_implicit_numpy import generalised_alpha, mass_times

Array = NDArray[np.float64]


@dataclass
class Section:
    """A section for the oracle: its start and end point, oracle.rhs parameters (``D``,
    ``LIFT``, ``h``, physics, ``explicit_contact=True``: contact in the right-hand side)."""

    start: int
    end: int
    par: dict


@dataclass
class Point:
    """A point: kind ("fixed", "free", "body"), mass, displaced volume, drag area, added-mass
    coefficient, seabed stiffness and damping and the full friction force of its contact."""

    kind: str
    mass: float = 0.0
    volume: float = 0.0
    drag_area: float = 0.0
    ca: float = 0.0
    kb: float = 0.0
    cb: float = 0.0
    friction: float = 0.0


def effective_mass(p: Point, x: Array, rho_w: float) -> float:
    """M + C_a rho_w V below z = 0."""
    return p.mass + (p.ca * rho_w * p.volume if x[2] < 0.0 else 0.0)


def forces(sections: list[Section], points: list[Point], r: list[Array], v: list[Array],
           x: Array, u: Array, env: dict) -> tuple[list[Array], Array]:
    """M_eff A of every section's nodes and the force on every free point (0 for others);
    ``x``, ``u`` all points' positions and velocities (fixed: at rest, body: their path's);
    ``env``: rho_w, g, current, z_b, v_c."""
    Fp = np.zeros_like(x)
    out = []
    for s, sec in enumerate(sections):
        a, b = sec.start, sec.end
        A, fl = oracle.rhs(r[s], v[s], x[a], x[b], u[b], avel=u[a], **sec.par)
        out.append(mass_times(r[s], fl.q, A, sec.par["m"], sec.par["m_an"], sec.par["m_at"]))
        if points[a].kind == "free":
            Fp[a] += fl.Nstar[0]
        if points[b].kind == "free":
            Fp[b] -= fl.Nstar[-1]
    rho_w, g = env["rho_w"], env["g"]
    uc = np.asarray(env["current"], dtype=float)
    for i, p in enumerate(points):
        if p.kind != "free":
            continue
        wet = x[i, 2] < 0.0
        Fp[i, 2] += ((rho_w * p.volume if wet else 0.0) - p.mass) * g
        if wet:
            w = uc - u[i]
            Fp[i] += 0.5 * rho_w * p.drag_area * np.linalg.norm(w) * w
        if x[i, 2] < env["z_b"]:
            if p.kb > 0.0:
                Fp[i, 2] += -p.kb * (x[i, 2] - env["z_b"]) - p.cb * min(u[i, 2], 0.0)
            speed = float(np.hypot(u[i, 0], u[i, 1]))
            if p.friction > 0.0 and speed > 0.0:
                mag = p.friction * np.sin(0.5 * np.pi * speed / max(env["v_c"], speed))
                Fp[i, :2] -= mag * u[i, :2] / speed
    return out, Fp


def step(sections: list[Section], points: list[Point], r: list[Array], v: list[Array],
         x: Array, u: Array, acc: list[Array], pacc: Array, ends, env: dict, t: float,
         dt: float, rho_inf: float, tol: float = 1e-13, max_iter: int = 30,
         fd_step: float = 1e-7):
    """One step from t to t + dt; ``ends(time)`` gives every point's prescribed position and
    velocity (rows of free points ignored). Returns (r, v, acc, x, u, pacc) at t + dt."""
    am, af, beta, gamma = generalised_alpha(rho_inf)
    free = [i for i, p in enumerate(points) if p.kind == "free"]
    sizes = [a.size for a in r]
    offs = np.concatenate(([0], np.cumsum(sizes)))
    rho_w = env["rho_w"]

    def state(xe, ue, px, pu):
        """All points: the prescribed ones' data, the free ones' state."""
        xs, us = xe.copy(), ue.copy()
        xs[free], us[free] = px[free], pu[free]
        return xs, us

    x0e, u0e = ends(t)
    x0, u0 = state(x0e, u0e, x, u)
    F0, Fp0 = forces(sections, points, r, v, x0, u0, env)
    An = []  # the start's A per section
    for s, sec in enumerate(sections):
        A, _ = oracle.rhs(r[s], v[s], x0[sec.start], x0[sec.end], u0[sec.end],
                          avel=u0[sec.start], **sec.par)
        An.append(A)
    x1e, u1e = ends(t + dt)

    def unpack(z):
        a1 = [z[offs[s]:offs[s + 1]].reshape(r[s].shape) for s in range(len(r))]
        pa1 = pacc.copy()
        pa1[free] = z[offs[-1]:].reshape(-1, 3)
        return a1, pa1

    def residual(z):
        a1, pa1 = unpack(z)
        r1 = [r[s] + dt * v[s] + dt * dt * ((0.5 - beta) * acc[s] + beta * a1[s])
              for s in range(len(r))]
        v1 = [v[s] + dt * ((1.0 - gamma) * acc[s] + gamma * a1[s]) for s in range(len(r))]
        px = x + dt * u + dt * dt * ((0.5 - beta) * pacc + beta * pa1)
        pu = u + dt * ((1.0 - gamma) * pacc + gamma * pa1)
        xs, us = state(x1e, u1e, px, pu)
        out = []
        for s, sec in enumerate(sections):
            A1, fl = oracle.rhs(r1[s], v1[s], xs[sec.start], xs[sec.end], us[sec.end],
                                avel=us[sec.start], **sec.par)
            R = (1.0 - am) * a1[s] + am * acc[s] - (1.0 - af) * A1 - af * An[s]
            out.append(mass_times(r1[s], fl.q, R, sec.par["m"], sec.par["m_an"],
                                  sec.par["m_at"]).reshape(-1))
        _, Fp1 = forces(sections, points, r1, v1, xs, us, env)
        for i in free:
            meff = effective_mass(points[i], xs[i], rho_w)
            out.append(meff * ((1.0 - am) * pa1[i] + am * pacc[i]) - (1.0 - af) * Fp1[i]
                       - af * Fp0[i])
        return np.concatenate(out)

    z = np.concatenate([a.reshape(-1) for a in acc] + [pacc[free].reshape(-1)])
    for _ in range(max_iter):
        R0 = residual(z)
        n = R0.size
        J = np.empty((n, n))
        h = fd_step * max(1.0, float(np.max(np.abs(z))))
        for j in range(n):
            e = np.zeros(n)
            e[j] = h
            J[:, j] = (residual(z + e) - residual(z - e)) / (2.0 * h)
        dz = np.linalg.solve(J, -R0)
        z = z + dz
        if np.max(np.abs(beta * dt * dt * dz)) <= tol:
            break
    a1, pa1 = unpack(z)
    r1 = [r[s] + dt * v[s] + dt * dt * ((0.5 - beta) * acc[s] + beta * a1[s])
          for s in range(len(r))]
    v1 = [v[s] + dt * ((1.0 - gamma) * acc[s] + gamma * a1[s]) for s in range(len(r))]
    px = x + dt * u + dt * dt * ((0.5 - beta) * pacc + beta * pa1)
    pu = u + dt * ((1.0 - gamma) * pacc + gamma * pa1)
    return r1, v1, a1, px, pu, pa1
