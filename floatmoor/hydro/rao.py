"""Response amplitude operators (RAOs) of a moored floater from its hydrodynamic database.

The rigid-body motion amplitude X (per unit wave amplitude) solves, at every database
frequency omega and wave direction beta, the linear equation of motion in capytaine's
e^{-i omega t} convention (docs/theory/hydrodynamics.md#response-amplitude-operators):

    [-omega^2 (M + A(omega)) - i omega (B(omega) + B_ext) + C + K_moor] X = F_exc(omega, beta),

with M the rigid-body mass matrix about the rotation centre (:meth:`Floater.mass_matrix`),
A and B the database's added mass and radiation damping, C the hydrostatic and gravity
stiffness (:func:`floatmoor.hydro.radiation.hydrostatic_stiffness_total`), K_moor the
mooring's linearised stiffness at the rest position (the central difference of the
quasi-static lines used for the natural periods,
:func:`floatmoor.hydro.natural_periods.mooring_stiffness`) and B_ext an optional linear
damping matrix (the case has no key for one: the ``rao`` command takes it per DOF). The
matrices are indexed (influenced_dof, radiating_dof): row i is the force in DOF i from a
motion in DOF j.

Units of the RAO: m/m for Surge, Sway, Heave; rad/m for Roll, Pitch, Yaw. Their figure is
drawn by :func:`floatmoor.plots.rao.plot_rao`.
"""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.schema import Case, Floater
from floatmoor.hydro.radiation import hydrostatic_stiffness_total

