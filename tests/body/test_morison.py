"""Morison drag on the floater's strips (floatmoor/body/morison.py): the compiled kernels
against the NumPy oracle (tests/oracles/morison_numpy.py), closed forms of steady drag,
dissipation, the DeepCwind strips, and the prepared wave kinematics."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from floatmoor.body._morison_kernels import drag_force, lagrange_fill, lagrange_weights
from floatmoor.body.morison import (
    DEEPCWIND_OC4, KINEMATICS_PHASE_STEP, MIN_STRIPS, DragSettings, MorisonCoefficients,
    MorisonDrag, build_strips,
)
from floatmoor.case.load import load_case
from floatmoor.case.schema import Column, Floater, SemisubmersibleGeometry
from floatmoor.rotations import rotation_matrix
from floatmoor.waves.kinematics import PointKinematics
from floatmoor.waves.realisation import WaveField
from tests.oracles import morison_numpy as oracle


pytestmark = pytest.mark.oracle

ROOT = Path(__file__).resolve().parents[2]
DEEPCWIND = ROOT / "cases" / "deepcwind" / "deepcwind_free_decay.toml"
RHO = 1025.0

#: Compiled kernel against the NumPy oracle: the same terms summed in another order (and R
#: from a product of elementary rotations), so a few ulps of the largest strip force.
ORACLE_RTOL = 1e-12
#: Closed forms evaluated with the same floating-point operations in another order.
CLOSED_FORM_RTOL = 1e-12
#: The fluid velocity of prepare() at exact (every half step) sampling against the wave
#: module's PointKinematics: identical formulas, different summation (BLAS blocks), so
#: round-off of a sum of N components relative to its largest term.
KINEMATICS_RTOL = 1e-10


def _floater(columns=(), members=(), ref=(0.0, 0.0, 0.0)) -> Floater:
    return Floater(name="test", mass=1.0, centre_of_mass=(0.0, 0.0, 0.0),
                   inertia=(1.0, 1.0, 1.0, 0.0, 0.0, 0.0), reference_point=ref,
                   geometry=SemisubmersibleGeometry(columns=tuple(columns),
                                                    members=tuple(members)))


def _random_strips(rng: np.random.Generator, n: int):
    arms = rng.normal(scale=20.0, size=(n, 3))
    axes = rng.normal(size=(n, 3))
    axes /= np.linalg.norm(axes, axis=1)[:, None]
    cn = rng.uniform(0.0, 5e3, n)
    ca = rng.uniform(0.0, 5e3, n) * (rng.random(n) < 0.5)
    return arms, axes, cn, ca


# ------------------------------------------------------------------ kernels vs oracle
def test_kernel_matches_numpy_oracle() -> None:
    rng = np.random.default_rng(7)
    n = 57
    arms, axes, cn, ca = _random_strips(rng, n)
    worst = 0.0
    for _ in range(50):
        x = np.concatenate([rng.normal(scale=5.0, size=3), rng.uniform(-1.2, 1.2, 3)])
        v = np.concatenate([rng.normal(scale=2.0, size=3), rng.normal(scale=0.2, size=3)])
        fluid = rng.normal(scale=3.0, size=(4, n, 3))
        out = np.empty(6)
        drag_force(x, v, arms, axes, cn, ca, fluid, 2, out)
        ref = oracle.drag_force(x, v, arms, axes, cn, ca, fluid[2])
        scale = np.abs(ref).max()
        worst = max(worst, np.abs(out - ref).max() / scale)
    assert worst < ORACLE_RTOL, worst


def test_lagrange_fill_matches_oracle() -> None:
    rng = np.random.default_rng(3)
    m, n_fine, width = 7, 40, 5
    n_coarse = (n_fine - 1) // m + 4
    h = 0.3
    t_coarse = h * (np.arange(n_coarse) - 1.0)
    values = rng.normal(size=(n_coarse, width))
    out = np.empty((n_fine, width))
    lagrange_fill(values, lagrange_weights(m), out)
    for k in range(n_fine):
        ref = oracle.lagrange_interpolate(t_coarse, values, k * h / m)
        np.testing.assert_allclose(out[k], ref, rtol=0, atol=1e-13)


def test_lagrange_is_exact_for_cubics() -> None:
    m, n_fine = 5, 23
    n_coarse = (n_fine - 1) // m + 4
    h = 0.7
    tc = h * (np.arange(n_coarse) - 1.0)
    poly = np.array([0.3, -1.1, 2.0, 0.5])  # cubic
    out = np.empty((n_fine, 1))
    lagrange_fill(np.polyval(poly, tc)[:, None], lagrange_weights(m), out)
    tf = h / m * np.arange(n_fine)
    np.testing.assert_allclose(out[:, 0], np.polyval(poly, tf), rtol=1e-13, atol=1e-12)


# ------------------------------------------------------------------ closed forms
def test_uniform_flow_past_a_vertical_column() -> None:
    """F = 1/2 rho Cd D L U^2 along the flow, at the submerged length's centroid."""
    cd, d, x0, y0 = 0.8, 3.0, 4.0, -2.0
    col = Column(x=x0, y=y0, diameter=d, z_top=5.0, z_bottom=-10.0)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=cd),
                            strip_length=1.0)
    drag = MorisonDrag(_floater([col]), settings, RHO)
    assert drag.strips.n == 10 and drag.strips.submerged_length("column") == 10.0
    u = np.array([1.5, -0.8, 0.0])
    f = drag.force_in(np.tile(u, (drag.strips.n, 1)), np.zeros(6), np.zeros(6))
    mag = 0.5 * RHO * cd * d * 10.0 * float(u @ u)
    expected_f = mag * u / np.linalg.norm(u)
    arm = np.array([x0, y0, -5.0])  # the centroid of the submerged length
    expected = np.concatenate([expected_f, np.cross(arm, expected_f)])
    np.testing.assert_allclose(f, expected, rtol=CLOSED_FORM_RTOL, atol=1e-9 * mag)
    # the same relative flow from a body translating in still water
    g = drag.force_in(None, np.zeros(6), np.concatenate([-u, np.zeros(3)]))
    np.testing.assert_allclose(g, expected, rtol=CLOSED_FORM_RTOL, atol=1e-9 * mag)
    # a vertical flow along the column's axis gives no transverse drag
    h = drag.force_in(np.tile([0.0, 0.0, 2.0], (drag.strips.n, 1)), np.zeros(6), np.zeros(6))
    assert np.abs(h).max() < 1e-9 * mag


