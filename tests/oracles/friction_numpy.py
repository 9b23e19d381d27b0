"""NumPy oracle of the stick-spring seabed friction (docs/theory/cable.md#seabed-friction),
written from the page's equations, vectorised over nodes.

f = k_s d if k_s |d| <= mu N, else mu N d / |d|; d = anchor - x (horizontal), N = k_b (z_b - z)
below the seabed. Return mapping at a committed step: the anchor of a sliding node moves to
x + (mu N / k_s) d / |d|; off the seabed the anchor is the node's position.
"""

from __future__ import annotations

import numpy as np

Array = np.ndarray


def force(d: Array, cap: Array, ks: float) -> Array:
    """Friction force per length (..., 2) for displacements d (..., 2) and caps mu N (...)."""
    trial = ks * d
    mag = np.linalg.norm(trial, axis=-1)
    scale = np.where(mag > cap, cap / np.where(mag > 0.0, mag, 1.0), 1.0)
    return trial * scale[..., None]


def tangent(d: Array, cap: Array, ks: float, mu_kb: float) -> Array:
    """-df/d(x, y, z) (..., 2, 3) of :func:`force` with cap = mu k_b (z_b - z)."""
    out = np.zeros(d.shape[:-1] + (2, 3))
    dl = np.linalg.norm(d, axis=-1)
    slip = ks * dl > cap
    u = d / np.where(dl > 0.0, dl, 1.0)[..., None]
    eye = np.eye(2)
    lateral = (cap / np.where(dl > 0.0, dl, 1.0))[..., None, None] * (
        eye - u[..., :, None] * u[..., None, :])
    out[..., :2, :2] = np.where(slip[..., None, None], lateral, ks * eye)
    out[..., :, 2] = np.where(slip[..., None], mu_kb * u, 0.0)
    return out


def return_map(r: Array, anchors: Array, ks: float, mu_kb: float, z_b: float) -> Array:
    """The anchors (..., 2) after a committed step at positions r (..., 3)."""
    x = r[..., :2]
    bed = r[..., 2] < z_b
    cap = mu_kb * np.maximum(z_b - r[..., 2], 0.0)
    d = anchors - x
    dl = np.linalg.norm(d, axis=-1)
    slip = ks * dl > cap
    moved = x + (cap / (ks * np.where(dl > 0.0, dl, 1.0)))[..., None] * d
    out = np.where(slip[..., None], moved, anchors)
    return np.where(bed[..., None], out, x)
