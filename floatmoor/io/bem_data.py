"""BEM results read from another program's files, before they become a floatmoor database.

The importers (:mod:`floatmoor.io.wamit`, :mod:`floatmoor.io.bemio`) return an
:class:`ImportedBem`: dimensional SI values in floatmoor's (capytaine's) layout and
conventions, whatever the file's own (WAMIT's non-dimensional values and e^{+i omega t}
phases, BEMIO's normalised values). :mod:`floatmoor.hydro.importing` turns it into a
database. A file that cannot be read as its format says raises :class:`BemFileError`, which
names the file, where in it, what was expected and what was found.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.errors import FloatmoorError

__all__ = ["ImportedBem", "SecondOrder", "BemFileError", "DOFS"]

#: Rigid-body DOFs in capytaine's names and order (rotations about the rotation centre).
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


class BemFileError(FloatmoorError, ValueError):
    """A BEM result file is missing, malformed or inconsistent with the others given.

    The message reads ``FILE: WHERE: expected ..., found ...`` (``WHERE`` a line number, an
    HDF5 path or a quantity), like :class:`floatmoor.errors.CaseError`.
    """

    def __init__(self, path: str, where: str, expected: str, found: str) -> None:
        self.path, self.where, self.expected, self.found = path, where, expected, found
        at = f"{path}: {where}" if where else str(path)
        super().__init__(f"{at}: expected {expected}, found {found}")


@dataclass(frozen=True)
class SecondOrder:
    """Second-order wave loads read from another program's files, dimensional, SI,
    e^{-i omega t} (the layout of docs/guide/hydro_databases.md#imported-second-order-data).

    Mean drift arrays are (omega, wave_direction, DOF) on the first-order data's frequencies
    and directions, per unit wave amplitude squared [N/m^2, N m/m^2], about the file's
    reference point; the far field (momentum route) is NaN for Heave, Roll and Pitch. The QTF
    is (direction, omega_1, omega_2, DOF), Hermitian in (omega_1, omega_2), with
    F(t) = Re sum_i sum_j A_i conj(A_j) Q(omega_i, omega_j) e^{-i (omega_i - omega_j) t} over
    all ordered pairs of the sea's complex amplitudes A (capytaine's convention).

    Attributes
    ----------
    source
        ``"wamit"`` or ``"bemio"``.
    far_field, far_field_from
        Momentum-route mean drift and where it came from (file and route), or None.
    near_field, near_field_from
        Pressure-route mean drift (all six DOFs) and where it came from, or None.
    qtf_omega, qtf_directions, qtf_difference, qtf_from
        The difference-frequency QTF's own frequencies [rad/s] (ascending), unidirectional
        wave directions [rad], values and where they came from; None without a QTF.
    notes
        What the reader did that a user should know.
    """

    source: str
    far_field: NDArray[np.float64] | None = None
    far_field_from: str = ""
    near_field: NDArray[np.float64] | None = None
    near_field_from: str = ""
    qtf_omega: NDArray[np.float64] | None = None
    qtf_directions: NDArray[np.float64] | None = None
    qtf_difference: NDArray[np.complex128] | None = None
    qtf_from: str = ""
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class ImportedBem:
    """One rigid body's linear hydrodynamic coefficients, dimensional, SI, e^{-i omega t}.

    Index conventions are those of floatmoor's databases: ``added_mass[w, j, i]`` is the
    force in DOF i (influenced) per acceleration of DOF j (radiating); excitation arrays are
    (omega, wave_direction, influenced DOF) per unit wave amplitude; ``hydrostatic_stiffness
    [i, j]`` is the force in DOF i per displacement of DOF j. DOFs are :data:`DOFS` about
    ``rotation_center``. Optional parts a format does not carry are None.

    Attributes
    ----------
    format
        ``"wamit"`` or ``"bemio"``.
    files
        The files read (as given), in the order read.
    omega
        (n,) finite frequencies, positive and increasing [rad/s].
    added_mass, radiation_damping
        (n, 6, 6) [kg, kg m, kg m^2] and [kg/s, kg m/s, kg m^2/s].
    added_mass_infinite, added_mass_zero
        (6, 6) A at omega = infinity / 0 where the file gives them (WAMIT PER = 0 / -1).
    directions
        (m,) wave propagation directions [rad], from +x counter-clockwise; None without
        excitation.
    excitation_force, froude_krylov_force, diffraction_force
        (n, m, 6) complex [N/m, N m/m] per unit wave amplitude, e^{-i omega t}; the last two
        only where the file separates them.
    hydrostatic_stiffness
        (6, 6) [N/m, N, N m]: the file's restoring matrix (buoyancy part, see the importer).
    disp_volume, center_of_buoyancy, center_of_gravity, rotation_center
        [m^3], (3,) [m] where the file gives them.
    water_density, gravity, water_depth
        [kg/m^3], [m/s^2], [m] (``inf``: deep water) as the file states them or as the
        importer was told (WAMIT's numeric files state none of them).
    body_name
        The body's name in the file, if any.
    notes
        What the importer did that a user should know (one sentence each).
    second_order
        Mean drift and difference-frequency QTF read with the first-order data, or None.
    """

    format: str
    files: tuple[str, ...]
    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    radiation_damping: NDArray[np.float64]
    water_density: float
    gravity: float
    added_mass_infinite: NDArray[np.float64] | None = None
    added_mass_zero: NDArray[np.float64] | None = None
    directions: NDArray[np.float64] | None = None
    excitation_force: NDArray[np.complex128] | None = None
    froude_krylov_force: NDArray[np.complex128] | None = None
    diffraction_force: NDArray[np.complex128] | None = None
    hydrostatic_stiffness: NDArray[np.float64] | None = None
    disp_volume: float | None = None
    center_of_buoyancy: NDArray[np.float64] | None = None
    center_of_gravity: NDArray[np.float64] | None = None
    rotation_center: NDArray[np.float64] | None = None
    water_depth: float | None = None
    body_name: str | None = None
    notes: tuple[str, ...] = ()
    second_order: SecondOrder | None = None
