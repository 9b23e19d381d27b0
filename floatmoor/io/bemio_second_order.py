"""The mean drift of a WEC-Sim BEMIO ``.h5`` (read with :func:`floatmoor.io.bemio.read_bemio`).

Layout (WEC-Sim's ``writeBEMIOH5.m``; shapes as h5py reads them, ``Nh`` wave directions and
``Nf`` frequencies as the excitation's)::

    /bodyN/hydro_coeffs/mean_drift/momentum_conservation/val   (6, Nh, Nf)  F / (rho g)
    /bodyN/hydro_coeffs/mean_drift/control_surface/val         (6, Nh, Nf)  (not imported)
    /bodyN/hydro_coeffs/mean_drift/pressure_integration/val    (6, Nh, Nf)  F / (rho g)

BEMIO's ``readWAMIT`` fills ``md_mc`` / ``md_cs`` / ``md_pi`` with WAMIT's printed mean drift,
``Mod cos(Pha)``, which WAMIT normalises by rho g A^2 L^k (BEMIO takes ULEN = 1), and
``normalizeBEM`` divides other codes' by rho g: the stored values times rho g are the drift
per unit wave amplitude squared [N/m^2, N m/m^2] about the body's ``cg``. The modes the
momentum route does not give (Heave, Roll, Pitch: BEMIO writes 0) are NaN in floatmoor's far
field. The control-surface route and BEMIO's QTF groups (``excitation/QTF<N>/Diff<k>``,
``Sum<k>``) are not imported: a note says so. BEMIO's QTF layout cannot be read safely
(one wave direction; the periods of the source ``.12d``'s two columns numbered separately by
order of appearance, so the matrix's orientation depends on that file's line order:
docs/guide/hydro_databases.md#imported-second-order-data); the ``.12d`` itself can be imported.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

from floatmoor.io.bem_data import SecondOrder

__all__ = ["read_bemio_mean_drift", "BEMIO_DRIFT_ROUTES"]


class _Datasets(Protocol):
    """What this reader asks of the open file (:mod:`floatmoor.io.bemio`'s strict access)."""

    name: str

    def has(self, where: str) -> bool: ...

    def has_group(self, where: str) -> bool: ...

    def array(self, where: str, what: str, shape: tuple[int, ...]) -> NDArray[np.float64]: ...

#: BEMIO's mean drift groups, the floatmoor variable each goes to and the route's name.
BEMIO_DRIFT_ROUTES = (("momentum_conservation", "far_field", "momentum conservation"),
                      ("pressure_integration", "near_field", "pressure integration"))


def read_bemio_mean_drift(file: _Datasets, body: int, shape: tuple[int, int, int],
                          order: NDArray[np.int64], dir_order: NDArray[np.int64],
                          rho_g: float) -> SecondOrder | None:
    """The body's mean drift, SI, (omega sorted, direction sorted, DOF), or None when the
    file has none.

    Parameters
    ----------
    file
        The open BEMIO file (strict dataset access of :mod:`floatmoor.io.bemio`).
    body
        The body number.
    shape
        (6, Nh, Nf): the excitation's shape, which the drift must have.
    order, dir_order
        The sorting of the file's frequencies and directions (as the excitation's).
    rho_g
        rho g [N/m^3] that makes the normalised values dimensional.

    Raises
    ------
    BemFileError
        A drift dataset of another shape or type, or with NaN or inf.
    """
    base = f"/body{body}/hydro_coeffs/"
    found: dict[str, NDArray[np.float64]] = {}
    sources: dict[str, str] = {}
    for group, route, label in BEMIO_DRIFT_ROUTES:
        where = f"{base}mean_drift/{group}/val"
        if not file.has(where):
            continue
        values = file.array(where, f"mean drift ({label}) / (rho g)", shape)
        drift = np.transpose(values, (2, 1, 0))[order][:, dir_order, :] * rho_g
        if route == "far_field":
            drift[..., 2:5] = np.nan  # the momentum route gives Surge, Sway and Yaw only
        found[route] = drift
        sources[route] = f"{file.name}:{where} (BEMIO, {label})"
    notes = []
    if file.has(f"{base}mean_drift/control_surface/val"):
        notes.append(f"{file.name}: {base}mean_drift/control_surface not imported (the "
                     "database holds the momentum and pressure routes).")
    if file.has_group(f"{base}excitation/QTF{body}"):
        notes.append(f"{file.name}: {base}excitation/QTF{body} (BEMIO's QTFs) not imported "
                     "(their layout depends on the source .12d's line order: import that "
                     ".12d with the WAMIT files).")
    if not found:
        return SecondOrder(source="bemio", notes=tuple(notes)) if notes else None
    for route in found:
        notes.append(f"Mean drift {sources[route]} x rho g = {rho_g:g} N/m^3.")
    return SecondOrder(source="bemio", far_field=found.get("far_field"),
                       far_field_from=sources.get("far_field", ""),
                       near_field=found.get("near_field"),
                       near_field_from=sources.get("near_field", ""), notes=tuple(notes))
