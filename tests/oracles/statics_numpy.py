"""Plain NumPy reference of the static equilibrium of a mooring system, without the system
kernels.

Each section's end forces and end stiffnesses come from the public catenary API
(:func:`floatmoor.mooring.catenary.solve_catenary`, itself checked against
``tests/oracles/catenary_numpy.py`` and MoorPy): the force on the end point and its stiffness
from ``solve_catenary(start, end)``, the force on the start point and the start's own
stiffness from ``solve_catenary(end, start)``; the cross blocks are their negatives (the forces
depend on the end-to-end vector only). The free points' equilibrium is then a plain damped
Newton iteration with ``numpy.linalg.solve``, a step limit and halving of the step until the
residual norm falls.
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


def residual_and_stiffness(system, pos):
    """Net force on every free coordinate and K = -dR/dx, free points in system order."""
    free = list(system.free_index)
    col = {p: 3 * i for i, p in enumerate(free)}
    n = 3 * len(free)
    R = np.zeros(n)
    K = np.zeros((n, n))
    for i, p in enumerate(free):
        R[3 * i:3 * i + 3] += system.external_force[p]
    for s in range(len(system.section_names)):
        a, b = int(system.section_start[s]), int(system.section_end[s])
        fa, fb, kaa, kbb = section_forces(system, pos, s)
        blocks = {(a, a): kaa, (a, b): -kaa, (b, a): -kbb, (b, b): kbb}
        for p, f in ((a, fa), (b, fb)):
            if p in col:
                R[col[p]:col[p] + 3] += f
        for (p, q), k in blocks.items():
            if p in col and q in col:
                K[col[p]:col[p] + 3, col[q]:col[q] + 3] += k
    return R, K


def solve(system, body_positions=None, tol=1e-10, max_iter=200, step=20.0):
    """Positions of every point at equilibrium (free points from the system's guesses).

    Converged when |R| <= tol * (the largest end tension); ``step``: the largest move of a
    point in one iteration [m].
    """
    pos = np.array(system.positions, dtype=float)
    if body_positions is not None:
        pos[system.body_index] = body_positions
    free = list(system.free_index)
    for _ in range(max_iter):
        R, K = residual_and_stiffness(system, pos)
        scale = max(np.abs(section_forces(system, pos, s)[1]).max()
                    for s in range(len(system.section_names)))
        if np.abs(R).max() <= tol * scale:
            return pos
        dx = np.linalg.solve(K, R).reshape(-1, 3)
        dx *= min(1.0, step / np.linalg.norm(dx, axis=1).max())
        phi = R @ R
        alpha = 1.0
        while alpha > 1e-12:
            trial = pos.copy()
            trial[free] += alpha * dx
            try:
                Rt = residual_and_stiffness(system, trial)[0]
            except Exception:  # a section without a solution at the trial point
                Rt = None
            if Rt is not None and Rt @ Rt < phi:
                break
            alpha *= 0.5
        pos = trial
    raise RuntimeError("the reference Newton iteration did not converge")