def test_current_enters_the_relative_velocity() -> None:
    col = Column(x=0.0, y=0.0, diameter=2.0, z_top=1.0, z_bottom=-8.0)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=1.0))
    drag = MorisonDrag(_floater([col]), settings, RHO, current=(0.5, 0.0, 0.0))
    drag.prepare(0.0, 3, 0.01)
    f = drag.force(1, np.zeros(6), np.zeros(6))
    assert f[0] == pytest.approx(0.5 * RHO * 1.0 * 2.0 * 8.0 * 0.25, rel=CLOSED_FORM_RTOL)


@pytest.mark.parametrize("area", ["disc", "annulus"])
def test_heave_plate_axial_drag_opposes_heave(area: str) -> None:
    """A body moving in heave at speed w in still water: F_z = -1/2 rho Cd A |w| w."""
    cd, dc, dp = 1.6, 12.0, 24.0
    col = Column(x=0.0, y=0.0, diameter=dc, z_top=12.0, z_bottom=-20.0,
                 heave_plate_diameter=dp, heave_plate_height=6.0)
    settings = DragSettings(coefficients=MorisonCoefficients(heave_plate_axial=cd),
                            heave_plate_area=area)
    drag = MorisonDrag(_floater([col]), settings, RHO)
    a = math.pi / 4 * (dp ** 2 - (dc ** 2 if area == "annulus" else 0.0))
    for w in (-0.7, 0.4):
        f = drag.force_in(None, np.zeros(6), np.array([0.0, 0.0, w, 0.0, 0.0, 0.0]))
        expected = -0.5 * RHO * cd * a * abs(w) * w
        assert f[2] == pytest.approx(expected, rel=CLOSED_FORM_RTOL)
        assert np.abs(f[[0, 1, 3, 4, 5]]).max() < 1e-9 * abs(expected)


