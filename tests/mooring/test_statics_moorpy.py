"""Statics of mooring systems against MoorPy 1.3's ``System`` on the same inputs:
a chain-rope-chain line with a clump weight at one joint and a buoy at the other, and a
three-line system with free points (clump weights, a bridle, a buoy); free points on the
seabed (a clump weight, a massless joint); point positions and end forces to 1e-6 relative,
and the stiffness at the body.

Mapping of our inputs to MoorPy's:

* line type: MoorPy's ``d_vol`` is the volume-equivalent diameter and its submerged weight
  w = (m - rho_w pi d_vol^2 / 4) g; with d_vol = sqrt(4 m / (pi rho_c)) this is our
  m g (1 - rho_w / rho_c). ``m`` and ``EA`` are ours.
* friction: none (C_B = 0). MoorPy 1.3's ``Line.staticSolve`` overwrites the line's ``cb``
  with the height of end A above the seabed, 0 for an anchor on it, so it applies no seabed
  friction; our lines set ``seabed_friction = false``.
* points: fixed -> type 1; free -> type 0 with the same m and v (MoorPy adds full buoyancy
  below z = -1 m: every free point here is deeper); body points -> type 1 points for the
  equilibrium, and coupled points (type -1) or points on a coupled body (type -1) for the
  stiffness.
* free points on the seabed: MoorPy 1.3 keeps a point from sinking below the seabed and,
  within its ``zTol`` (2 m) of it, adds an upward force that grows linearly from 0 at 2 m to
  the point's submerged weight on the seabed: a soft seabed on which a clump weight hovers
  where that force balances it (0.63 m up for the clump below), not our hard seabed. With
  ``zTol`` -> 0 it becomes ours (the clump within zTol of the seabed, the seabed carrying the
  rest); the comparisons of points on the seabed set ``zTol = 1e-9`` m and check that the
  default differs. A massless joint feels no such force in MoorPy (it has no submerged
  weight), only the floor. Neither puts friction on the point.
* sections: one MoorPy line per section, end A at the section's start. MoorPy puts the
  seabed contact at end A only; every touching-down section here starts at its anchor.
* tolerances: ``solveEquilibrium(tol=1e-8, maxIter=2000)``. Its ``tol`` is the largest
  position step [m] at convergence (default 0.05 m, far too loose for 1e-6) and its
  catenaries are solved to 0.01 tol; 1e-8 m is converged: 1e-6 m already agrees with 1e-10 m
  to ~1e-7 relative, and 1e-8 m and 1e-10 m give the same answer to ~1e-12.
"""

from __future__ import annotations

import contextlib
import io
import math

import numpy as np
import pytest

from floatmoor.mooring.statics_solver import (
    body_point_stiffness, build_static_system, coupled_stiffness, solve_statics,
)
from floatmoor.case.schema import Point
from tests.mooring.statics_systems import (
    CHAIN, ENVIRONMENT, SEABED, chain_rope_chain, make_line, three_lines,
)


pytestmark = pytest.mark.peer

mp = pytest.importorskip("moorpy")

#: The agreement asked for (docs/validation/mooring_systems.md#statics-against-moorpy).
PEER_RTOL = 1e-6
#: MoorPy's position tolerance [m] (see the module docstring).
MOORPY_TOL = 1e-8
#: Stiffness: MoorPy's analytic stiffness uses its own catenary Jacobian, solved to its
#: catenary tolerance (1e-10 m); observed agreement ~1e-8.
STIFFNESS_RTOL = 1e-6


def _moorpy_type(t):
    d = math.sqrt(4.0 * t.mass_per_length / (math.pi * t.material_density))
    return dict(name=t.name, d_vol=d, m=t.mass_per_length, EA=t.axial_stiffness,
                w=t.weight_in_water(ENVIRONMENT), Cd=1.2, CdAx=0.2, MBL=1e9, cost=0.0,
                material=t.name)


def _moorpy(points, lines, body="fixed", ref=(0.0, 0.0, 0.0), z_tol=None):
    """MoorPy System of our points and lines, solved; body points fixed, coupled or on a
    coupled body; ``z_tol``: the free points' seabed-force range (MoorPy's default: 2 m)."""
    ms = mp.System(depth=ENVIRONMENT.water_depth, rho=ENVIRONMENT.water_density,
                   g=ENVIRONMENT.gravity)
    if body == "body":
        ms.addBody(-1, np.r_[np.asarray(ref), np.zeros(3)])
    number = {}
    for p in points:
        r = np.array(p.position, dtype=float)
        if p.kind == "body" and body == "body":
            ms.addPoint(1, r - np.asarray(ref), body=1)
        elif p.kind == "body":
            ms.addPoint(-1 if body == "coupled" else 1, r)
        else:
            ms.addPoint(1 if p.kind == "fixed" else 0, r, m=p.mass, v=p.volume)
            if z_tol is not None:
                ms.pointList[-1].zTol = z_tol
        number[p.name] = len(ms.pointList)
    for line in lines:
        for s in line.sections:
            ms.lineTypes[s.line_type.name] = _moorpy_type(s.line_type)
            ms.addLine(s.length, s.line_type.name, pointA=number[s.start],
                       pointB=number[s.end])
    with contextlib.redirect_stdout(io.StringIO()):
        ms.initialize()
        ms.solveEquilibrium(tol=MOORPY_TOL, maxIter=2000)
    return ms, number


