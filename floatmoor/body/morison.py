"""Viscous (Morison) drag on a floater's members: strips, coefficients and a per-stage force.

docs/theory/floater.md (viscous effects potential flow misses: quadratic Morison
drag on members). Only the DRAG term of Morison's equation is computed here. The inertia
terms (Froude-Krylov, diffraction, added mass) of the same members are already in the
potential-flow hydrodynamics of the Cummins body (BEM excitation X, A_inf and the radiation
memory K); adding Morison inertia would count them twice. This is the usual hybrid model of
semisubmersibles (OC4 DeepCwind in OpenFAST HydroDyn: every member has ``PropPot = TRUE``, for
which "only viscous-drag loads ... will be computed for that member", HydroDyn user guide,
input_files.rst "Members").

Model
-----
Each submerged part of the geometry at rest (z < 0) is cut into strips: body-fixed points with
a unit axis, a transverse coefficient cn = 1/2 rho Cd_t D ds and an axial coefficient ca
[kg/m]. The force of a strip on the relative velocity u = u_fluid - v_point, split into its
axial part u_a = (u . e) e and its normal part u_n = u - u_a, is

    f = cn |u_n| u_n + ca |u . e| u_a,

Morison's quadratic drag (Morison et al. 1950) in its relative-velocity form, applied per
direction as in HydroDyn's strip theory. Strips:

* vertical columns (``Column``): transverse drag along the submerged length, Cd_t per unit
  length on the column diameter;
* heave plates (the column's wider base): transverse drag on the plate's side (plate diameter,
  ``heave_plate_transverse``) and the axial drag of the plate, one lumped strip at the centre of
  its bottom face, ca = 1/2 rho Cd_axial A_plate;
* pontoons and braces (``Member``): transverse drag on their submerged part (clipped at z = 0
  at rest), optionally an axial (skin-friction) term ca = 1/2 rho Cd_ax pi D ds;
* a column without heave plate may get an axial drag on its bottom disc (``column_axial``).

Heave-plate area. OpenFAST HydroDyn, the OC4 DeepCwind reference model (OpenFAST r-test
5MW_OC4Semi_WSt_WavesWN, NRELOffshrBsline5MW_OC4DeepCwindSemi_HydroDyn.dat), puts the whole
axial drag of a base column on the joint at its bottom face (z = -20 m, ``JointAxID`` 2,
AxCd = 9.60) and none at its top (z = -14 m, AxCd = 0). HydroDyn's joint drag
(modules/hydrodyn/src/Morison.f90, Morison_Init) is F = A_n rho AxCd / (4 |A_n|^2)
|u . A_n| (u . A_n), A_n the area-weighted normal of the member ends at the joint: the FULL
disc pi R^2 of the 24 m base, and 1/4 rho AxCd where the standard form has 1/2 rho Cd, i.e.
Cd = AxCd / 2 = 4.8 on the full disc. Here: ``heave_plate_area = "disc"`` (default) uses the
full disc pi/4 D_plate^2 at the plate's bottom face, HydroDyn's geometry; ``"annulus"`` uses
pi/4 (D_plate^2 - D_column^2). The coefficient of the preset is the quasi-dynamic paper's (1.60, docs/cases/deepcwind.md), which is a
third of the r-test's effective 4.8: that Table 6 is the quasi-dynamic paper's choice and
is kept as given (see :data:`DEEPCWIND_OC4`).

Kinematics. Strip points are body-fixed; their velocity is v[:3] + v[3:] x R r0 with the full
rotation R (large angles, as :func:`floatmoor.body.kinematics.points_state`), and forces are
summed into forces and moments about the displaced reference point with the rotated arms (as
:func:`floatmoor.body.kinematics.generalised_force`). The fluid velocity is the linear (Airy)
incident-wave velocity at the strips' MEAN positions (the rest position, or a given mean
displacement), the standard first-order approximation: the change of the fluid velocity over
the body's displacement is a product of two first-order quantities. Strips are the submerged
parts in the mean pose (the rest position, or the run's static equilibrium with its mean
heel or trim): no wave stretching and no wetting/drying at the moving waterline (a strip
that emerges keeps its drag, a dry one stays dry; so no mean drift force from the splash
zone), and the incident field is undisturbed by
the body (no diffraction of the kinematics). A steady uniform current is added to the waves.

Cost. :meth:`MorisonDrag.prepare` computes the fluid velocity at all strips on the RK4 stage
grid t0 + k dt/2 of a chunk of steps with blocked complex products
(:func:`floatmoor.waves.synthesis.harmonic_sum`) on a coarser grid and cubic Lagrange
interpolation (module constant :data:`KINEMATICS_PHASE_STEP`); :meth:`MorisonDrag.force` is
then O(strips) per stage in a numba kernel (floatmoor/body/_morison_kernels.py).

Linear and quadratic damping matrices (docs/theory/floater.md: the viscous
effects potential flow misses) are not here: :class:`floatmoor.body.cummins.CumminsBody` takes ``linear_damping`` and
``quadratic_damping`` (6x6) directly.

References
----------
Morison, J. R., O'Brien, M. P., Johnson, J. W., Schaaf, S. A. (1950). The force exerted by
surface waves on piles. Petroleum Transactions AIME 189, 149-154.
Robertson, A. et al. (2014). Definition of the semisubmersible floating system for phase II
of OC4. NREL/TP-5000-60601.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from floatmoor.body._morison_kernels import drag_force, lagrange_fill, lagrange_weights
from floatmoor.case.drag import (
    DEEPCWIND_OC4, DEFAULT_STRIP_LENGTH, HEAVE_PLATE_AREAS, MIN_STRIPS, NO_DRAG, PRESETS,
    DragSettings, MorisonCoefficients,
)
from floatmoor.case.schema import (
    Column, CylinderGeometry, Floater, Member, MeshGeometry, SemisubmersibleGeometry,
)
from floatmoor.rotations import rotation_matrix
from floatmoor.waves.kinematics import _profiles
from floatmoor.waves.realisation import WaveField
from floatmoor.waves.synthesis import harmonic_sum

__all__ = ["MorisonCoefficients", "DragSettings", "Strips", "MorisonDrag", "build_strips",
           "DEEPCWIND_OC4", "NO_DRAG", "PRESETS", "HEAVE_PLATE_AREAS",
           "DEFAULT_STRIP_LENGTH", "MIN_STRIPS", "KINEMATICS_PHASE_STEP"]

#: Coarse sampling of the fluid velocity: omega_max * interval <= this phase [rad]. The
#: remainder of cubic Lagrange interpolation between the middle nodes is at most
#: (9/16) (omega h)^4 / 24 of the amplitude: 1.5e-3 at omega_max and 3e-6 at a quarter of it
#: (tests/body/test_morison.py::test_prepare_interpolation_matches_exact_sum). Measured on
#: the LC34 sea (Hs 10.5 m, Tp 14.3 s, 3094 components to 2 rad/s, dt/2 = 0.025 s, 10 half
#: steps per sample): 2.8e-4 of the largest fluid velocity, 2.1e-4 of the largest surge drag.
KINEMATICS_PHASE_STEP = 0.5
#: Strip kinds (Strips.kind codes).
KIND_COLUMN, KIND_PLATE_SIDE, KIND_PLATE_AXIAL, KIND_COLUMN_AXIAL, KIND_MEMBER = range(5)
KIND_NAMES = ("column", "heave_plate_side", "heave_plate_axial", "column_axial", "member")


@dataclass(frozen=True)
class Strips:
    """The drag strips of a floater at rest (global axes), shape (n, ...) each."""

    points: NDArray[np.float64]  #: strip centres at rest (n, 3) [m]
    arms: NDArray[np.float64]  #: points minus the reference point (n, 3) [m]
    axes: NDArray[np.float64]  #: unit axes at rest (n, 3)
    normal: NDArray[np.float64]  #: cn = 1/2 rho Cd_t D ds (n,) [kg/m]
    axial: NDArray[np.float64]  #: ca (n,) [kg/m]
    length: NDArray[np.float64]  #: strip length ds (0 for lumped discs) (n,) [m]
    kind: NDArray[np.int64]  #: KIND_* codes (n,)

    @property
    def n(self) -> int:
        """Number of strips."""
        return int(self.points.shape[0])

    def count(self, kind: str) -> int:
        """Strips of a kind named in KIND_NAMES."""
        return int(np.sum(self.kind == KIND_NAMES.index(kind)))

    def submerged_length(self, kind: str) -> float:
        """Total strip length of a kind [m]."""
        return float(self.length[self.kind == KIND_NAMES.index(kind)].sum())


class _StripBuilder:
    def __init__(self, settings: DragSettings, rho: float, centre: NDArray[np.float64],
                 mean_displacement: NDArray[np.float64]) -> None:
        self.s = settings
        self.half_rho = 0.5 * rho
        self.rows: list[tuple[Any, ...]] = []
        # elevation of a body point in the mean pose: z = c_z + x_z + (R (p - c))_z, affine
        xm = mean_displacement
        self._rz = rotation_matrix(xm[3], xm[4], xm[5])[2]
        self._z0 = centre[2] + xm[2] - self._rz @ centre

    def z(self, p: NDArray) -> float:
        """Elevation of the body point ``p`` (given at rest) in the mean pose [m]."""
        return float(self._z0 + self._rz @ p)

    def n_strips(self, length: float) -> int:
        return max(self.s.min_strips, math.ceil(length / self.s.strip_length - 1e-9))

    def line(self, a: NDArray, b: NDArray, diameter: float, cd_t: float, cd_ax: float,
             kind: int) -> None:
        """Strips on the submerged part (z < 0 in the mean pose) of the segment a-b (none
        without drag)."""
        za, zb = self.z(a), self.z(b)
        if (cd_t == 0.0 and cd_ax == 0.0) or (za >= 0.0 and zb >= 0.0):
            return
        if za > 0.0 or zb > 0.0:  # clip at the still water line (the elevation is affine)
            (wet, zw), (dry, zd) = ((a, za), (b, zb)) if za < 0.0 else ((b, zb), (a, za))
            t = zw / (zw - zd)
            a, b = wet, wet + t * (dry - wet)
        d = b - a
        length = float(np.linalg.norm(d))
        if length == 0.0:
            return
        axis = d / length
        n = self.n_strips(length)
        ds = length / n
        for j in range(n):
            p = a + (j + 0.5) * ds * axis
            self.rows.append((p, axis, self.half_rho * cd_t * diameter * ds,
                              self.half_rho * cd_ax * math.pi * diameter * ds, ds, kind))

    def disc(self, p: NDArray, area: float, cd: float, kind: int) -> None:
        if cd > 0.0 and self.z(p) < 0.0 and area > 0.0:
            self.rows.append((p, np.array([0.0, 0.0, 1.0]), 0.0, self.half_rho * cd * area,
                              0.0, kind))

    def column(self, col: Column) -> None:
        c = self.s.coefficients
        z_b, z_t = col.z_bottom, col.z_top
        base = np.array([col.x, col.y, z_b])
        if col.heave_plate_diameter is not None and col.heave_plate_height > 0.0:
            dp = col.heave_plate_diameter
            z_p = z_b + col.heave_plate_height
            self.line(base, np.array([col.x, col.y, min(z_p, z_t)]), dp,
                      c.heave_plate_transverse, 0.0, KIND_PLATE_SIDE)
            if z_t > z_p:
                self.line(np.array([col.x, col.y, z_p]), np.array([col.x, col.y, z_t]),
                          col.diameter, c.column_transverse, 0.0, KIND_COLUMN)
            area = 0.25 * math.pi * dp ** 2
            if self.s.heave_plate_area == "annulus":
                area -= 0.25 * math.pi * col.diameter ** 2
            self.disc(base, area, c.heave_plate_axial, KIND_PLATE_AXIAL)
        else:
            self.line(base, np.array([col.x, col.y, z_t]), col.diameter,
                      c.column_transverse, 0.0, KIND_COLUMN)
            self.disc(base, 0.25 * math.pi * col.diameter ** 2, c.column_axial,
                      KIND_COLUMN_AXIAL)

    def member(self, m: Member) -> None:
        c = self.s.coefficients
        self.line(np.asarray(m.start, dtype=float), np.asarray(m.end, dtype=float),
                  m.diameter, c.member_transverse, c.member_axial, KIND_MEMBER)


def build_strips(floater: Floater, settings: DragSettings, water_density: float,
                 mean_displacement: ArrayLike | None = None) -> Strips:
    """The drag strips of ``floater``'s geometry (module docstring), in body coordinates at
    rest, on the parts that are submerged in the mean pose ``mean_displacement`` (6,) (default
    the rest position): a mean heel or trim, as the rotor thrust gives, lifts part of a
    column out of the water and sinks another part.

    A :class:`CylinderGeometry` is one column on the reference point's vertical axis from
    -draft to height - draft (its bottom disc takes ``column_axial``). A
    :class:`MeshGeometry` has no members of its own: its strips are on the Morison columns
    and members the case gives with it (``[[floater.geometry.columns]]``, ``members``), none
    without them.
    """
    settings.validate()
    if not (math.isfinite(water_density) and water_density > 0.0):
        raise ValueError(f"drag: water density must be > 0, got {water_density!r}")
    xm = np.zeros(6) if mean_displacement is None else np.asarray(mean_displacement, float)
    b = _StripBuilder(settings, water_density, np.asarray(floater.reference_point, float), xm)
    g = floater.geometry
    if isinstance(g, CylinderGeometry):
        x0, y0 = floater.reference_point[0], floater.reference_point[1]
        b.column(Column(x=x0, y=y0, diameter=g.diameter, z_top=g.height - g.draft,
                        z_bottom=-g.draft))
    elif isinstance(g, (SemisubmersibleGeometry, MeshGeometry)):
        for col in g.columns:
            b.column(col)
        for mem in g.members:
            b.member(mem)
    else:  # pragma: no cover - the schema has three kinds
        raise ValueError(f"drag: unsupported floater geometry {type(g).__name__}")
    ref = np.asarray(floater.reference_point, dtype=float)
    if not b.rows:
        empty = np.zeros((0, 3))
        return Strips(empty, empty.copy(), empty.copy(), np.zeros(0), np.zeros(0),
                      np.zeros(0), np.zeros(0, dtype=np.int64))
    pts = np.array([r[0] for r in b.rows], dtype=float)
    return Strips(points=pts, arms=pts - ref,
                  axes=np.array([r[1] for r in b.rows], dtype=float),
                  normal=np.array([r[2] for r in b.rows], dtype=float),
                  axial=np.array([r[3] for r in b.rows], dtype=float),
                  length=np.array([r[4] for r in b.rows], dtype=float),
                  kind=np.array([r[5] for r in b.rows], dtype=np.int64))


class MorisonDrag:
    """The drag force of a floater's strips in a sea, per RK4 stage.

    Usage: :meth:`prepare` a chunk of the half-step grid t0 + k dt_half, then call
    :meth:`force` with the stage's index k. :meth:`force_in` takes explicit fluid velocities.

    Parameters
    ----------
    floater
        The floater (geometry and reference point).
    settings
        Coefficients and discretisation.
    water_density
        [kg/m^3].
    sea
        The incident waves (None or no components: still water).
    current
        Steady uniform current velocity [m/s].
    mean_displacement
        The body's mean displacement (6,) at which the fluid velocity is evaluated (default:
        the rest position; a coupled run passes its static equilibrium).
    """

    def __init__(self, floater: Floater, settings: DragSettings, water_density: float,
                 sea: WaveField | None = None, *,
                 current: ArrayLike = (0.0, 0.0, 0.0),
                 mean_displacement: ArrayLike | None = None) -> None:
        self.settings = settings
        self.strips = build_strips(floater, settings, water_density, mean_displacement)
        self.centre = np.asarray(floater.reference_point, dtype=float)
        self.sea = sea if sea is not None and sea.n_components > 0 else None
        self.current = np.asarray(current, dtype=float).reshape(3)
        xm = np.zeros(6) if mean_displacement is None else np.asarray(mean_displacement,
                                                                      dtype=float)
        s = self.strips
        self.mean_points = (self.centre + xm[:3]
                            + s.arms @ rotation_matrix(xm[3], xm[4], xm[5]).T)
        self._arms = np.ascontiguousarray(s.arms)
        self._axes = np.ascontiguousarray(s.axes)
        self._cn = np.ascontiguousarray(s.normal)
        self._ca = np.ascontiguousarray(s.axial)
        self._coef: NDArray[np.complex128] | None = None
        if self.sea is not None and s.n:
            self._coef = self._velocity_coefficients()
        self._fluid = np.zeros((1, s.n, 3))
        self._fluid[0] = self.current
        self._n_ready = 0
        self.t0 = math.nan
        self.dt_half = math.nan
        self._still = np.zeros((1, s.n, 3))
        self._still[0] = self.current

    # ---------------------------------------------------------------- fluid velocity
    def _velocity_coefficients(self) -> NDArray[np.complex128]:
        """c (N, 3 n): the fluid velocity at strip i, component q, is
        Re{sum_j c[j, 3 i + q] e^{-i omega_j t}} (floatmoor.waves.kinematics formulas)."""
        f = self.sea
        p = self.mean_points
        if np.any(p[:, 2] >= 0.0):
            raise ValueError("drag: a strip's mean position is not submerged")
        if not math.isinf(f.depth) and np.any(p[:, 2] <= -f.depth):
            raise ValueError("drag: a strip's mean position is below the seabed")
        c = f.complex_elevation(p[:, 0], p[:, 1])  # (n, N)
        ch, sh = _profiles(f.wavenumber, p[:, 2:3], f.depth)  # (n, N)
        w = f.omega
        horizontal = c * (w * ch)
        out = np.empty((f.n_components, p.shape[0], 3), dtype=complex)
        out[:, :, 0] = (horizontal * np.cos(f.direction)).T
        out[:, :, 1] = (horizontal * np.sin(f.direction)).T
        out[:, :, 2] = (-1j * c * (w * sh)).T
        return out.reshape(f.n_components, -1)

    def decimation(self, dt_half: float) -> int:
        """Half steps per coarse kinematics sample for the half step ``dt_half`` [s]."""
        interval = self.settings.kinematics_interval
        if self.sea is None:
            return 1
        if interval is None:
            interval = KINEMATICS_PHASE_STEP / float(np.max(self.sea.omega))
        return max(1, int(math.floor(interval / dt_half + 1e-9)))

    def prepare(self, t0: float, n_half: int, dt_half: float,
                ramp: Callable[[float], float] | None = None) -> None:
        """Fluid velocity at the strips at t0 + k dt_half, k = 0 .. n_half - 1.

        ``ramp(t)`` scales the waves (not the current), as the run's excitation ramp.
        """
        if n_half < 1 or not dt_half > 0.0:
            raise ValueError("drag: prepare needs n_half >= 1 and dt_half > 0")
        n = self.strips.n
        if self._fluid.shape[0] < n_half:
            self._fluid = np.empty((n_half, n, 3))
        fluid = self._fluid
        self.t0, self.dt_half, self._n_ready = float(t0), float(dt_half), int(n_half)
        if self._coef is None:
            fluid[:n_half] = self.current
            return
        flat = fluid[:n_half].reshape(n_half, 3 * n)
        m = self.decimation(dt_half)
        if m == 1:
            flat[:] = harmonic_sum(self._coef, self.sea.omega,
                                   t0 + dt_half * np.arange(n_half))
        else:
            n_coarse = (n_half - 1) // m + 4
            times = t0 + m * dt_half * (np.arange(n_coarse) - 1.0)
            coarse = harmonic_sum(self._coef, self.sea.omega, times)
            lagrange_fill(coarse, lagrange_weights(m), flat)
        if ramp is not None:
            factors = np.array([ramp(t0 + k * dt_half) for k in range(n_half)])
            if not np.all(factors == 1.0):
                fluid[:n_half] *= factors[:, None, None]
        if np.any(self.current):
            fluid[:n_half] += self.current

    @property
    def fluid_velocity(self) -> NDArray[np.float64]:
        """The prepared fluid velocities (n_half, n_strips, 3) [m/s] (a view)."""
        return self._fluid[:self._n_ready]

    def index(self, t: float) -> int:
        """The prepared row of time ``t`` (nearest half step)."""
        return int(round((t - self.t0) / self.dt_half))

    # ---------------------------------------------------------------- force
    def force(self, k: int, x: NDArray[np.float64], v: NDArray[np.float64],
              out: NDArray[np.float64] | None = None) -> NDArray[np.float64]:
        """The 6-DOF drag force [N, N m] at prepared row ``k`` and body state (x, v) (6,)."""
        if not 0 <= k < self._n_ready:
            raise IndexError(f"drag: half step {k} outside the prepared 0..{self._n_ready - 1}")
        if out is None:
            out = np.empty(6)
        drag_force(np.asarray(x, dtype=float), np.asarray(v, dtype=float), self._arms,
                   self._axes, self._cn, self._ca, self._fluid, k, out)
        return out

    def force_in(self, fluid_velocity: ArrayLike | None, x: NDArray[np.float64],
                 v: NDArray[np.float64]) -> NDArray[np.float64]:
        """The drag force for explicit fluid velocities (n_strips, 3) [m/s] at the strips
        (None: the current only)."""
        if fluid_velocity is None:
            fluid = self._still
        else:
            fluid = np.ascontiguousarray(np.asarray(fluid_velocity, dtype=float)
                                         .reshape(1, self.strips.n, 3))
        out = np.empty(6)
        drag_force(np.asarray(x, dtype=float), np.asarray(v, dtype=float), self._arms,
                   self._axes, self._cn, self._ca, fluid, 0, out)
        return out
