"""The physical properties of one DG cable (a line or a line section) and its surroundings.

:class:`CableProperties` gathers what the DG kernels need of a line type, the water, the
seabed and the current, in SI units, built from a case's line or section (or directly, in
tests); it gives the cable's wave speeds, its stable time step for given numerics and the
kernels' packed parameter vector. The line and system models
(:mod:`floatmoor.mooring.dg.line`, :mod:`floatmoor.mooring.dg.system`) are built on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from floatmoor.case.schema import DynamicSettings, Environment, Line, Seabed, Section
from floatmoor.errors import SolverError
from floatmoor.mooring.catenary import solve_catenary
from floatmoor.mooring.dg import _kernels as _k
from floatmoor.mooring.dg.reference import STABLE_STEP_FACTOR
from floatmoor.mooring.dg.stability import stable_step_factor

__all__ = ["CableProperties", "IMPLICIT_MAX_STEP"]

#: Largest implicit step when the case gives no ``max_time_step`` [s]: the error control
#: (``IMPLICIT_ERROR_SHARE``) takes it down where the fairlead force needs it; a forced run's
#: output interval and a coupled run's half body step bound it further.
IMPLICIT_MAX_STEP = 0.5

@dataclass(frozen=True)
class CableProperties:
    """Physical properties of a line and its surroundings, SI units.

    Built from a case with :meth:`from_case` (or :meth:`from_section`); tests may build one
    directly (e.g. with ``water_density = 0`` for a line in vacuum, or ``seabed_z = -inf``
    for no seabed). The cable laws they enter are those of docs/theory/cable.md.

    Attributes
    ----------
    length
        Unstretched length [m].
    mass_per_length
        Dry mass per unstretched length m [kg/m].
    axial_stiffness
        EA [N].
    diameter
        Diameter the drag coefficients refer to, also the seabed contact width [m].
    material_density
        Density of the line's material rho_c [kg/m^3] (with the mass, the displaced
        volume).
    normal_drag_coefficient, tangential_drag_coefficient
        Morison drag coefficients normal to the line and along it, on the diameter [-].
    added_mass_coefficient, tangential_added_mass_coefficient
        Added-mass coefficients normal to the line and along it, on the material area
        m / rho_c [-].
    internal_damping
        c_int in T = EA eps + c_int d(eps)/dt [N s] (:meth:`from_section` gives it from
        the line type's damping ratio).
    water_density
        [kg/m^3]; 0 for a line in vacuum.
    gravity
        [m/s^2].
    current_velocity
        Steady, uniform current (x, y, z) [m/s].
    seabed_z
        Elevation of the seabed [m]; -inf for none.
    seabed_stiffness
        Normal stiffness of the seabed per unit contact area [Pa/m].
    seabed_damping_ratio
        Damping ratio of the normal contact spring-damper [-].
    friction_coefficient
        Coulomb friction coefficient along the seabed [-].
    slip_speed
        Sliding speed at which the smoothed Coulomb friction reaches its full value [m/s].
    friction_model
        ``"coulomb"`` (regularised by the slip speed) or ``"stick_spring"``
        (docs/theory/cable.md#seabed-friction).
    """

    length: float  #: unstretched [m]
    mass_per_length: float  #: [kg/m]
    axial_stiffness: float  #: EA [N]
    diameter: float  #: drag diameter, also the seabed contact width [m]
    material_density: float  #: [kg/m^3]
    normal_drag_coefficient: float = 0.0
    tangential_drag_coefficient: float = 0.0
    added_mass_coefficient: float = 0.0  #: normal, on the material area
    tangential_added_mass_coefficient: float = 0.0
    internal_damping: float = 0.0  #: c_int in T = EA eps + c_int d(eps)/dt [N s]
    water_density: float = 1000.0  #: [kg/m^3]
    gravity: float = 9.81  #: [m/s^2]
    current_velocity: tuple[float, float, float] = (0.0, 0.0, 0.0)  #: [m/s]
    seabed_z: float = -math.inf  #: [m]
    seabed_stiffness: float = 0.0  #: per unit contact area [Pa/m]
    seabed_damping_ratio: float = 0.0
    friction_coefficient: float = 0.0
    slip_speed: float = 0.01  #: [m/s]
    #: "coulomb" (regularised by the slip speed) or "stick_spring" (docs/theory/cable.md)
    friction_model: str = "coulomb"

    @classmethod
    def from_case(cls, line: Line, environment: Environment, seabed: Seabed) -> "CableProperties":
        """The properties of a case's one-section line (:meth:`from_section` of its section;
        a ValueError for a line of several sections)."""
        if len(line.sections) != 1:
            raise ValueError(f"line '{line.name}' has {len(line.sections)} sections; build "
                             "each section's properties with from_section")
        return cls.from_section(line.sections[0], environment, seabed)

    @classmethod
    def from_section(cls, section: Section, environment: Environment,
                     seabed: Seabed) -> "CableProperties":
        """The properties of a case's section: its line type and length.

        The internal damping ratio zeta is that of the section's own first longitudinal mode
        (fixed-fixed, omega_1 = pi c / L) for the Kelvin-Voigt law T = EA eps + c_int eps_t,
        zeta_n = c_int omega_n / (2 EA), so c_int = 2 zeta L sqrt(EA m) / pi with L the
        section's length: a property of the section, independent of the discretisation.
        """
        lt = section.line_type
        c_int = (2.0 * lt.internal_damping_ratio * section.length
                 * math.sqrt(lt.axial_stiffness * lt.mass_per_length) / math.pi)
        return cls(length=section.length, mass_per_length=lt.mass_per_length,
                   axial_stiffness=lt.axial_stiffness, diameter=lt.diameter,
                   material_density=lt.material_density,
                   normal_drag_coefficient=lt.normal_drag_coefficient,
                   tangential_drag_coefficient=lt.tangential_drag_coefficient,
                   added_mass_coefficient=lt.added_mass_coefficient,
                   tangential_added_mass_coefficient=lt.tangential_added_mass_coefficient,
                   internal_damping=c_int, water_density=environment.water_density,
                   gravity=environment.gravity, current_velocity=environment.current_velocity,
                   seabed_z=environment.seabed_z, seabed_stiffness=seabed.stiffness,
                   seabed_damping_ratio=seabed.damping_ratio,
                   friction_coefficient=seabed.friction_coefficient,
                   slip_speed=seabed.slip_speed, friction_model=seabed.friction_model)

    @property
    def stick_stiffness(self) -> float:
        """k_s of the stick-spring friction per length [N/m^2], 0 for the Coulomb law: the
        seabed's normal stiffness per length k_b (docs/theory/cable.md#seabed-friction)."""
        if self.friction_model != "stick_spring":
            return 0.0
        return self.seabed_stiffness * self.diameter

    @property
    def material_area(self) -> float:
        """A_c = m / rho_c [m^2]."""
        return self.mass_per_length / self.material_density

    @property
    def wave_speed(self) -> float:
        """Longitudinal wave speed sqrt(EA / m) [m/s]."""
        return math.sqrt(self.axial_stiffness / self.mass_per_length)

    def transverse_wave_speed(self, anchor: NDArray[np.float64],
                              fairlead: NDArray[np.float64]) -> float:
        """Transverse wave speed sqrt(H / (m + m_a)) of the line at rest between ``anchor``
        and ``fairlead`` [m/s]: H the horizontal tension of its frictionless catenary, m_a the
        normal added mass per length; 0 for a line that does not sink (no catenary)."""
        if self.submerged_weight <= 0.0:
            return 0.0
        try:
            sol = solve_catenary(anchor, fairlead, self.length, self.axial_stiffness,
                                 self.submerged_weight, 0.0, seabed_z=self.seabed_z)
        except SolverError:  # no static shape between these ends: resolve the shape only
            return 0.0
        added = self.added_mass_coefficient * self.water_density * self.material_area
        return math.sqrt(max(sol.horizontal_tension, 0.0) / (self.mass_per_length + added))

    @property
    def submerged_weight(self) -> float:
        """m g (1 - rho_w / rho_c) [N/m]."""
        return self.mass_per_length * self.gravity * (1.0 - self.water_density
                                                      / self.material_density)

    def time_step(self, settings: DynamicSettings) -> float:
        """The DG time step of this cable with ``settings`` [s]; with the implicit integration
        its largest step (``max_time_step``, default ``IMPLICIT_MAX_STEP``). Explicit: ``cfl``
        times the SSP-RK3 stability limit of the longitudinal wave on an element
        (``STABLE_STEP_FACTOR``; with explicit internal damping, from the spectrum of the
        damped scheme, stability.py) and of the explicit contact where it applies, capped by
        the user's ``max_time_step``.
        (Not checked: :class:`DynamicLine` refuses a step that is not finite and > 0.)"""
        st = settings
        if st.time_integration != "explicit":
            return st.max_time_step if st.max_time_step is not None else IMPLICIT_MAX_STEP
        h, c = self.length / st.elements, self.wave_speed
        if self.internal_damping > 0.0 and st.internal_damping == "explicit":
            nu = self.internal_damping / (self.mass_per_length * c * h)
            factor = stable_step_factor(st.order, nu)
        else:
            factor = STABLE_STEP_FACTOR[st.order]
        dt = st.cfl * factor * h / c
        kb = self.seabed_stiffness * self.diameter  # per m of line, as packed()'s P_KB
        if st.seabed_contact == "explicit" and kb > 0.0:
            omega = math.sqrt(kb / self.mass_per_length)
            # SSP-RK3 is stable to |lambda dt| ~ 2.5 on the negative real axis; a damped
            # oscillator of ratio xi has its fastest eigenvalue near omega (xi + sqrt(xi^2 + 1))
            xi = self.seabed_damping_ratio
            dt = min(dt, st.cfl * 2.5 / (omega * (xi + math.sqrt(xi * xi + 1.0))))
        if self.stick_stiffness > 0.0:
            # the stick spring is in the explicit stages: an undamped oscillator, inside
            # SSP-RK3's stability region on the imaginary axis up to |lambda dt| = sqrt(3)
            omega = math.sqrt(self.stick_stiffness / self.mass_per_length)
            dt = min(dt, st.cfl * math.sqrt(3.0) / omega)
        if st.max_time_step is not None:
            dt = min(dt, st.max_time_step)
        return dt

    def packed(self, settings: DynamicSettings, element_length: float) -> NDArray[np.float64]:
        """The kernels' parameter vector."""
        prm = np.zeros(_k.N_PRM)
        m = self.mass_per_length
        kb = self.seabed_stiffness * self.diameter  # per m of line: contact width = d
        prm[_k.P_M] = m
        prm[_k.P_EA] = self.axial_stiffness
        prm[_k.P_D] = self.diameter
        prm[_k.P_AC] = self.material_area
        prm[_k.P_RHO_W] = self.water_density
        prm[_k.P_G] = self.gravity
        prm[_k.P_CDN] = self.normal_drag_coefficient
        prm[_k.P_CDT] = self.tangential_drag_coefficient
        prm[_k.P_MAN] = self.added_mass_coefficient * self.water_density * self.material_area
        prm[_k.P_MAT] = (self.tangential_added_mass_coefficient * self.water_density
                         * self.material_area)
        prm[_k.P_CINT] = self.internal_damping
        prm[_k.P_WSUB] = abs(self.submerged_weight)
        prm[_k.P_ZB] = self.seabed_z if math.isfinite(self.seabed_z) else -1e300
        prm[_k.P_KB] = kb
        prm[_k.P_CB] = 2.0 * self.seabed_damping_ratio * math.sqrt(m * kb)
        prm[_k.P_MU] = self.friction_coefficient
        prm[_k.P_VC] = self.slip_speed
        prm[_k.P_UX:_k.P_UX + 3] = self.current_velocity
        prm[_k.P_H] = element_length
        prm[_k.P_IMPLICIT_CONTACT] = 1.0 if settings.seabed_contact == "implicit" else 0.0
        prm[_k.P_FILTER] = 1.0 if settings.slack_filter else 0.0
        prm[_k.P_C] = self.wave_speed
        prm[_k.P_IMPLICIT_DAMPING] = 1.0 if settings.internal_damping == "implicit" else 0.0
        prm[_k.P_DAMPING_TOL] = _k.DAMPING_TANGENT_TOL
        prm[_k.P_KS] = self.stick_stiffness
        return prm