@pytest.mark.parametrize("maker", [chain_rope_chain, three_lines])
def test_equilibrium_matches_moorpy(maker):
    points, lines = maker()
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    ours = solve_statics(system)
    ms, number = _moorpy(points, lines)
    theirs = np.array([ms.pointList[number[n] - 1].r for n in system.point_names])
    fa = np.array([line.fA for line in ms.lineList])
    fb = np.array([line.fB for line in ms.lineList])
    span = np.ptp(system.positions, axis=0).max()
    pos_err = np.abs(ours.positions - theirs).max() / span
    force_scale = np.abs(ours.end_force).max()
    fa_err = np.abs(ours.start_force - fa).max() / force_scale
    fb_err = np.abs(ours.end_force - fb).max() / force_scale
    print(f"\n{maker.__name__}: positions {pos_err:.1e} of the span, start forces "
          f"{fa_err:.1e}, end forces {fb_err:.1e} of the largest tension")
    assert pos_err <= PEER_RTOL
    assert fa_err <= PEER_RTOL and fb_err <= PEER_RTOL
    # and each force component to 1e-6 of itself where it is not negligible
    big = np.abs(ours.end_force) > 1e-3 * force_scale
    np.testing.assert_allclose(ours.end_force[big], fb[big], rtol=PEER_RTOL)
    # the systems exercise what the check is for: a clump off the seabed, a buoy, touchdown
    assert np.all(ours.positions[system.free_index, 2] > system.seabed_z + 5.0)
    assert np.any(ours.laid_length > 0.0)


def test_body_point_stiffness_matches_moorpy_coupled_points():
    points, lines = three_lines()
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    K = body_point_stiffness(system, solve_statics(system))
    ms, _ = _moorpy(points, lines, body="coupled")
    K_mp = ms.getCoupledStiffnessA(lines_only=True)
    np.testing.assert_allclose(K, K_mp, rtol=STIFFNESS_RTOL,
                               atol=STIFFNESS_RTOL * np.abs(K).max())


def test_coupled_6x6_stiffness_matches_moorpy_body():
    points, lines = three_lines()
    ref = np.array([0.0, 0.0, -5.0])
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    K6 = coupled_stiffness(system, solve_statics(system), ref)
    ms, _ = _moorpy(points, lines, body="body", ref=ref)
    K6_mp = ms.getCoupledStiffnessA(lines_only=True)
    scale = np.abs(K6).max(axis=1, keepdims=True)  # rows mix N/m, N, N m/rad
    assert np.all(np.abs(K6 - K6_mp) <= STIFFNESS_RTOL * scale), (K6 - K6_mp) / scale


#: MoorPy's seabed-force range for a hard seabed (see the module docstring): the clump then
#: sits within 1e-9 m of the seabed, its forces within ~1e-9 of ours.
HARD_SEABED_Z_TOL = 1e-9


def _compare(points, lines, **kw):
    """(relative position error, relative force error, ours, MoorPy's positions)."""
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    ours = solve_statics(system)
    ms, number = _moorpy(points, lines, **kw)
    theirs = np.array([ms.pointList[number[n] - 1].r for n in system.point_names])
    fa = np.array([line.fA for line in ms.lineList])
    fb = np.array([line.fB for line in ms.lineList])
    span = np.ptp(system.positions, axis=0).max()
    force_scale = np.abs(ours.end_force).max()
    force_err = max(np.abs(ours.start_force - fa).max(), np.abs(ours.end_force - fb).max())
    return (np.abs(ours.positions - theirs).max() / span, force_err / force_scale, ours,
            theirs)


def test_clump_on_the_seabed_matches_moorpy_with_a_hard_seabed():
    points, lines = chain_rope_chain(anchor_x=-900.0)
    pos_err, force_err, ours, _ = _compare(points, lines, z_tol=HARD_SEABED_Z_TOL)
    print(f"\nclump on the seabed: positions {pos_err:.1e} of the span, forces "
          f"{force_err:.1e} of the largest tension")
    assert ours.on_seabed[1] and ours.seabed_reaction[1] > 1e3
    assert pos_err <= PEER_RTOL and force_err <= PEER_RTOL
    # MoorPy's default soft seabed holds the clump up off it: another model
    pos_err, force_err, _, theirs = _compare(points, lines)
    assert theirs[1, 2] > ENVIRONMENT.seabed_z + 0.1 and force_err > 1e-3


def test_massless_joint_on_the_seabed_matches_moorpy():
    """A chain split by a massless joint that lies on the seabed (no friction)."""
    points = [Point("anchor", "fixed", (-850.0, 0.0, -200.0)),
              Point("joint", "free", (-500.0, 0.0, -150.0)),
              Point("fair", "body", (0.0, 0.0, -20.0))]
    lines = [make_line("l", [(CHAIN, 300.0, "anchor", "joint"), (CHAIN, 600.0, "joint", "fair")],
                       points)]
    pos_err, force_err, ours, _ = _compare(points, lines)
    assert ours.on_seabed[1] and ours.laid_length[0] == 300.0 and ours.laid_length[1] > 100.0
    assert pos_err <= PEER_RTOL and force_err <= PEER_RTOL


def test_body_point_stiffness_with_a_clump_on_the_seabed_matches_moorpy():
    """MoorPy's stiffness of a point on its seabed has a 1e12 N/m vertical term: its z is held,
    as ours."""
    points, lines = chain_rope_chain(anchor_x=-900.0)
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    K = body_point_stiffness(system, solve_statics(system))
    ms, _ = _moorpy(points, lines, body="coupled", z_tol=HARD_SEABED_Z_TOL)
    K_mp = ms.getCoupledStiffnessA(lines_only=False)
    np.testing.assert_allclose(K, K_mp, rtol=STIFFNESS_RTOL,
                               atol=STIFFNESS_RTOL * np.abs(K).max())
