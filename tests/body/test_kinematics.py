"""Rigid-body kinematics of body-fixed points and the generalised force of point loads."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.body.kinematics import generalised_force, points_state
from floatmoor.rotations import rotation_matrix


pytestmark = pytest.mark.oracle

#: Identities that hold to round-off.
ROUND_OFF = 1e-13


def test_points_follow_the_body_and_forces_give_moments_about_the_reference() -> None:
    rng = np.random.default_rng(5)
    arms = rng.normal(size=(4, 3)) * 10.0
    centre = np.array([1.0, -2.0, 0.5])
    x = np.concatenate([rng.normal(size=3), rng.uniform(-0.3, 0.3, 3)])
    v = rng.normal(size=6)
    pos, vel = points_state(x, v, arms, centre)
    R = rotation_matrix(*x[3:])
    assert np.abs(pos - (centre + x[:3] + arms @ R.T)).max() <= ROUND_OFF * 100
    forces = rng.normal(size=(4, 3)) * 1e3
    f6 = generalised_force(x, forces, arms)
    assert np.abs(f6[:3] - forces.sum(0)).max() <= ROUND_OFF * 1e4
    # without pitch and yaw the Euler-angle rates are the angular velocity, and the
    # generalised moment is the moment itself
    flat = x.copy()
    flat[4:] = 0.0
    R = rotation_matrix(*flat[3:])
    _, vel = points_state(flat, v, arms, centre)
    assert np.abs(vel - (v[:3] + np.cross(v[3:], arms @ R.T))).max() <= ROUND_OFF * 100
    f6 = generalised_force(flat, forces, arms)
    assert np.abs(f6[3:] - np.cross(arms @ R.T, forces).sum(0)).max() <= ROUND_OFF * 1e5
    # a force +x at 90 m above the reference pitches the body about +y (M_y = +90 F)
    f = generalised_force(np.zeros(6), np.array([[1.0, 0.0, 0.0]]), np.array([[0, 0, 90.0]]))
    assert np.allclose(f, [1.0, 0, 0, 0, 90.0, 0])


#: Central difference of the points' positions over +-h along (x', rates): its error is
#: (h^2 / 6) |d^3p/dt^3| ~ 1e-8 of arms ~10 m at h = 1e-4 (round-off ~1e-12 / h ~ 1e-8 m/s).
FD_STEP = 1e-4
FD_TOL = 1e-6


def test_point_velocity_is_the_derivative_of_its_position_and_powers_match() -> None:
    """At large angles the points' velocity is dp/dt of their position (the angular
    velocity of the Euler-angle rates), and the generalised force does on x' the power the
    point forces do on the points' velocities: the coupling neither makes nor loses energy
    in the kinematics (docs/theory/floater.md, "Energy consistency of the coupling"). The
    identification omega = (roll', pitch', yaw') failed both by ~|pitch| |rates| |arm|."""
    rng = np.random.default_rng(17)
    arms = rng.normal(size=(3, 3)) * 10.0
    centre = np.array([0.5, 1.0, -2.0])
    for _ in range(10):
        x = np.concatenate([rng.normal(size=3), rng.uniform(-0.6, 0.6, size=3)])
        v = rng.normal(size=6)
        _, vel = points_state(x, v, arms, centre)
        ahead, _ = points_state(x + FD_STEP * v, v, arms, centre)
        behind, _ = points_state(x - FD_STEP * v, v, arms, centre)
        assert np.abs(vel - (ahead - behind) / (2.0 * FD_STEP)).max() <= FD_TOL * 10.0
        forces = rng.normal(size=(3, 3)) * 1e3
        power = generalised_force(x, forces, arms) @ v
        assert abs(power - np.sum(forces * vel)) <= ROUND_OFF * 1e6


#: Kernels against tests/oracles/kinematics_numpy.py: the same arithmetic in another order
#: (the oracle multiplies the three elementary rotations, uses numpy.cross); round-off of
#: arms ~10 m and forces ~1e6 N. Observed <= 2e-15 relative.
KERNEL_RTOL = 1e-13


def test_kernels_match_numpy_oracle() -> None:
    from tests.oracles import kinematics_numpy as oracle

    rng = np.random.default_rng(11)
    for n in (1, 3, 7):
        for _ in range(20):
            x = np.concatenate([rng.normal(size=3) * 5.0, rng.uniform(-0.7, 0.7, size=3)])
            v = rng.normal(size=6)
            arms = rng.normal(size=(n, 3)) * 20.0
            centre = rng.normal(size=3)
            forces = rng.normal(size=(n, 3)) * 1e6
            p, w = points_state(x, v, arms, centre)
            po, wo = oracle.points_state(x, v, arms, centre)
            assert np.abs(p - po).max() <= KERNEL_RTOL * np.abs(po).max()
            assert np.abs(w - wo).max() <= KERNEL_RTOL * np.abs(wo).max()
            f = generalised_force(x, forces, arms)
            fo = oracle.generalised_force(x, forces, arms)
            assert np.abs(f - fo).max() <= KERNEL_RTOL * np.abs(fo).max()
