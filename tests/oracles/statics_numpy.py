"""Plain NumPy reference of the static equilibrium of a mooring system, without the system
kernels.

Each section's end forces and end stiffnesses come from the public catenary API
(:func:`floatmoor.mooring.catenary.solve_catenary`, itself checked against
``tests/oracles/catenary_numpy.py`` and MoorPy): the force on the end point and its stiffness
from ``solve_catenary(start, end)``, the force on the start point and the start's own
stiffness from ``solve_catenary(end, start)``; the cross blocks are their negatives (the forces
depend on the end-to-end vector only). The free points' equilibrium is then a plain damped
Newton iteration with ``numpy.linalg.solve``, a step limit and halving of the step until the
residual norm falls. Free points on the seabed: a set of points whose z is held at the seabed
(their x, y solved); a Newton step that would take a point below the seabed puts it there, and
after convergence a point whose net vertical force (weight, buoyancy, sections) points up
leaves it, one at a time, until none does.
"""

from __future__ import annotations

import numpy as np

from floatmoor.mooring.catenary import solve_catenary


def section_forces(system, pos, s):
    """(force on start, force on end, K_start_start, K_end_end) of section ``s`` at ``pos``."""
    a, b = pos[system.section_start[s]], pos[system.section_end[s]]
    # a section whose ends are both off the seabed is solved free of it: an intermediate
    # iterate may sag below it, which the catenary API refuses
    lowest = min(a[2], b[2])
    seabed = system.seabed_z if lowest - system.seabed_z <= 1e-6 * system.length[s] else -np.inf
    args = (system.length[s], system.axial_stiffness[s], system.weight[s], system.friction[s],
            seabed)
    fwd = solve_catenary(a, b, *args, tol=system.tolerance[s])
    back = solve_catenary(b, a, *args, tol=system.tolerance[s])
    return fwd.anchor_force, fwd.fairlead_force, back.stiffness, fwd.stiffness


def net_forces(system, pos):
    """Net force of the sections, weights and buoyancies on every point, (n_points, 3)."""
    net = np.array(system.external_force, dtype=float)
    for s in range(len(system.section_names)):
        fa, fb = section_forces(system, pos, s)[:2]
        net[system.section_start[s]] += fa
        net[system.section_end[s]] += fb
    return net


def residual_and_stiffness(system, pos, pinned=()):
    """Net force on every free coordinate and K = -dR/dx, free points in system order, the z
    of the points ``pinned`` left out."""
    coords = [(int(p), c) for p in system.free_index for c in range(3)
              if not (c == 2 and int(p) in pinned)]
    full_R = np.zeros(3 * len(system.point_names))
    full_K = np.zeros((full_R.size, full_R.size))
    full_R[:] = np.asarray(system.external_force, dtype=float).ravel()
    for s in range(len(system.section_names)):
        a, b = int(system.section_start[s]), int(system.section_end[s])
        fa, fb, kaa, kbb = section_forces(system, pos, s)
        full_R[3 * a:3 * a + 3] += fa
        full_R[3 * b:3 * b + 3] += fb
        for (p, q), k in {(a, a): kaa, (a, b): -kaa, (b, a): -kbb, (b, b): kbb}.items():
            full_K[3 * p:3 * p + 3, 3 * q:3 * q + 3] += k
    rows = [3 * p + c for p, c in coords]
    return full_R[rows], full_K[np.ix_(rows, rows)]


def _scale(system, pos):
    return max(np.abs(section_forces(system, pos, s)[1]).max()
               for s in range(len(system.section_names)))


def solve(system, body_positions=None, tol=1e-10, max_iter=200, step=20.0,
          return_contacts=False):
    """Positions of every point at equilibrium (free points from the system's guesses).

    Converged when |R| <= tol * (the largest end tension); ``step``: the largest move of a
    point in one iteration [m]. With ``return_contacts``: also the set of free points
    resting on the seabed.
    """
    pos = np.array(system.positions, dtype=float)
    if body_positions is not None:
        pos[system.body_index] = body_positions
    free = [int(p) for p in system.free_index]
    zb = system.seabed_z
    pinned = {p for p in free if pos[p, 2] <= zb}
    pos[list(pinned), 2] = zb
    iterations = 0
    while iterations < max_iter:
        R, K = residual_and_stiffness(system, pos, pinned)
        if np.abs(R).max() <= tol * _scale(system, pos):
            up = {p: net_forces(system, pos)[p, 2] for p in pinned}
            lifting = [p for p, fz in up.items() if fz > tol * _scale(system, pos)]
            if not lifting:
                return (pos, pinned) if return_contacts else pos
            pinned.discard(max(lifting, key=up.get))
            continue
        iterations += 1
        dx = np.zeros((len(system.point_names), 3))
        mask = np.zeros_like(dx, dtype=bool)
        for p in free:
            mask[p] = [True, True, p not in pinned]
        dx[mask] = np.linalg.solve(K, R)
        dx *= min(1.0, step / np.linalg.norm(dx, axis=1).max())
        landing = [p for p in free if p not in pinned and pos[p, 2] + dx[p, 2] < zb]
        if landing:
            pinned.update(landing)
            pos[landing, 2] = zb
            continue
        phi = R @ R
        alpha = 1.0
        while alpha > 1e-12:
            trial = pos + alpha * dx
            try:
                Rt = residual_and_stiffness(system, trial, pinned)[0]
            except Exception:  # a section without a solution at the trial point
                Rt = None
            if Rt is not None and Rt @ Rt < phi:
                break
            alpha *= 0.5
        pos = trial
    raise RuntimeError("the reference Newton iteration did not converge")