def test_pitching_column_moment() -> None:
    """Column on the pitch axis from -L to 0, pitch rate q in still water: point velocity
    q z e_x, so f_x = 1/2 rho Cd D q|q| z^2 per length and M_y = -1/2 rho Cd D q|q| L^4/4.
    With n midpoint strips the sums of z^2 and z^3 are exactly L^3/3 (1 - 1/(4 n^2)) and
    -L^4/4 (1 - 1/(2 n^2)) (composite midpoint rule, remainder exact for cubics)."""
    cd, d, length, n = 0.6, 6.5, 20.0, 40
    col = Column(x=0.0, y=0.0, diameter=d, z_top=10.0, z_bottom=-length)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=cd),
                            strip_length=length / n)
    drag = MorisonDrag(_floater([col]), settings, RHO)
    assert drag.strips.n == n
    k = 0.5 * RHO * cd * d
    for q in (0.05, -0.03):
        f = drag.force_in(None, np.zeros(6), np.array([0.0, 0.0, 0.0, 0.0, q, 0.0]))
        fx = k * q * abs(q) * length ** 3 / 3 * (1 - 1 / (4 * n * n))
        my = -k * q * abs(q) * length ** 4 / 4 * (1 - 1 / (2 * n * n))
        assert f[0] == pytest.approx(fx, rel=CLOSED_FORM_RTOL)
        assert f[4] == pytest.approx(my, rel=CLOSED_FORM_RTOL)
        assert my * q < 0.0  # opposes the rotation
        assert np.abs(f[[1, 2, 3, 5]]).max() < 1e-9 * abs(my) / length


def test_rotated_body_uses_the_rotated_axis() -> None:
    """A column pitched by 90 degrees lies along x: heave flow is transverse to it, surge
    flow is axial (no transverse drag)."""
    cd, d = 1.0, 2.0
    col = Column(x=0.0, y=0.0, diameter=d, z_top=0.0, z_bottom=-10.0)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=cd),
                            strip_length=1.0)
    drag = MorisonDrag(_floater([col]), settings, RHO)
    x = np.array([0.0, 0.0, 0.0, 0.0, math.pi / 2, 0.0])
    surge = drag.force_in(None, x, np.array([1.0, 0, 0, 0, 0, 0]))
    heave = drag.force_in(None, x, np.array([0, 0, 1.0, 0, 0, 0]))
    mag = 0.5 * RHO * cd * d * 10.0
    assert abs(surge[0]) < 1e-9 * mag
    assert heave[2] == pytest.approx(-mag, rel=CLOSED_FORM_RTOL)
    # the rotated arms: centroid at R (0, 0, -5) = (-5, 0, 0): M_y = z f_x - x f_z = -5 mag
    assert heave[4] == pytest.approx(-5.0 * mag, rel=CLOSED_FORM_RTOL)


# ------------------------------------------------------------------ dissipation
def test_drag_dissipates_in_still_water() -> None:
    """Power v . F = -sum (cn |u_n|^3 + ca |u_a|^3) <= 0 for any body velocity."""
    case = load_case(DEEPCWIND)
    drag = MorisonDrag(case.floater, DragSettings(coefficients=DEEPCWIND_OC4), RHO)
    s = drag.strips
    rng = np.random.default_rng(11)
    worst = 0.0
    for _ in range(300):
        x = np.concatenate([rng.normal(scale=3.0, size=3), rng.uniform(-0.5, 0.5, 3)])
        v = np.concatenate([rng.normal(scale=2.0, size=3), rng.normal(scale=0.1, size=3)])
        f = drag.force_in(None, x, v)
        power = float(v @ f)
        r = oracle.rotation(*x[3:])
        arm, e = s.arms @ r.T, s.axes @ r.T
        u = -(v[:3] + np.cross(v[3:], arm))
        ua = np.sum(u * e, axis=1)
        un = np.linalg.norm(u - ua[:, None] * e, axis=1)
        expected = -float(np.sum(s.normal * un ** 3 + s.axial * np.abs(ua) ** 3))
        assert power <= 0.0
        worst = max(worst, abs(power - expected) / abs(expected))
    assert worst < ORACLE_RTOL, worst


