"""Statics of mooring systems (floatmoor.mooring.statics_solver): the equilibrium of free
points joined by catenary sections, its stiffness at the body and its time series."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import Point
from floatmoor.errors import SolverError
from floatmoor.mooring import _statics_solver_kernels as k
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.statics_solver import (
    SystemStatics, body_point_stiffness, build_static_system, coupled_stiffness, solve_statics,
)
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE
from tests.oracles import statics_numpy
from tests.mooring.statics_systems import (
    CHAIN, ENVIRONMENT, ROPE, SEABED, chain_rope_chain, make_line, three_lines,
)


pytestmark = pytest.mark.oracle

#: Kernel against the NumPy reference: both converge the force residual to ~1e-9 of the
#: tensions, which leaves the positions within ~1e-8 m of each other on these ~1 km systems.
POSITION_ATOL = 1e-7
#: Stiffness against central differences of the equilibrium (steps 5 cm, 2e-4 rad; solved to
#: a relative residual of 1e-10): the truncation error is ~(h/L)^2 ~ 1e-7 and the
#: equilibrium's noise ~1e-10 T / h ~ 1e-3 N/m, both far below 1e-5 of the stiffness.
FD_RTOL = 1e-5


def _system(maker, **kw):
    points, lines = maker(**kw)
    return build_static_system(points, lines, ENVIRONMENT, SEABED)


# ------------------------------------------------------------------------ one section
def test_single_section_line_is_exactly_todays_catenary():
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"'])
    system = build_static_system(case.points, case.lines, case.environment, case.seabed)
    line = case.lines[0]
    solution = solve_statics(system)
    w = line.line_type.weight_in_water(case.environment)
    cb = case.seabed.friction_coefficient if line.quasi_static.seabed_friction else 0.0
    ref = solve_catenary(line.anchor, line.fairlead, line.length,
                         line.line_type.axial_stiffness, w, cb, case.environment.seabed_z,
                         tol=line.quasi_static.tolerance,
                         max_iter=line.quasi_static.max_iterations)
    assert solution.iterations == 0  # no free point
    assert np.array_equal(solution.end_force[0], ref.fairlead_force)
    assert np.array_equal(solution.start_force[0], ref.anchor_force)
    assert solution.laid_length[0] == ref.laid_length
    assert np.array_equal(solution.section_stiffness[0, 3], ref.stiffness)


@pytest.mark.parametrize("kind", ["suspended", "touchdown", "touchdown with friction"])
def test_section_stiffness_is_the_derivative_of_its_end_forces(kind):
    pa = np.array([0.0, 0.0, -200.0]) if kind != "suspended" else np.array([0.0, 0.0, -150.0])
    pb = np.array([520.0, 210.0, -20.0])
    cb = 0.6 if kind == "touchdown with friction" else 0.0
    args = (600.0, 4.93e8, 980.0, cb, -200.0, np.nan, np.nan, 1e-13, 100)

    def forces(a, b):
        out = np.empty(k.N_SECTION_OUT)
        assert k.section_solve(a, b, *args, out) == 0
        return out

    out = forces(pa, pb)
    assert out[k.S_LB] > 0.0 if kind != "suspended" else out[k.S_LB] == 0.0
    h = 1e-4
    for which, p in (("A", 0), ("B", 1)):
        for c in range(3):
            dp = np.zeros(3)
            dp[c] = h
            ends_p = [pa, pb]
            ends_m = [pa, pb]
            ends_p[p] = ends_p[p] + dp
            ends_m[p] = ends_m[p] - dp
            if which == "A" and kind != "suspended" and c == 2:
                continue  # lifting the anchor off the seabed changes the regime (one-sided)
            fp, fm = forces(*ends_p), forces(*ends_m)
            for name, f in (("A", k.S_FA), ("B", k.S_FB)):
                fd = -(fp[f:f + 3] - fm[f:f + 3]) / (2 * h)
                blk = {"AA": k.S_KAA, "AB": k.S_KAB, "BA": k.S_KBA, "BB": k.S_KBB}[name + which]
                col = out[blk:blk + 9].reshape(3, 3)[:, c]
                np.testing.assert_allclose(col, fd, rtol=1e-5, atol=1e-6 * np.abs(out[:9]).max(),
                                           err_msg=f"K_{name}{which}, column {c}")


# ------------------------------------------------------------------------ equilibrium
@pytest.mark.parametrize("maker", [chain_rope_chain, three_lines])
def test_equilibrium_matches_numpy_reference(maker):
    system = _system(maker)
    solution = solve_statics(system)
    assert solution.residual <= 1e-9
    free = system.free_index
    # free points balance their sections' forces, their weight and their buoyancy
    net = solution.point_force[free] + system.external_force[free]
    assert np.abs(net).max() <= 1e-8 * np.abs(solution.end_force).max()
    assert np.abs(solution.positions - statics_numpy.solve(system)).max() <= POSITION_ATOL
    # the clump hangs off the seabed, the first chain rests partly on it
    assert solution.laid_length[0] > 0.0
    assert np.all(solution.positions[free, 2] > system.seabed_z + 1.0)


def test_far_off_initial_guess_reaches_the_same_equilibrium():
    points, lines = three_lines()
    reference = solve_statics(build_static_system(points, lines, ENVIRONMENT, SEABED))
    moved = [Point(p.name, p.kind, (0.5 * p.position[0], 0.5 * p.position[1], -120.0),
                   p.mass, p.volume) if p.kind == "free" else p for p in points]
    solution = solve_statics(build_static_system(moved, lines, ENVIRONMENT, SEABED))
    assert np.abs(solution.positions - reference.positions).max() <= POSITION_ATOL


# ------------------------------------------------------------------------ stiffness
def _equilibrium_forces(system, statics, body):
    solution = statics.solve(body)
    return solution, solution.point_force[system.body_index]


def test_body_point_stiffness_matches_finite_differences_of_the_equilibrium():
    system = _system(three_lines)
    statics = SystemStatics(system, force_rtol=1e-10)
    base = system.positions[system.body_index]
    solution = statics.solve(base)
    K = body_point_stiffness(system, solution)
    h = 5e-2
    fd = np.zeros_like(K)
    for j in range(K.shape[1]):
        dp = np.zeros(K.shape[1])
        dp[j] = h
        fp = _equilibrium_forces(system, statics, base + dp.reshape(-1, 3))[1].ravel()
        fm = _equilibrium_forces(system, statics, base - dp.reshape(-1, 3))[1].ravel()
        fd[:, j] = -(fp - fm) / (2 * h)
    np.testing.assert_allclose(K, fd, rtol=FD_RTOL, atol=FD_RTOL * np.abs(K).max())
    # condensing matters: the fairleads' own section stiffness alone is far from it
    own = np.zeros_like(K)
    for j, p in enumerate(system.body_index):
        for s, (a, b) in enumerate(zip(system.section_start, system.section_end)):
            if b == p:
                own[3 * j:3 * j + 3, 3 * j:3 * j + 3] += solution.section_stiffness[s, 3]
            if a == p:
                own[3 * j:3 * j + 3, 3 * j:3 * j + 3] += solution.section_stiffness[s, 0]
    assert np.abs(own - K).max() > 0.1 * np.abs(K).max()


def _rotation(theta):
    angle = np.linalg.norm(theta)
    if angle == 0.0:
        return np.eye(3)
    n = theta / angle
    N = np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])
    return np.eye(3) + np.sin(angle) * N + (1.0 - np.cos(angle)) * N @ N


def test_coupled_6x6_stiffness_matches_finite_differences_of_the_equilibrium():
    system = _system(three_lines)
    statics = SystemStatics(system, force_rtol=1e-10)
    ref = np.array([0.0, 0.0, -5.0])
    rel = system.positions[system.body_index] - ref
    solution = statics.solve(rel + ref)
    K6 = coupled_stiffness(system, solution, ref)

    def load(q):
        R = _rotation(q[3:])
        centre = ref + q[:3]
        points = centre + rel @ R.T
        forces = _equilibrium_forces(system, statics, points)[1]
        return np.concatenate([forces.sum(axis=0),
                               np.cross(points - centre, forces).sum(axis=0)])

    fd = np.zeros((6, 6))
    for j, h in enumerate([5e-2] * 3 + [2e-4] * 3):
        dq = np.zeros(6)
        dq[j] = h
        fd[:, j] = -(load(dq) - load(-dq)) / (2 * h)
    scale = np.abs(K6).max(axis=1, keepdims=True)  # rows mix N/m, N, N m/rad
    assert np.all(np.abs(K6 - fd) <= FD_RTOL * scale), (K6 - fd) / scale


# ------------------------------------------------------------------------ time series
def _circle_path(system, n, radius=4.0, period=40.0, dt=0.5):
    t = np.arange(n) * dt
    offset = np.stack([radius * np.sin(2 * np.pi * t / period), np.zeros(n),
                       0.5 * radius * np.cos(2 * np.pi * t / period)], axis=1)
    return t, system.positions[system.body_index][None, :, :] + offset[:, None, :]


def _series(system, t, path):
    n, ns, npnt = len(t), len(system.section_names), len(system.point_names)
    out = dict(positions=np.empty((n, npnt, 3)), start_force=np.empty((n, ns, 3)),
               end_force=np.empty((n, ns, 3)), laid_length=np.empty((n, ns)),
               iterations=np.empty(n), residual=np.empty(n))
    SystemStatics(system).solve_path(t, path, np.zeros_like(path), **out)
    return out


def test_warm_started_series_matches_independent_solves():
    system = _system(three_lines)
    t, path = _circle_path(system, 40)
    out = _series(system, t, path)
    for i in (0, 7, 23, 39):
        cold = solve_statics(system, path[i])  # from the system's initial guesses
        assert np.abs(out["positions"][i] - cold.positions).max() <= POSITION_ATOL
        np.testing.assert_allclose(out["end_force"][i], cold.end_force, rtol=1e-7,
                                   atol=1e-7 * np.abs(cold.end_force).max())
        np.testing.assert_allclose(out["start_force"][i], cold.start_force, rtol=1e-7,
                                   atol=1e-7 * np.abs(cold.start_force).max())
        np.testing.assert_allclose(out["laid_length"][i], cold.laid_length, atol=1e-6)
    assert np.all(out["residual"] <= 1e-9)
    assert out["iterations"][1:].max() <= 6  # warm starts


def test_series_kernel_matches_numpy_reference_and_is_fast():
    system = _system(three_lines)
    t, path = _circle_path(system, 400)
    _series(system, t[:2], path[:2])  # compile / load the kernels
    start = time.perf_counter()
    out = _series(system, t, path)
    per_sample = (time.perf_counter() - start) / len(t)
    for i in (0, 133, 399):
        ref = statics_numpy.solve(system, path[i])
        assert np.abs(out["positions"][i] - ref).max() <= POSITION_ATOL
    print(f"\nthree-line system statics: {per_sample * 1e3:.3f} ms per sample "
          f"({int(np.mean(out['iterations']) * 100) / 100} Newton iterations on average)")
    assert per_sample < 0.05  # generous: ~0.1 ms measured on one core


# ------------------------------------------------------------------------ failures
def test_unsupported_free_points_are_refused_naming_the_point():
    points, lines = chain_rope_chain()
    points = points + [Point("lost1", "free", (100.0, 0.0, -50.0), mass=100.0),
                       Point("lost2", "free", (150.0, 0.0, -50.0))]
    lines = lines + [make_line("stray", [(CHAIN, 60.0, "lost1", "lost2")], points)]
    with pytest.raises(SolverError, match=r"free point 'lost1' has no support.*'lost1', "
                                          r"'lost2'.*net force"):
        build_static_system(points, lines, ENVIRONMENT, SEABED)


def test_free_point_without_section_is_refused():
    points, lines = chain_rope_chain()
    points = points + [Point("alone", "free", (100.0, 0.0, -50.0), mass=100.0)]
    with pytest.raises(SolverError, match="free point 'alone' has no section"):
        build_static_system(points, lines, ENVIRONMENT, SEABED)


def test_buoy_without_equilibrium_below_the_surface_fails_with_its_residual():
    # a 5 m^3 buoy on 230 m of rope from an anchor 200 m deep: it would float above the surface
    points = [Point("anchor", "fixed", (0.0, 0.0, -200.0)),
              Point("buoy", "free", (30.0, 0.0, -60.0), mass=1000.0, volume=5.0)]
    lines = [make_line("riser", [(ROPE, 230.0, "anchor", "buoy")], points)]
    system = build_static_system(points, lines, ENVIRONMENT, SEABED)
    with pytest.raises(SolverError) as info:
        solve_statics(system)
    message = str(info.value)
    assert "free point 'buoy' has no equilibrium below the surface" in message
    lift = float(message.split("a net upward force of ")[1].split(" N")[0])
    # held at the surface it pulls up by its net buoyancy less the weight of the 200 m of
    # rope hanging from it (the other 30 m rest on the seabed; the stretch is ~2e-4)
    g, rho = ENVIRONMENT.gravity, ENVIRONMENT.water_density
    expected = rho * g * 5.0 - 1000.0 * g - ROPE.weight_in_water(ENVIRONMENT) * 200.0
    assert lift == pytest.approx(expected, rel=1e-3)


def test_failure_along_a_path_names_the_time():
    system = _system(chain_rope_chain)
    t = np.array([0.0, 1.0, 2.0])
    body = system.positions[system.body_index]
    path = np.stack([body, body + [0.0, 0.0, -100.0], body + [0.0, 0.0, -185.0]])
    with pytest.raises(SolverError, match=r"at t = 2 s: section l1\[2\] from 'buoy' .* to "
                                          r"'fair' .* has no valid catenary: .*below the seabed"):
        _series(system, t, path)


# ------------------------------------------------------------------------ free points on the seabed
#: The split line against the unsplit one: both solved to FORCE_RTOL (1e-9) of their tensions.
SPLIT_RTOL = 1e-8


def _lindahl(tmp_path, lengths, friction):
    """The Lindahl chain, quasi-static, whole or split into sections of ``lengths``."""
    sets = ['lines.*.model="quasi-static"', f"lines.*.quasi_static.seabed_friction={friction}"]
    if lengths is None:
        return load_case(LINDAHL_CASE, sets)
    sections = ", ".join(f'{{ type = "chain", length = {x} }}' for x in lengths)
    text = LINDAHL_CASE.read_text().replace(
        'type = "chain"\nlength = 33.0                  # m, unstretched',
        f"sections = [{sections}]")
    path = tmp_path / "split.toml"
    path.write_text(text)
    return load_case(path, sets)


def _solve_case(case):
    return solve_statics(build_static_system(case.points, case.lines, case.environment,
                                             case.seabed))


@pytest.mark.parametrize("friction", ["true", "false"])
@pytest.mark.parametrize("lengths", [(12.0, 21.0), (25.0, 8.0), (5.0, 7.0, 21.0)])
def test_split_lindahl_chain_is_the_same_catenary(tmp_path, lengths, friction):
    """A massless joint on the laid length rests on the seabed and carries nothing; one on
    the suspended length hangs; either way the line is the unsplit catenary (the 18.7 m laid
    length of the Lindahl chain at rest ends between 12 and 25 m from the anchor)."""
    one = _solve_case(_lindahl(tmp_path, None, friction))
    case = _lindahl(tmp_path, lengths, friction)
    two = _solve_case(case)
    scale = one.end_tension[0]
    np.testing.assert_allclose(two.end_force[-1], one.end_force[0], rtol=0,
                               atol=SPLIT_RTOL * scale)
    np.testing.assert_allclose(two.start_force[0], one.start_force[0], rtol=0,
                               atol=SPLIT_RTOL * scale)
    assert two.laid_length.sum() == pytest.approx(one.laid_length[0], abs=SPLIT_RTOL * 33.0)
    seabed = case.environment.seabed_z
    joints = [two.point_names.index(p.name) for p in case.points if p.kind == "free"]
    for j, p in enumerate(joints):
        on = sum(lengths[:j + 1]) < one.laid_length[0]
        assert bool(two.on_seabed[p]) == on
        assert (two.positions[p, 2] == seabed) == on
        assert two.seabed_reaction[p] == 0.0  # massless, and its sections lie flat on it
    if friction == "true":  # the friction drops the tension along the laid length
        assert two.start_tension[0] < two.end_tension[-1] - 1.0


@pytest.mark.parametrize("friction", ["true", "false"])
def test_split_lindahl_forced_run_is_the_unsplit_one(tmp_path, friction):
    """The whole record of the Lindahl case's circular motion (15 s, 6001 samples): the split
    line's fairlead and anchor forces are the unsplit line's; its joint stays on the seabed."""
    one = run_forced_motion(_lindahl(tmp_path, None, friction)).dataset
    case = _lindahl(tmp_path, (12.0, 21.0), friction)
    two = run_forced_motion(case).dataset
    assert two.sizes["time"] == one.sizes["time"] == 6001
    scale = float(one["fairlead_tension"].max())
    for name in ("fairlead_force", "anchor_force"):
        np.testing.assert_allclose(two[name].values, one[name].values, rtol=0,
                                   atol=SPLIT_RTOL * scale)
    joint = two["point_position"].sel(point="chain.joint1").values
    assert np.all(joint[:, 2] == case.environment.seabed_z)
    assert np.ptp(joint[:, 0]) > 1e-3  # it slides with the chain's stretch


def test_clump_resting_on_the_seabed_is_held_by_its_reaction():
    """The clump of the chain-rope-chain line with the anchor 30 m closer rests on the
    seabed: its seabed reaction is its submerged weight minus what its sections lift, its
    horizontal forces balance, and the NumPy reference finds the same state."""
    system = _system(chain_rope_chain, anchor_x=-900.0)
    solution = solve_statics(system)
    c = system.point_index("clump")
    assert solution.on_seabed.tolist() == [False, True, False, False]
    assert solution.positions[c, 2] == system.seabed_z
    g, rho = ENVIRONMENT.gravity, ENVIRONMENT.water_density
    submerged_weight = (3000.0 - rho * 0.5) * g
    lift = solution.point_force[c, 2]  # the sections' upward pull
    assert 0.0 < lift < submerged_weight  # the rope lifts part of it
    tension = np.abs(solution.end_force).max()
    assert solution.seabed_reaction[c] == pytest.approx(submerged_weight - lift,
                                                        abs=1e-9 * tension)
    assert np.abs(solution.point_force[c, :2]).max() <= 1e-9 * tension
    ref, resting = statics_numpy.solve(system, return_contacts=True)
    assert resting == {c}
    assert np.abs(solution.positions - ref).max() <= POSITION_ATOL


def test_point_starting_below_the_seabed_rests_on_it_or_rises():
    """Initial guesses below the seabed: the clump that should rest there does; the buoy
    that should float rises to where it floats (the same equilibrium as from good guesses)."""
    for anchor_x, clump_rests in ((-900.0, True), (-930.0, False)):
        points, lines = chain_rope_chain(anchor_x=anchor_x)
        reference = solve_statics(build_static_system(points, lines, ENVIRONMENT, SEABED))
        sunk = [Point(p.name, p.kind, (p.position[0], p.position[1], -250.0), p.mass,
                      p.volume) if p.kind == "free" else p for p in points]
        solution = solve_statics(build_static_system(sunk, lines, ENVIRONMENT, SEABED))
        assert solution.on_seabed[1] == clump_rests and not solution.on_seabed[2]
        assert np.abs(solution.positions - reference.positions).max() <= POSITION_ATOL


def _clump_path(system, n=241, period=60.0):
    """The fairlead swings 15 m either side of 5 m towards the anchor: the clump (anchor at
    -915 m) rests on the seabed at the near end and hangs at the far end."""
    t = np.linspace(0.0, 2 * period, n)
    offset = np.zeros((n, 1, 3))
    offset[:, 0, 0] = -5.0 + 15.0 * np.sin(2 * np.pi * t / period)
    return t, system.positions[system.body_index][None] + offset


def test_clump_lifts_off_and_lands_along_a_path():
    """Warm-started through lift-offs and landings: every sample is the independent
    equilibrium, and the clump's path and the tensions are continuous (across each switch
    the secant slope against the fairlead's motion lies within the slopes on either side)."""
    system = _system(chain_rope_chain, anchor_x=-915.0)
    t, path = _clump_path(system)
    n = len(t)
    out = _series(system, t, path)
    on_seabed = np.empty((n, len(system.point_names)), dtype=bool)
    SystemStatics(system).solve_path(t, path, np.zeros_like(path),
                                     **{k: np.empty_like(v) for k, v in out.items()},
                                     on_seabed=on_seabed)
    c = system.point_index("clump")
    rests = on_seabed[:, c]
    switches = np.flatnonzero(rests[1:] != rests[:-1])
    assert len(switches) == 4  # two lift-offs and two landings
    assert rests[switches[0]] != rests[switches[1]]
    z = out["positions"][:, c, 2]
    assert np.all(z[rests] == system.seabed_z) and np.all(z[~rests] > system.seabed_z)
    x = path[:, 0, 0]
    series = {"clump": out["positions"][:, c], "tension": np.linalg.norm(out["end_force"],
                                                                       axis=2)}
    for name, values in series.items():
        slope = np.linalg.norm(np.diff(values, axis=0).reshape(n - 1, -1), axis=1) / np.abs(
            np.diff(x))
        for i in switches:
            assert slope[i] <= 1.5 * max(slope[i - 1], slope[i + 1]), (name, i, slope[i - 2:i + 3])
    for i in np.concatenate([switches, switches + 1]):
        cold = solve_statics(system, path[i])
        assert cold.on_seabed[c] == rests[i]
        assert np.abs(out["positions"][i] - cold.positions).max() <= POSITION_ATOL
        assert np.abs(out["positions"][i] - statics_numpy.solve(system, path[i])).max() \
            <= POSITION_ATOL
    # at the switches the seabed reaction has faded to almost nothing
    reactions = [solve_statics(system, path[i + (0 if rests[i] else 1)]).seabed_reaction[c]
                 for i in switches]
    weight = (3000.0 - ENVIRONMENT.water_density * 0.5) * ENVIRONMENT.gravity
    assert max(reactions) < 0.1 * weight


