"""Tests of the MoorDyn peer harness (``tests/io/moordyn_runner.py``) itself: the mapping of
floatmoor's line description onto MoorDyn's, read back from MoorDyn's own node quantities, and
MoorDyn's settled fairlead tension against floatmoor's static catenary.

Coarse settings (40 segments, 1 to 2 simulated seconds) keep the whole file within seconds.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import floatmoor
from tests.io.moordyn_runner import (
    MoorDynError,
    MoorDynLine,
    _coupling_path,
    moordyn_input,
    moordyn_parameters,
    moordyn_system,
    run_moordyn_forced,
)


pytestmark = pytest.mark.peer

moordyn = pytest.importorskip("moordyn")

SEGMENTS = 40
DT = 1e-4  # s; the Lindahl seabed spring (K d = 6.6e6 N/m^2) needs about this with RK2
#: Lumped-mass discretisation error of MoorDyn's static tension at 40 segments, observed:
#: 1e-4 (suspended), +0.15 % (Lindahl, of which ~+0.15 % is physics: the top ~0.7 m of chain
#: is in air, where the catenary below uses the submerged weight); asked: 1 %.
STATIC_RTOL = 0.01
#: MoorDyn's undamped axial jitter at rest on the seabed (+-0.3 %) is averaged over this window.
AVERAGE_WINDOW = 1.0  # s


def lindahl(friction: float = 0.0) -> MoorDynLine:
    """Case A, the Lindahl chain (docs/cases/lindahl.md), fairlead at its mean position."""
    return MoorDynLine(33.0, 0.0818, 1.0e4, 2.2e-3, 7800.0, 2.5, 0.5, 3.8,
                       anchor=(0.0, 0.0, -3.0), fairlead=(32.554, 0.0, 0.3), water_depth=3.0,
                       seabed_stiffness=3e9, seabed_damping_ratio=1.0,
                       friction_coefficient=friction, slip_speed=0.01)


def suspended() -> MoorDynLine:
    """The Lindahl chain's section, 25 m long, hanging free between two points far above the
    seabed in 50 m of water (20 m would be shorter than the 21.2 m chord: taut, not a
    catenary)."""
    return MoorDynLine(25.0, 0.0818, 1.0e4, 2.2e-3, 7800.0, 2.5, 0.5, 3.8,
                       tangential_added_mass_coefficient=0.7,
                       anchor=(0.0, 0.0, -40.0), fairlead=(15.0, 0.0, -25.0), water_depth=50.0)


def held_still(line: MoorDynLine, duration: float, dt: float = 0.01):
    t = np.arange(round(duration / dt) + 1) * dt
    x = np.tile(np.asarray(line.fairlead, dtype=float), (t.size, 1))
    return t, x, np.zeros_like(x)


@pytest.mark.parametrize("line", [suspended(), lindahl()], ids=["suspended", "lindahl"])
def test_static_tension_matches_catenary(line, capfd):
    cat = floatmoor.solve_catenary(line.anchor, line.fairlead, line.length,
                                   line.axial_stiffness, line.weight_in_water,
                                   friction_coefficient=0.0, seabed_z=-line.water_depth)
    duration = 2.0
    t, tension, wall = run_moordyn_forced(line, *held_still(line, duration),
                                          segments=SEGMENTS, dt=DT)
    out, _ = capfd.readouterr()
    assert out == ""  # MoorDyn's banner and input echo are kept off the console
    settled = float(np.mean(tension[t >= duration - AVERAGE_WINDOW]))
    print(f"{cat.profile_type}: MoorDyn {settled:.5g} N, catenary {cat.fairlead_tension:.5g} N "
          f"({settled / cat.fairlead_tension - 1:+.2e}), stepping {wall:.3f} s")
    assert settled == pytest.approx(cat.fairlead_tension, rel=STATIC_RTOL)
    assert 0.0 < wall


def test_mapping_read_back_from_moordyn():
    """Weight in water, added mass and drag per length as MoorDyn computes them equal floatmoor's
    definitions (docs/theory/cable.md) with the nominal drag diameter and the material area."""
    line = suspended()
    n = 20
    seg = line.length / n
    rho_w, d, a_c = line.water_density, line.diameter, line.material_area
    with moordyn_system(line, segments=n, dt=DT) as system:
        ml = moordyn.GetLine(system, 1)
        # weight in water of an interior node: m g (1 - rho_w / rho_c) per length
        assert moordyn.GetLineNodeWeight(ml, 5) == pytest.approx(
            (0.0, 0.0, -line.weight_in_water * seg), rel=1e-12)
        # mass matrix of an interior node: m + Ca rho_w A_c (normal), Ca_t rho_w A_c (tangent)
        q = np.subtract(moordyn.GetLineNodePos(ml, 6), moordyn.GetLineNodePos(ml, 4))
        q /= np.linalg.norm(q)
        qq = np.outer(q, q)
        expected = seg * (line.mass_per_length * np.eye(3) + rho_w * a_c * (
            line.added_mass_coefficient * (np.eye(3) - qq)
            + line.tangential_added_mass_coefficient * qq))
        np.testing.assert_allclose(moordyn.GetLineNodeM(ml, 5), expected, rtol=1e-12,
                                   atol=1e-12 * expected.max())
        # normal drag on the fairlead node (half a segment) moving out of the line's plane
        speed = 0.3
        fair = moordyn.GetLineNodePos(ml, n)
        moordyn.Step(system, list(fair), [0.0, speed, 0.0], 0.0, DT)
        drag = moordyn.GetLineNodeDrag(ml, n)
        assert drag[1] == pytest.approx(
            -0.5 * rho_w * line.normal_drag_coefficient * d * (seg / 2) * speed**2, rel=1e-9)
    with moordyn_system(line, segments=n, dt=DT) as system:
        ml = moordyn.GetLine(system, 1)
        # tangential drag on the fairlead node moving along the last segment
        fair = np.asarray(moordyn.GetLineNodePos(ml, n))
        q = fair - np.asarray(moordyn.GetLineNodePos(ml, n - 1))
        q /= np.linalg.norm(q)
        moordyn.Step(system, list(fair), list(speed * q), 0.0, DT)
        drag = np.asarray(moordyn.GetLineNodeDrag(ml, n))
        expected = -0.5 * rho_w * line.tangential_drag_coefficient * d * (seg / 2) * speed**2 * q
        np.testing.assert_allclose(drag, expected, rtol=1e-6, atol=1e-9 * np.abs(expected).max())


def test_seabed_and_friction_mapping():
    """The seabed spring per length is K d (penetration of a resting node w / (K d)); the
    damping, critical for the line's own mass; friction saturating at the slip speed on a
    resting node. Read back from the input file and from MoorDyn's settled state."""
    line = lindahl(friction=0.3)
    p = moordyn_parameters(line, SEGMENTS)
    k_l = line.seabed_stiffness * line.diameter
    assert p.seabed_stiffness * p.diameter == pytest.approx(k_l, rel=1e-14)
    assert p.seabed_damping * p.diameter == pytest.approx(
        2.0 * math.sqrt(line.mass_per_length * k_l), rel=1e-14)
    node_weight = line.weight_in_water * line.length / SEGMENTS
    assert p.friction_damping * line.slip_speed == pytest.approx(node_weight, rel=1e-14)
    text = moordyn_input(line, segments=SEGMENTS, dt=DT)
    options = {parts[1]: float(parts[0]) for parts in
               (ln.split() for ln in text.split("OPTIONS")[1].splitlines()[1:])
               if len(parts) == 2 and parts[1] != "tScheme"}
    assert options["kBot"] == p.seabed_stiffness
    assert options["cBot"] == p.seabed_damping
    assert options["FricDamp"] == p.friction_damping
    assert options["FrictionCoefficient"] == 0.3
    assert options["StatDynFricScale"] == 1.0
    assert options["dtM"] == DT and options["WtrDpth"] == 3.0
    with moordyn_system(line, segments=SEGMENTS, dt=DT) as system:
        ml = moordyn.GetLine(system, 1)
        for i in (3, 8):  # nodes lying on the seabed
            z = moordyn.GetLineNodePos(ml, i)[2]
            assert -line.water_depth - z == pytest.approx(line.weight_in_water / k_l, rel=1e-3)
            assert moordyn.GetLineNodeSeabedForce(ml, i)[2] == pytest.approx(node_weight,
                                                                             rel=1e-3)
        # the fairlead is 0.3 m above the water: MoorDyn weighs each segment's submerged
        # fraction only (floatmoor: instantaneous submergence), here the last segment's
        seg = line.length / SEGMENTS
        z_below, z_top = (moordyn.GetLineNodePos(ml, i)[2] for i in (SEGMENTS - 1, SEGMENTS))
        assert z_below < 0.0 < z_top
        submerged = -z_below / (z_top - z_below)  # MoorDyn also allows for the radius (~1 %)
        expected = -0.5 * seg * line.gravity * (line.mass_per_length - submerged
                                                * line.water_density * line.material_area)
        assert moordyn.GetLineNodeWeight(ml, SEGMENTS)[2] == pytest.approx(expected, rel=0.01)