# ------------------------------------------------------------------ DeepCwind strips
def test_deepcwind_preset_strips() -> None:
    case = load_case(DEEPCWIND)
    settings = DragSettings(coefficients=DEEPCWIND_OC4)
    s = build_strips(case.floater, settings, RHO)
    geometry = case.floater.geometry
    # columns: central 20 m below z = 0, three upper columns from -14 to 0 m, three 6 m plates
    assert s.submerged_length("column") == pytest.approx(20.0 + 3 * 14.0, rel=1e-12)
    assert s.submerged_length("heave_plate_side") == pytest.approx(3 * 6.0, rel=1e-12)
    assert s.count("heave_plate_axial") == 3 and s.count("column_axial") == 0
    # members: their parts below z = 0 (the braces rise from -16.2 m to +9.13 m)
    wet, counts = 0.0, 0
    for m in geometry.members:
        a, b = np.array(m.start), np.array(m.end)
        frac = 1.0 if max(a[2], b[2]) < 0 else -min(a[2], b[2]) / abs(b[2] - a[2])
        length = frac * float(np.linalg.norm(b - a))
        wet += length
        counts += max(MIN_STRIPS, math.ceil(length / settings.strip_length))
    assert s.submerged_length("member") == pytest.approx(wet, rel=1e-12)
    assert s.count("member") == counts
    assert s.count("column") == 10 + 3 * 7 and s.count("heave_plate_side") == 3 * 4
    assert s.n == 141
    assert np.all(s.points[:, 2] < 0.0)
    # transverse coefficient sum: 1/2 rho sum Cd D ds over the kinds
    expected_cn = 0.5 * RHO * (0.6 * (6.5 * 20 + 12.0 * 3 * 14) + 0.6 * 24.0 * 18
                               + 0.564 * 1.6 * wet)
    assert s.normal.sum() == pytest.approx(expected_cn, rel=1e-12)
    # heave-plate axial: full 24 m discs with Cd 1.60 (HydroDyn's area, the quasi-dynamic paper's Cd, docs/cases/deepcwind.md)
    plate = s.axial[s.kind == 2]
    np.testing.assert_allclose(plate, 0.5 * RHO * 1.6 * math.pi / 4 * 24.0 ** 2, rtol=1e-14)


def test_strips_follow_the_mean_waterline_of_a_trimmed_body() -> None:
    """With a mean trim and heave (the rotor thrust's), the strips cover the parts that are
    wet in the mean pose: a column whose top rises keeps less length, one that sinks more,
    and every strip centre is submerged there."""
    case = load_case(DEEPCWIND)
    settings = DragSettings(coefficients=DEEPCWIND_OC4)
    pitch, heave = math.radians(-4.0), -0.3  # the +x column rises by 28.9 sin(4 deg) = 2.0 m
    xm = np.array([-9.0, 0.0, heave, 0.0, pitch, 0.0])
    s = build_strips(case.floater, settings, RHO, xm)
    R = rotation_matrix(*xm[3:])
    centre = np.asarray(case.floater.reference_point)
    z_mean = centre[2] + xm[2] + (s.points - centre) @ R[2]
    assert np.all(z_mean < 0.0)
    # the columns: wet from their bottom (the plate's top, -14 m, or -20 m for the central
    # column) up to where the mean pose's waterline crosses their axis
    wet = 0.0
    for c in case.floater.geometry.columns:
        bottom = c.z_bottom + (c.heave_plate_height if c.heave_plate_diameter else 0.0)
        # heave + R[2] . (p - centre) = 0 at p = (x, y, z_body)
        z_body = -(heave + R[2, 0] * c.x + R[2, 1] * c.y) / R[2, 2]
        wet += z_body - bottom
    assert s.submerged_length("column") == pytest.approx(wet, rel=1e-12)
    rest = build_strips(case.floater, settings, RHO)
    assert s.submerged_length("heave_plate_side") == rest.submerged_length("heave_plate_side")
    # the +x column lost about 2 m, the other two gained about 1 m each, the central 0.3 m
    assert wet - rest.submerged_length("column") == pytest.approx(0.3 + 3 * 0.3, abs=0.05)


