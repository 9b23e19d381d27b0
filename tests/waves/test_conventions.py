"""The phase convention against capytaine 3 itself (e^{-i omega t}, waves towards beta).

capytaine's incident wave (capytaine/bem/airy_waves.py) and its Froude-Krylov force are the
reference: our complex elevation and velocity amplitudes must equal capytaine's, and a force
Re{X A e^{-i omega t}} built from capytaine's X must have the physically right phase relative to
our elevation and kinematics. A conjugated convention fails every test here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.waves.excitation_series import WaveExcitation
from floatmoor.waves.kinematics import airy_kinematics
from floatmoor.waves.realisation import WaveField

cpt = pytest.importorskip("capytaine")
airy = pytest.importorskip("capytaine.bem.airy_waves")

G = 9.81
RHO = 1025.0
#: Two implementations of the same closed form; capytaine's wavenumber solver and ours agree
#: to ~1e-12, so amplitudes agree to that.
CROSS_CODE_RTOL = 1e-9


@pytest.fixture(scope="module")
def body():
    """A vertical cylinder, radius 0.5 m, draft 3 m, hull only (no lid): cheap Froude-Krylov."""
    mesh = cpt.mesh_vertical_cylinder(length=4.0, radius=0.5, center=(0, 0, -1.0),
                                      resolution=(4, 16, 16)).immersed_part()
    return cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)))


def test_crest_reaches_quarter_wavelength_a_quarter_period_later():
    period = 8.0
    field = WaveField.regular(2.0, period, direction=0.0, depth=math.inf, gravity=G)
    lam = 2 * np.pi / field.wavenumber[0]
    t = np.linspace(0.0, period, 80001)
    assert t[np.argmax(field.elevation(t, 0.0, 0.0))] == pytest.approx(0.0, abs=1e-9)
    assert t[np.argmax(field.elevation(t, lam / 4, 0.0))] == pytest.approx(period / 4,
                                                                           abs=t[1])
    # waves towards +y for beta = 90 deg
    field_y = WaveField.regular(2.0, period, direction=np.pi / 2, gravity=G)
    assert t[np.argmax(field_y.elevation(t, 0.0, lam / 4))] == pytest.approx(period / 4,
                                                                             abs=t[1])


@pytest.mark.parametrize("depth", [15.0, math.inf])
@pytest.mark.parametrize("beta", [0.0, 0.6])
def test_elevation_and_velocity_amplitudes_equal_capytaines(body, depth, beta):
    omega = 0.9
    field = WaveField.from_components([omega], [1.0], [0.0], [beta], depth, G)
    pb = cpt.DiffractionProblem(body=body, omega=omega, wave_direction=beta,
                                water_depth=depth, g=G, rho=RHO)
    assert float(pb.wavenumber) == pytest.approx(field.wavenumber[0], rel=1e-10)
    lam = 2 * np.pi / field.wavenumber[0]
    xy = np.array([[0.0, 0.0], [lam / 4, 0.0], [0.0, lam / 4], [3.0, -7.0]])
    eta_cpt = airy.airy_waves_free_surface_elevation(xy, pb)
    np.testing.assert_allclose(field.complex_elevation(xy[:, 0], xy[:, 1])[:, 0], eta_cpt,
                               rtol=CROSS_CODE_RTOL)
    points = np.column_stack([xy, [-1.0, -2.5, -5.0, -12.0]])
    v_cpt = airy.airy_waves_velocity(points, pb)  # complex amplitudes, e^{-i omega t}
    for t in (0.0, 0.25 * 2 * np.pi / omega, 1.234):
        ours = airy_kinematics(field, points, t, "none").velocity
        np.testing.assert_allclose(ours, (v_cpt * np.exp(-1j * omega * t)).real,
                                   rtol=0, atol=CROSS_CODE_RTOL * np.abs(v_cpt).max())


def test_froude_krylov_force_phase_from_capytaine(body):
    """With capytaine's X: the heave force of a long wave peaks with the crest at the body
    (hydrostatics, X3 ~ rho g A_wp > 0) and the surge force follows the fluid's horizontal
    acceleration at the body (X1 ~ -i |X1|: it leads the elevation by a quarter period)."""
    omega, period = 0.3, 2 * np.pi / 0.3
    pb = cpt.DiffractionProblem(body=body, omega=omega, wave_direction=0.0,
                                water_depth=math.inf, g=G, rho=RHO)
    fk = airy.froude_krylov_force(pb)
    x = np.array([[fk["Surge"], fk["Heave"]]])
    field = WaveField.regular(2.0, period, phase=0.7, depth=math.inf, gravity=G)
    force = WaveExcitation(field, x)
    t = np.linspace(0.0, 2 * period, 2001)
    f = force.series(t)
    eta = field.elevation(t)
    area = np.pi * 0.5 ** 2
    assert np.corrcoef(f[:, 1], eta)[0, 1] > 0.999
    assert np.max(f[:, 1]) == pytest.approx(RHO * G * area * 1.0, rel=0.1)  # polygonal mesh
    acc = np.array([airy_kinematics(field, [[0.0, 0.0, -1.5]], ti, "none").acceleration[0, 0]
                    for ti in t[::20]])
    assert np.corrcoef(f[::20, 0], acc)[0, 1] > 0.999


def test_wamit_form_is_the_conjugate_convention():
    """The WAMIT-style form (docs/conventions.md): Re{X_W a e^{i(omega t + phi)}} with X_W = conj(X) (WAMIT) is our
    Re{X a e^{-i phi} e^{-i omega t}}: the same signal with the phase sign flipped."""
    x = np.array([[3.0 - 4.0j]])
    omega, a, phi = 0.8, 1.2, 0.5
    t = np.linspace(0, 30, 301)
    wamit_form = (np.conj(x[0, 0]) * a * np.exp(1j * (omega * t + phi))).real
    ours = WaveExcitation(WaveField.from_components([omega], [a], [-phi], gravity=G), x)
    np.testing.assert_allclose(ours.series(t)[:, 0], wamit_form, atol=1e-12)
    # using capytaine's X directly in that formula is a different (wrong) signal
    assert np.abs((x[0, 0] * a * np.exp(1j * (omega * t + phi))).real - wamit_form).max() > 1
