"""Hydrostatics of a hull mesh: displaced volume, centre of buoyancy, waterplane properties
and the hydrostatic (buoyancy) stiffness about a rotation centre.

Every quantity is an integral over the wetted hull of n_z times a polynomial of degree <= 2,
by the divergence theorem (the waterplane closes the hull at z = 0):

    V = int z n_z dS,  V x_B = int x z n_z dS,  V z_B = int z^2/2 n_z dS,
    int_wp f(x, y) dA = -int f n_z dS.

Panels are planar triangles or quads (split into two triangles); the edge-midpoint rule
integrates the quadratic integrands exactly on each triangle, so the results are exact for the
polyhedral hull (the test of the cylinder compares them with the inscribed polygon prism to
1e-6). Using only n_z-weighted integrals has a second benefit: gaps left on vertical walls
where a member joins a column (floatmoor.hydro.geometry) have n_z = 0 and change nothing.
(capytaine's own hydrostatics use one quadrature point per panel, exact for C33 and V but not
for the waterplane second moments: -0.75 % in C44 of the case-C buoy's buoyancy part.)

The stiffness is the hull's alone, as if the centre of mass were at the rotation centre c
(capytaine's convention with ``center_of_mass = c``):

    C33 = rho g A_wp,   C34 = rho g int_wp (y - yc),   C35 = -rho g int_wp (x - xc),
    C44 = rho g (int_wp (y - yc)^2 + V (z_B - zc)),   C55 = rho g (int_wp (x - xc)^2 + V (z_B - zc)),
    C45 = -rho g int_wp (x - xc)(y - yc),   C46 = -rho g V (x_B - xc),   C56 = -rho g V (y_B - yc),

with C43 = C34, C53 = C35, C54 = C45; the weight terms are added by
:func:`floatmoor.hydro.radiation.hydrostatic_stiffness_total`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["hull_hydrostatics"]


def _triangles(mesh) -> NDArray[np.float64]:
    """(n, 3, 3) triangles of a capytaine mesh (quads split along a diagonal)."""
    merged = mesh.merged() if hasattr(mesh, "merged") else mesh
    v = np.asarray(merged.vertices, dtype=float)
    f = np.asarray(merged.faces, dtype=int)  # triangles padded by repeating the last vertex
    first = v[f[:, [0, 1, 2]]]
    quads = f[:, 3] != f[:, 2]
    second = v[f[quads][:, [0, 2, 3]]]
    return np.concatenate([first, second])


def hull_hydrostatics(mesh, *, rho: float, g: float,
                      rotation_center: NDArray[np.float64] | tuple[float, float, float]
                      ) -> dict[str, object]:
    """Hydrostatics of the wetted hull ``mesh`` (outward normals, z <= 0).

    Returns
    -------
    dict with ``disp_volume`` [m^3], ``center_of_buoyancy`` (3,) [m], ``waterplane_area``
    [m^2], ``waterplane_center`` (2,) [m] and ``hydrostatic_stiffness`` (6, 6) indexed
    (influenced, radiating) as capytaine's, about ``rotation_center``.
    """
    tri = _triangles(mesh)
    c = np.asarray(rotation_center, dtype=float)
    area_vector = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    nz_da = area_vector[:, 2]
    mids = 0.5 * (tri + np.roll(tri, -1, axis=1))  # (n, 3 midpoints, 3)
    x, y, z = mids[..., 0], mids[..., 1], mids[..., 2]

    def integral(values: NDArray[np.float64]) -> float:
        """int f n_z dS with f sampled at the 3 edge midpoints of each triangle."""
        return float(np.sum(nz_da * values.mean(axis=1)))

    volume = integral(z)
    cob = np.array([integral(x * z), integral(y * z), integral(0.5 * z * z)]) / volume
    dx, dy = x - c[0], y - c[1]
    awp = -integral(np.ones_like(x))
    sx, sy = -integral(dx), -integral(dy)
    ixx, iyy, ixy = -integral(dy * dy), -integral(dx * dx), -integral(dx * dy)
    k = np.zeros((6, 6))
    rg = rho * g
    k[2, 2] = rg * awp
    k[2, 3] = k[3, 2] = rg * sy
    k[2, 4] = k[4, 2] = -rg * sx
    k[3, 3] = rg * (ixx + volume * (cob[2] - c[2]))
    k[4, 4] = rg * (iyy + volume * (cob[2] - c[2]))
    k[3, 4] = k[4, 3] = -rg * ixy
    k[3, 5] = -rg * volume * (cob[0] - c[0])
    k[4, 5] = -rg * volume * (cob[1] - c[1])
    return {
        "disp_volume": volume,
        "center_of_buoyancy": cob,
        "waterplane_area": awp,
        "waterplane_center": np.array([sx, sy]) / awp + c[:2],
        "hydrostatic_stiffness": k,
    }