def test_strip_length_convergence() -> None:
    """Default 2 m strips against 0.25 m strips on the DeepCwind preset (body motion in
    still water): the midpoint rule's O(ds^2) error."""
    case = load_case(DEEPCWIND)
    coarse = MorisonDrag(case.floater, DragSettings(coefficients=DEEPCWIND_OC4), RHO)
    fine = MorisonDrag(case.floater, DragSettings(coefficients=DEEPCWIND_OC4,
                                                  strip_length=0.25), RHO)
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(50):
        v = np.concatenate([rng.normal(scale=1.0, size=3), rng.normal(scale=0.03, size=3)])
        fc, ff = coarse.force_in(None, np.zeros(6), v), fine.force_in(None, np.zeros(6), v)
        scale = np.concatenate([np.abs(ff[:3]).max() * np.ones(3),
                                np.abs(ff[3:]).max() * np.ones(3)])
        worst = max(worst, float(np.max(np.abs(fc - ff) / scale)))
    # measured 6.2e-4: the error of the coarse strips relative to the largest force / moment
    assert worst < STRIP_CONVERGENCE_TOL, worst


#: 2 m against 0.25 m strips (test_strip_length_convergence): the midpoint rule's relative
#: error on the rotation-induced (linear in position) velocity squared is ~ 1/(4 n^2) per
#: part; with 4 to 13 strips per part that is 1.5e-3 to 1.6e-2 of a part's own force, and
#: the parts' errors partly cancel in the sums. Measured: 6.2e-4.
STRIP_CONVERGENCE_TOL = 2e-3


# ------------------------------------------------------------------ prepared kinematics
def _two_columns() -> Floater:
    return _floater([Column(x=10.0, y=-5.0, diameter=4.0, z_top=3.0, z_bottom=-15.0),
                     Column(x=-20.0, y=8.0, diameter=6.0, z_top=3.0, z_bottom=-9.0,
                            heave_plate_diameter=10.0, heave_plate_height=2.0)])


def test_prepare_exact_matches_point_kinematics() -> None:
    sea = WaveField.regular(2.0, 9.0, direction=0.4, phase=0.3, depth=60.0)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=1.0,
                                                             heave_plate_axial=2.0),
                            kinematics_interval=0.0)
    drag = MorisonDrag(_two_columns(), settings, RHO, sea)
    t0, dt_half, n = 12.3, 0.05, 9
    drag.prepare(t0, n, dt_half)
    pk = PointKinematics(sea, drag.strips.points, stretching="none")
    for k in range(n):
        kin = pk(t0 + k * dt_half)
        # PointKinematics dries points above a trough; the drag keeps the strips wet at
        # their mean positions (first-order model), so compare where both are wet
        assert kin.wet.sum() >= drag.strips.n - 2
        ref = kin.velocity[kin.wet]
        got = drag.fluid_velocity[k][kin.wet]
        assert np.abs(got - ref).max() <= KINEMATICS_RTOL * np.abs(ref).max()