def test_outputs_and_coupling_path():
    line = suspended()
    t, x, v = held_still(line, 0.2)
    x = x + np.outer(np.sin(np.pi * t), [0.01, 0.0, 0.02])
    v = np.outer(np.pi * np.cos(np.pi * t), [0.01, 0.0, 0.02])
    times, tension, wall = run_moordyn_forced(line, t, x, v, segments=10, dt=5e-4,
                                              output_every=4)
    np.testing.assert_array_equal(times, t[::4])
    assert tension.shape == times.shape and np.all(tension > 0.0) and wall > 0.0
    _, tension_hermite, _ = run_moordyn_forced(line, t, x, v, segments=10, dt=5e-4,
                                               output_every=4, substeps=2)
    np.testing.assert_allclose(tension_hermite, tension, rtol=1e-3)
    # the coupling path: piecewise linear, or the cubic Hermite interpolant (exact on cubics)
    start, secant = _coupling_path(x, v, 0.01, 1)
    np.testing.assert_array_equal(start, x[:-1])
    np.testing.assert_allclose(start + 0.01 * secant, x[1:], rtol=0, atol=1e-15)
    s = np.linspace(0.0, 1.0, 6)
    cubic = np.stack([s**3, s**2 - s, 2 * s], axis=1)
    dcubic = np.stack([3 * s**2, 2 * s - 1, 2 + 0 * s], axis=1)  # samples 0.2 s apart: t = s
    start, secant = _coupling_path(cubic, dcubic, 0.2, 4)
    fine = np.linspace(0.0, 1.0, 21)[:-1]
    np.testing.assert_allclose(start, np.stack([fine**3, fine**2 - fine, 2 * fine], axis=1),
                               atol=1e-14)


def test_failures_are_reported():
    line = lindahl()
    with pytest.raises(MoorDynError, match="MoorDyn failed near"):
        run_moordyn_forced(line, *held_still(line, 1.0), segments=SEGMENTS, dt=1e-2)
    with pytest.raises(ValueError, match="uniformly"):
        t, x, v = held_still(line, 0.1)
        t[3] += 1e-3
        run_moordyn_forced(line, t, x, v, segments=SEGMENTS, dt=DT)
    with pytest.raises(ValueError, match="below the seabed"):
        MoorDynLine(33.0, 0.0818, 1.0e4, 2.2e-3, 7800.0, 2.5, 0.5, 3.8,
                    anchor=(0.0, 0.0, -3.5), fairlead=(32.554, 0.0, 0.3), water_depth=3.0)
