"""The floating body of a case: its Cummins equation from the case's mass properties and the
floater's hydrodynamic database (docs/theory/floater.md)."""

from __future__ import annotations

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.body.cummins import CumminsBody
from floatmoor.body.state_space_radiation import RadiationStates
from floatmoor.case.schema import RADIATION_METHODS, Environment, Floater
from floatmoor.errors import CaseError
from floatmoor.hydro.radiation import (
    consistent_infinite_added_mass, hydrostatic_stiffness_total, kernel_samples,
    radiation_kernel, truncation_time,
)
from floatmoor.hydro.state_space.realisation import StateSpaceRadiation

__all__ = ["static_force", "build_body", "consistent_infinite_added_mass", "KERNEL_SUBSTEPS",
           "KERNEL_START_SUBSTEPS", "MAX_KERNEL_SAMPLES",
           "radiation_states_of", "checked_state_space", "state_space_infinite_added_mass"]

#: Fine samples of K(t) per body step for the memory weights (the kernel's peak at t = 0 of
#: slowly decaying surge and pitch damping is a few body steps wide at T / 60).
KERNEL_SUBSTEPS = 10
#: Fine samples of K(t) per body step over [0, 2 dt], for the two weights whose hats reach
#: t = 0 (:func:`floatmoor.body._memory_kernels.hat_weights`, ``start``): DeepCwind's surge
#: kernel (tail exponent 1.2) has a cusp there; its W_0 at dt = 0.1 s converges to 1e-5 at
#: 100 samples per step and 3e-6 at 200 (against 1.3 % at :data:`KERNEL_SUBSTEPS`).
KERNEL_START_SUBSTEPS = 200
#: Most samples of K(t) (truncation time / (time step / KERNEL_SUBSTEPS)), counted before they
#: are allocated: each is 36 doubles and a term of every body step's convolution. The shipped
#: cases take 15 700 to 31 400; 2 million (0.6 GB of kernel) is 60 times that, while a 1e-9 s
#: step on the buoy asked for 3e11 (2.3 TiB).
MAX_KERNEL_SAMPLES = 2_000_000


def static_force(floater: Floater, ds: xr.Dataset, environment: Environment
                 ) -> NDArray[np.float64]:
    """F_0: buoyancy rho g V at the centre of buoyancy minus the weight m g at the centre of
    mass, as forces and moments about the rotation centre, at the rest position (6,)."""
    g = environment.gravity
    rc = ds["rotation_center"].values
    buoyancy = environment.water_density * g * float(ds["disp_volume"].values)
    weight = floater.mass * g
    rb = ds["center_of_buoyancy"].values - rc
    rg = np.subtract(floater.centre_of_mass, rc)
    f = np.zeros(6)
    f[2] = buoyancy - weight
    # r x (0, 0, Fz) = (r_y Fz, -r_x Fz, 0)
    f[3] = rb[1] * buoyancy - rg[1] * weight
    f[4] = -(rb[0] * buoyancy - rg[0] * weight)
    return f


def state_space_infinite_added_mass(ds: xr.Dataset, realisation: StateSpaceRadiation
                                    ) -> NDArray[np.float64]:
    """A_inf consistent with the realisation and the BEM added mass over the band (6, 6):
    the mean over the BEM frequencies of A(w) - (A_fit(w) - A_inf), the state-space form of
    :func:`consistent_infinite_added_mass` (A_fit - A_inf = Im H(i w) / w of the
    realisation; zero for the pairs without memory, as K is there)."""
    omega = ds["omega"].values
    added = ds["added_mass"].transpose("omega", "radiating_dof", "influenced_dof").values
    shape, _ = realisation.frequency_response(omega)
    return (added - shape).mean(axis=0)


def radiation_states_of(ds: xr.Dataset, dt: float) -> RadiationStates:
    """The database's stored state-space realisation packed for a body step ``dt``.

    Raises
    ------
    HydroDatabaseError
        See :func:`checked_state_space`.
    """
    return RadiationStates.from_pairs(
        [(p.radiating, p.influenced, p.a, p.b, p.c) for p in checked_state_space(ds).pairs],
        dt)


def checked_state_space(ds: xr.Dataset) -> StateSpaceRadiation:
    """The database's stored realisation, checked to belong to its K(t).

    Raises
    ------
    HydroDatabaseError
        No realisation in the database, a damaged one, or one fitted from another K(t)
        (:func:`floatmoor.hydro.state_space.fit.stale_reasons`).
    """
    from floatmoor.hydro.database import HydroDatabaseError
    from floatmoor.hydro.state_space.fit import stale_reasons
    from floatmoor.hydro.state_space.storage import read_state_space

    where = ds.attrs.get("path", ds.attrs.get("database", "the database"))
    realisation = read_state_space(ds)
    if realisation is None:
        raise HydroDatabaseError(f"{where}: no state-space realisation of the radiation (add "
                                 "one with 'floatmoor hydro fit-state-space NAME')")
    reasons = stale_reasons(ds, realisation)
    if reasons:
        raise HydroDatabaseError(f"{where}: stale state-space realisation, fitted from another "
                                 f"K(t): {'; '.join(reasons)}; refit with 'floatmoor hydro "
                                 "fit-state-space NAME'")
    return realisation