def test_prepare_interpolation_matches_exact_sum() -> None:
    """Coarse sampling + cubic Lagrange against the exact sum, within the interpolation
    remainder bound (9/16) (omega h)^4 / 24 |c| summed over components."""
    sea = WaveField.jonswap(6.0, 11.0, seed=1, duration=600.0, omega_min=0.3,
                            omega_max=2.0, depth=200.0)
    coef = MorisonCoefficients(column_transverse=1.0, heave_plate_transverse=1.0)
    exact = MorisonDrag(_two_columns(), DragSettings(coefficients=coef,
                                                     kinematics_interval=0.0), RHO, sea)
    auto = MorisonDrag(_two_columns(), DragSettings(coefficients=coef), RHO, sea)
    dt_half = 0.025
    m = auto.decimation(dt_half)
    h = m * dt_half
    assert m == math.floor(KINEMATICS_PHASE_STEP / 2.0 / dt_half + 1e-9) == 10
    exact.prepare(100.0, 401, dt_half)
    auto.prepare(100.0, 401, dt_half)
    amplitude = np.abs(exact._coef)  # (N, 3 n)
    bound = (9.0 / 16.0) * h ** 4 / 24.0 * (amplitude * sea.omega[:, None] ** 4).sum(axis=0)
    err = np.abs(auto.fluid_velocity - exact.fluid_velocity).reshape(401, -1).max(axis=0)
    assert np.all(err <= bound)
    scale = np.abs(exact.fluid_velocity).max()
    # measured 1.9e-4 of the largest velocity (Hs 6 m up to 2 rad/s, h = 0.25 s)
    assert err.max() < 1e-3 * scale


def test_prepare_ramp_and_force_index() -> None:
    sea = WaveField.regular(1.0, 8.0, depth=100.0)
    settings = DragSettings(coefficients=MorisonCoefficients(column_transverse=1.0))
    drag = MorisonDrag(_two_columns(), settings, RHO, sea)
    drag.prepare(0.0, 5, 0.1)
    full = drag.fluid_velocity.copy()
    drag.prepare(0.0, 5, 0.1, ramp=lambda t: 0.5)
    np.testing.assert_allclose(drag.fluid_velocity, 0.5 * full, rtol=1e-15)
    assert drag.index(0.3) == 3
    with pytest.raises(IndexError):
        drag.force(5, np.zeros(6), np.zeros(6))
    out = np.empty(6)
    assert drag.force(4, np.zeros(6), np.zeros(6), out=out) is out


# ------------------------------------------------------------------ settings
def test_settings_from_table_and_validation() -> None:
    s = DragSettings.from_settings({"preset": "deepcwind_oc4", "heave_plate_axial": 4.8,
                                    "strip_length": 1.0, "kinematics_interval": "auto"})
    assert s.coefficients.heave_plate_axial == 4.8
    assert s.coefficients.member_transverse == DEEPCWIND_OC4.member_transverse
    assert s.kinematics_interval is None and s.strip_length == 1.0
    assert DragSettings.from_settings({}).coefficients == MorisonCoefficients()
    bad = [({"preset": "oc5"}, "unknown preset"),
           ({"colum_transverse": 1.0}, "unknown key"),
           ({"column_transverse": -0.1}, "column_transverse"),
           ({"column_transverse": float("nan")}, "column_transverse"),
           ({"strip_length": 0.0}, "strip_length"),
           ({"min_strips": 0}, "min_strips"),
           ({"heave_plate_area": "ring"}, "heave_plate_area"),
           ({"kinematics_interval": -1.0}, "kinematics_interval")]
    for table, message in bad:
        with pytest.raises(ValueError, match=message):
            DragSettings.from_settings(table)


def test_buoy_case_has_no_drag_by_default() -> None:
    case = load_case(ROOT / "cases" / "cylinder_buoy" / "buoy_regular_T1.20.toml")
    drag = MorisonDrag(case.floater, DragSettings(), 1000.0)
    assert drag.strips.n == 0
    np.testing.assert_array_equal(drag.force_in(None, np.zeros(6), np.ones(6)), np.zeros(6))
    # with coefficients: the side below the draft and the bottom disc
    s = build_strips(case.floater, DragSettings(coefficients=MorisonCoefficients(
        column_transverse=1.0, column_axial=1.0)), 1000.0)
    g = case.floater.geometry
    assert s.submerged_length("column") == pytest.approx(g.draft, rel=1e-12)
    assert s.count("column") == MIN_STRIPS and s.count("column_axial") == 1