def test_stiffness_with_a_point_on_the_seabed_matches_finite_differences():
    """The clump resting on the seabed stays there under small fairlead motions: the body
    stiffness condenses its x and y only, and matches central differences of the equilibrium."""
    system = _system(chain_rope_chain, anchor_x=-900.0)
    statics = SystemStatics(system, force_rtol=1e-10)
    base = system.positions[system.body_index]
    solution = statics.solve(base)
    assert solution.on_seabed[system.point_index("clump")]
    K = body_point_stiffness(system, solution)
    h = 5e-2
    fd = np.zeros_like(K)
    for j in range(3):
        dp = np.zeros((1, 3))
        dp[0, j] = h
        plus, fp = _equilibrium_forces(system, statics, base + dp)
        minus, fm = _equilibrium_forces(system, statics, base - dp)
        assert plus.on_seabed[1] and minus.on_seabed[1]
        fd[:, j] = -(fp - fm).ravel() / (2 * h)
    np.testing.assert_allclose(K, fd, rtol=FD_RTOL, atol=FD_RTOL * np.abs(K).max())
    # condensing the clump's z as if it were free gives another (wrong) stiffness
    released = dataclasses.replace(solution, on_seabed=np.zeros_like(solution.on_seabed))
    assert np.abs(body_point_stiffness(system, released) - K).max() > 1e-3 * np.abs(K).max()
