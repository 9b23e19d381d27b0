"""MacCamy-Fuchs diffraction by a bottom-mounted vertical circular cylinder in finite depth,
and its mean drift force (docs/theory/hydrodynamics.md#mean-wave-drift).

On the wall r = R the total potential of a unit-amplitude wave travelling towards +x is
(e^{-i omega t}, capytaine's incident potential -i g / omega cosh k(z+h) / cosh kh e^{ikx})

    phi(R, theta, z) = -i g / omega Z(z) sum_m eps_m i^m 2 i / (pi k R H_m'(kR)) cos m theta,

Z = cosh k(z+h) / cosh kh, eps_0 = 1, eps_m = 2 (the Wronskian of J_m and H_m removes J_m).
The wall is fixed, so the mean drift is Pinkster's waterline and velocity terms alone:

    F = -rho g / 4 oint |zeta|^2 n R dtheta + rho / 4 int int (|phi_theta / R|^2 + |phi_z|^2) n R dtheta dz,

the z integrals in closed form, the theta integrals by the trapezoidal rule (exact for the
trigonometric polynomials of the truncated series). Short-wave limit: 2/3 rho g R per unit
amplitude squared (Faltinsen 1990, ch. 5) as kR and kh grow.
"""

from __future__ import annotations

import numpy as np
from scipy.special import hankel1, h1vp


def maccamy_fuchs_drift(k: float, radius: float, depth: float, *, rho: float = 1000.0,
                        g: float = 9.81, terms: int | None = None, parts: bool = False):
    """Mean surge drift force per unit wave amplitude squared [N/m^2] (``parts``: the
    waterline and velocity terms)."""
    kr = k * radius
    m_max = terms if terms is not None else int(kr + 30)
    m = np.arange(m_max + 1)
    eps = np.where(m == 0, 1.0, 2.0)
    coef = eps * (1j ** m) * 2j / (np.pi * kr * h1vp(m, kr))  # zeta(theta) = sum coef cos m theta
    n_theta = 8 * m_max + 16
    theta = np.linspace(0.0, 2.0 * np.pi, n_theta, endpoint=False)
    cos_m = np.cos(np.outer(m, theta))
    sin_m = np.sin(np.outer(m, theta))
    zeta = coef @ cos_m                    # elevation on the wall at z = 0 (unit amplitude)
    dzeta = -(coef * m) @ sin_m            # d zeta / d theta
    omega2 = g * k * np.tanh(k * depth)
    kh = k * depth
    # phi = -i g / omega Z(z) zeta(theta); |phi|^2 scale (g / omega)^2
    th = np.tanh(kh)
    sech2 = 1.0 - th * th  # 1 / cosh^2 kh, without overflow in deep water
    z_cc = depth / 2.0 * sech2 + th / (2.0 * k)  # int Z^2 dz over (-h, 0)
    z_ss = k * k * (th / (2.0 * k) - depth / 2.0 * sech2)  # int Z'^2 dz
    dtheta = 2.0 * np.pi / n_theta
    nx = np.cos(theta)
    waterline = -0.25 * rho * g * np.sum(np.abs(zeta) ** 2 * nx) * radius * dtheta
    scale = g * g / omega2
    velocity = 0.25 * rho * scale * np.sum(
        (np.abs(dzeta / radius) ** 2 * z_cc + np.abs(zeta) ** 2 * z_ss) * nx) * radius * dtheta
    if parts:
        return float(waterline), float(velocity)
    return float(waterline + velocity)