def build_body(floater: Floater, ds: xr.Dataset, environment: Environment, dt: float, *,
               extra_stiffness: NDArray[np.float64] | None = None,
               linear_damping: NDArray[np.float64] | None = None,
               quadratic_damping: NDArray[np.float64] | None = None,
               kernel_time: float | None = None,
               infinite_added_mass: str = "kramers-kronig",
               radiation: str | None = None) -> CumminsBody:
    """The Cummins body of ``floater`` with its database ``ds`` at time step ``dt``.

    Parameters
    ----------
    floater
        The case's floater (mass properties, reference point, radiation choice).
    ds
        Its hydrodynamic database.
    environment
        Water density and gravity.
    dt
        The body's time step [s].
    extra_stiffness
        C (6, 6) added to the hydrostatic stiffness (e.g. a linearised mooring), or None.
    linear_damping, quadratic_damping
        B_1, B_2 (6, 6) or None (:class:`~floatmoor.body.cummins.CumminsBody`).
    kernel_time
        Truncation time of K(t) [s] (default: the database's, radiation.truncation_time).
    infinite_added_mass
        ``"kramers-kronig"`` (:func:`consistent_infinite_added_mass`, or
        :func:`state_space_infinite_added_mass` on the state-space path) or ``"bem"`` (the
        database's A_inf).
    radiation
        ``"convolution"`` or ``"state-space"`` (the database's stored realisation,
        :func:`radiation_states_of`); None: the floater's.

    Returns
    -------
    CumminsBody
        The body.
    """
    radiation = floater.radiation if radiation is None else radiation
    if radiation not in RADIATION_METHODS:
        raise ValueError(f"radiation: one of {RADIATION_METHODS}, got {radiation!r}")
    if infinite_added_mass not in ("kramers-kronig", "bem"):
        raise ValueError(f"infinite_added_mass: 'kramers-kronig' or 'bem', got "
                         f"{infinite_added_mass!r}")
    states, kernel_start = None, None
    if radiation == "state-space":
        if kernel_time is not None:
            raise ValueError("kernel_time: the state-space realisation was fitted over the "
                             "database's own truncation time")
        realisation = checked_state_space(ds)
        states = RadiationStates.from_pairs(
            [(p.radiating, p.influenced, p.a, p.b, p.c) for p in realisation.pairs], dt)
        if infinite_added_mass == "kramers-kronig":
            a_inf = state_space_infinite_added_mass(ds, realisation)
        else:
            a_inf = ds["added_mass_infinite"].transpose("radiating_dof",
                                                        "influenced_dof").values
    else:
        t_max = truncation_time(ds["omega"].values) if kernel_time is None else kernel_time
        samples = t_max / (dt / KERNEL_SUBSTEPS)
        if not samples <= MAX_KERNEL_SAMPLES:  # the CLI names the case file
            raise CaseError("", "simulation.time_step", f"a body step giving at most "
                            f"{MAX_KERNEL_SAMPLES:.3g} samples of the radiation kernel over its "
                            f"{t_max:.4g} s ({KERNEL_SUBSTEPS} a step; floatmoor.body.model."
                            "MAX_KERNEL_SAMPLES) [s]", f"{dt!r} (~{samples:.3g} samples)")
        kernel = radiation_kernel(ds, dt=dt / KERNEL_SUBSTEPS, t_max=kernel_time)
        t_start = np.linspace(0.0, 2.0 * dt, 2 * KERNEL_START_SUBSTEPS + 1)
        kernel_start = (t_start, kernel_samples(ds, t_start, kernel.tail_exponent))
        if infinite_added_mass == "kramers-kronig":
            a_inf = consistent_infinite_added_mass(ds, kernel.time, kernel.kernel)
        else:
            a_inf = kernel.added_mass_infinite
    stiffness = hydrostatic_stiffness_total(ds, floater)
    if extra_stiffness is not None:
        stiffness = stiffness + extra_stiffness
    return CumminsBody(floater.mass_matrix(), a_inf, stiffness,
                       static_force(floater, ds, environment),
                       None if states is not None else (kernel.time, kernel.kernel), dt,
                       linear_damping=linear_damping, quadratic_damping=quadratic_damping,
                       radiation_states=states, kernel_start=kernel_start)