__all__ = ["DOFS", "RAO_TITLE", "motion_matrices", "rao", "rao_for_case", "rao_dataset",
           "rao_units", "RAO_FILE"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
#: ``title`` attribute of a RAO file: what ``floatmoor rao`` may overwrite.
RAO_TITLE = "floatmoor response amplitude operators"


def rao_units() -> xr.DataArray:
    """Unit of each DOF's RAO (m/m or rad/m), indexed by ``radiating_dof``."""
    return xr.DataArray(["m/m"] * 3 + ["rad/m"] * 3, dims=("radiating_dof",),
                        coords={"radiating_dof": list(DOFS)})


def motion_matrices(ds: xr.Dataset, floater: Floater,
                    k_moor: NDArray[np.float64] | None = None) -> tuple[NDArray, NDArray]:
    """(M, C + K_moor), both (6, 6) indexed (influenced, radiating), about the rotation
    centre."""
    c = hydrostatic_stiffness_total(ds, floater)
    if k_moor is not None:
        c = c + np.asarray(k_moor, float)
    return floater.mass_matrix(), c


def rao(ds: xr.Dataset, floater: Floater, k_moor: NDArray[np.float64] | None = None,
        linear_damping: NDArray[np.float64] | None = None) -> xr.DataArray:
    """RAOs of the floater over the database's frequencies and wave directions.

    Parameters
    ----------
    ds
        A database holding ``excitation_force`` (read by
        :func:`floatmoor.hydro.database.read_database`: complex values merged).
    floater
        Mass properties.
    k_moor
        Mooring stiffness (6, 6) about the rotation centre [N/m, N, N m/rad], or None.
    linear_damping
        Extra linear damping B_ext (6, 6) [N s/m, N s, N m s/rad], or None.

    Returns
    -------
    xarray.DataArray
        Complex, dims (omega, wave_direction, radiating_dof); attribute ``units`` states the
        units of the translations and of the rotations (m/m, rad/m), ``long_name`` the
        phase convention.
    """
    from floatmoor.hydro.database import merge_complex

    omega = ds["omega"].values.astype(float)
    m, c = motion_matrices(ds, floater, k_moor)
    a = ds["added_mass"].transpose("omega", "influenced_dof", "radiating_dof").values
    b = ds["radiation_damping"].transpose("omega", "influenced_dof", "radiating_dof").values
    if linear_damping is not None:
        b = b + np.asarray(linear_damping, float)[None]
    exc = merge_complex(ds, "excitation_force")
    f = exc.transpose("omega", "wave_direction", "influenced_dof").values
    w = omega[:, None, None]
    h = -w * w * (m[None] + a) - 1j * w * b + c[None]
    x = np.linalg.solve(h[:, None], f[..., None])[..., 0]
    out = xr.DataArray(x, dims=("omega", "wave_direction", "radiating_dof"),
                       coords={"omega": omega,
                               "wave_direction": ds["wave_direction"].values,
                               "radiating_dof": list(DOFS)}, name="rao")
    out.attrs.update({"long_name": "response amplitude operator: rigid-body motion "
                      "amplitude per unit wave amplitude (e^{-i omega t} convention)",
                      "units": "m/m (Surge, Sway, Heave), rad/m (Roll, Pitch, Yaw)"})
    return out


def rao_for_case(case: Case, ds: xr.Dataset, *, mooring: bool = True,
                 linear_damping: NDArray[np.float64] | None = None
                 ) -> tuple[xr.DataArray, dict[str, Any]]:
    """RAOs of the case's floater with its lines' linearised stiffness (``mooring``), and the
    conditions they were computed with (mass matrix, stiffness, damping: JSON-ready).

    What ``floatmoor rao`` computes (docs/guide/rao_and_drift.md#raos-floatmoor-rao): the
    linear, frequency-domain motions, with the mooring as its stiffness about the rest
    position (central differences of the lines' static forces,
    :func:`floatmoor.hydro.natural_periods.mooring_stiffness`), without line dynamics or
    drag.

    Parameters
    ----------
    case
        A case with a ``[floater]``.
    ds
        The floater's database, with ``excitation_force``
        (:func:`floatmoor.hydro.database.load_for_case`).
    mooring
        Whether the lines' linearised stiffness is added (False: the floater free).
    linear_damping
        Extra linear damping B_ext (6, 6) about the rotation centre [N s/m, N s, N m s/rad],
        or None.

    Returns
    -------
    rao : xarray.DataArray
        Complex, dims (omega, wave_direction, radiating_dof) [m/m, rad/m]
        (:func:`rao`).
    conditions : dict
        ``case_file``, ``mass_matrix``, ``hydrostatic_and_gravity_stiffness``,
        ``mooring_stiffness``, ``mooring_lines``, ``linear_damping`` and
        ``matrix_layout``: the matrices as nested lists in SI units, for
        :func:`rao_dataset`'s attributes.

    Raises
    ------
    SolverError
        When a line has no static solution near its rest position (with ``mooring``).
    """
    from floatmoor.hydro.natural_periods import mooring_stiffness

    assert case.floater is not None
    k_moor = mooring_stiffness(case) if mooring and case.lines else np.zeros((6, 6))
    x = rao(ds, case.floater, k_moor, linear_damping)
    b_ext = np.zeros((6, 6)) if linear_damping is None else np.asarray(linear_damping, float)
    conditions = {
        "case_file": str(case.source),
        "mass_matrix": floater_matrix(case.floater.mass_matrix()),
        "hydrostatic_and_gravity_stiffness": floater_matrix(
            hydrostatic_stiffness_total(ds, case.floater)),
        "mooring_stiffness": floater_matrix(k_moor),
        "mooring_lines": [line.name for line in case.lines] if mooring else [],
        "linear_damping": floater_matrix(b_ext),
        "matrix_layout": "rows influenced_dof, columns radiating_dof, SI units, about the "
                         "rotation centre",
    }
    return x, conditions


def floater_matrix(m: NDArray[np.float64]) -> list[list[float]]:
    """A 6 x 6 matrix as nested lists (JSON)."""
    return [[float(v) for v in row] for row in np.asarray(m, float)]


def rao_dataset(x: xr.DataArray, conditions: dict[str, Any], ds: xr.Dataset) -> xr.Dataset:
    """A RAO as a netCDF-ready dataset: real and imaginary parts along ``complex``, amplitude
    and phase, with units and long names, and the conditions in the attributes.

    netCDF has no complex type, hence the ``complex`` dimension; the file's ``title``
    (:data:`RAO_TITLE`) is what lets ``floatmoor rao`` replace a RAO file of its own and no
    other file.

    Parameters
    ----------
    x
        The complex RAOs, dims (omega, wave_direction, radiating_dof) (:func:`rao`,
        :func:`rao_for_case`) [m/m, rad/m].
    conditions
        What they were computed with (:func:`rao_for_case`'s second answer), stored as
        the JSON attribute ``rao_conditions_json``.
    ds
        The database they come from: its ``database`` and ``inputs_hash`` attributes are
        recorded.

    Returns
    -------
    xarray.Dataset
        ``rao`` (complex, omega, wave_direction, radiating_dof), ``rao_amplitude``,
        ``rao_phase`` [rad] and ``rao_units``, with the period as a coordinate along
        omega [s].
    """
    from floatmoor._version import __version__

    values = x.values
    coords = {
        "omega": ("omega", x["omega"].values, {"long_name": "wave angular frequency",
                                                "units": "rad/s"}),
        "period": ("omega", 2.0 * np.pi / x["omega"].values, {"long_name": "wave period",
                                                              "units": "s"}),
        "wave_direction": ("wave_direction", x["wave_direction"].values,
                           {"long_name": "direction the waves travel towards, from +x "
                            "counter-clockwise", "units": "rad"}),
        "radiating_dof": ("radiating_dof", np.array(DOFS), {"long_name": "degree of freedom "
                                                            "of the motion", "units": "1"}),
        "complex": ("complex", np.array(["re", "im"]),
                    {"long_name": "real and imaginary parts (e^{-i omega t} convention)",
                     "units": "1"}),
    }
    units = "m/m (Surge, Sway, Heave), rad/m (Roll, Pitch, Yaw)"
    dims = ("omega", "wave_direction", "radiating_dof")
    out = xr.Dataset({
        "rao": (("complex",) + dims, np.stack([values.real, values.imag]),
                {"long_name": "response amplitude operator (motion per unit wave amplitude)",
                 "units": units}),
        "rao_amplitude": (dims, np.abs(values), {"long_name": "RAO amplitude",
                                                 "units": units}),
        "rao_phase": (dims, np.angle(values), {"long_name": "RAO phase (motion lags the wave "
                                               "crest at the rotation centre by minus this, "
                                               "e^{-i omega t})", "units": "rad"}),
        "rao_units": (("radiating_dof",), rao_units().values,
                      {"long_name": "unit of each DOF's RAO"}),
    }, coords=coords)
    out.attrs.update({
        "title": RAO_TITLE,
        "floatmoor_version": __version__,
        "database": str(ds.attrs.get("database", "")),
        "database_inputs_hash": str(ds.attrs.get("inputs_hash", "")),
        "rao_conditions_json": json.dumps(conditions),
        "time_convention": "e^{-i omega t}",
    })
    return out


def _is_rao_file(path) -> str | None:
    from floatmoor.io.output_kinds import netcdf_content

    try:
        from floatmoor.io.netcdf3_reader import read_attributes_netcdf3

        attrs = read_attributes_netcdf3(path)
    except Exception:  # noqa: BLE001 - any unreadable file is not a RAO file
        return netcdf_content(path)
    return None if attrs.get("title") == RAO_TITLE else netcdf_content(path)


#: ``kind`` of :func:`floatmoor.io.output_files.check_output_file` for a RAO file.
RAO_FILE = ("RAO file", (b"CDF\x01", b"CDF\x02"), _is_rao_file)
