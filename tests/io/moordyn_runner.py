"""Peer-code harness: one mooring line in MoorDyn (MoorDyn-C v2, the ``moordyn`` Python wrapper
from PyPI), its fairlead forced along a prescribed path, the fairlead tension recorded.

This is a test helper, not a test file. The peer tests and the MoorDyn benchmark call
:func:`run_moordyn_forced`; the harness tests use :func:`moordyn_system` to query MoorDyn's
internals and :func:`moordyn_parameters` to read the mapping back.

How floatmoor's line description maps onto MoorDyn's (MoorDyn-C 2.7, ``Line.cpp``)
------------------------------------------------------------------------------------
(The mapping is coded once, in ``floatmoor.io.moordyn.line_types``; summarised here.)
MoorDyn has one line diameter ``d`` that it uses at once as the volume-equivalent diameter
(buoyancy ``rho_w g pi d^2/4`` and added mass ``Ca rho_w pi d^2/4`` per length) and as the drag
reference (normal drag ``0.5 rho_w Cdn d |v_n| v_n``, tangential drag
``0.5 rho_w Cdt pi d |v_t| v_t`` -- note the ``pi``: MoorDyn's axial coefficient refers to the
circumference). floatmoor (docs/theory/cable.md) has the material area ``A_c = m / rho_c`` for
buoyancy and added mass and a separate drag diameter ``d`` (the nominal chain diameter, for
the Lindahl chain 2.2 mm against a volume-equivalent 3.65 mm). So we write:

- MoorDyn ``Diam = d_v = sqrt(4 m / (pi rho_c))``, hence MoorDyn's area is ``A_c``: the weight in
  water is ``m g (1 - rho_w / rho_c)`` and the added mass ``Ca rho_w A_c`` (``Can = Ca``,
  ``Cat = Ca_t``) exactly as in floatmoor; MoorDyn's mass per length is ``m`` itself;
- ``Cd = Cdn d / d_v`` and ``CdAx = Cdt d / (pi d_v)``, so the drag forces per length are
  floatmoor's ``0.5 rho_w d Cdn |v_n| v_n`` and ``0.5 rho_w d Cdt |v_t| v_t``;
- ``BA = internal_damping`` [N s] (MoorDyn divides a positive BA by its area and multiplies it
  back, so the damping tension is ``BA * d(eps)/dt``), ``EI = 0``.

Seabed: MoorDyn's vertical contact force per length is ``(kBot (z_b - z) - cBot v_z) d_v``
(both directions of v_z). floatmoor's stiffness is given per m of contact width, the contact
width being the line's (drag) diameter ``d``: ``K_l = K d`` per length per penetration, and the
damping per length ``c_l = 2 xi sqrt(m K_l)`` (critical for the line's own mass when xi = 1).
We write ``kBot = K d / d_v`` and ``cBot = 2 xi sqrt(m K d) / d_v``, which give MoorDyn the same
force per length. (floatmoor's DG kernel damps only while the line moves into the seabed;
MoorDyn damps both ways, which acts only within the ~1e-7 m of penetration.)

Friction: MoorDyn-C 2.7 has ``FrictionCoefficient`` (mu), ``FricDamp`` (C_v) and
``StatDynFricScale``; its friction magnitude on a node in contact is
``min(mu C_v |v_xy|, mu |F_z|)`` with ``F_z`` the node's contact force (static friction equal
to dynamic with ``StatDynFricScale = 1``). floatmoor's friction rises from 0 to ``mu |F_z|``
at the slip speed ``v_c`` (linearly in the chain paper's Table 8, as a sine in the gpc paper).
A node resting on the seabed carries ``F_z = w l`` (w the weight in water per length, l the
segment length), so ``FricDamp = w l / v_c`` makes MoorDyn's friction saturate at ``v_c`` on such
nodes: the linear ramp, per node, for a line lying statically on the seabed.

Fairlead tension: the magnitude of the force MoorDyn returns on the coupled fairlead point,
i.e. the net force of the line's end node: the last segment's tension plus the end node's
half-segment weight (and drag). In statics this is exactly the continuous line's tension at
its end (the vertical component grows by ``w l / 2`` over the half segment), whereas
``GetLineFairTen`` (the last segment's tension, at ``s = L - l/2``) is low by about
``w l / 2 sin(angle)``. It excludes the end node's inertia (an O(l) mass).

Coupling: within a ``moordyn.Step(x, xd, t, dt_c)`` MoorDyn moves a coupled point as
``x + xd tau`` for ``tau`` in ``[0, dt_c]`` (``Point::updateFairlead``) while it sub-steps at
``dtM``. We pass the start position of each coupling interval and the secant velocity, so the
fairlead path is the piecewise-linear interpolant of the samples (continuous, no jump between
intervals); with ``substeps > 1`` each sample interval is first refined by cubic Hermite
interpolation of the prescribed position and velocity.

Initial state: MoorDyn's own. It starts from its catenary profile and refines it with its
stationary solver (MoorDyn-C 2.7's default, ``ICgenDynamic 0``) for at most ``TmaxIC`` =
:data:`IC_MAX_TIME` pseudo-seconds, or less when it stagnates; ``threshIC`` is left at its
default. On the Lindahl chain at 40 segments its tension is 0.4 % below the dynamic
equilibrium. A forced-motion run should therefore start with a ramp, from rest. At rest on the
seabed MoorDyn's fairlead tension jitters by about +-0.3 % (undamped axial modes excited by the
contact), so static comparisons average over a second or so.

Console: MoorDyn prints its banner and input echo while it reads the file, before a verbosity
can be set, and its errors on stderr. The harness sends file descriptors 1 and 2 to a file in
the temporary directory while MoorDyn creates, initialises and steps the system (the file's
tail goes into :class:`MoorDynError`), and sets MoorDyn's console verbosity to errors only.
No log file (``writeLog 0``), ``disableOutput 1``; MoorDyn's own output files, if any, go into
the temporary directory.
"""

from __future__ import annotations

import contextlib
import ctypes
import math
import os
import sys
import tempfile
import time as _time
from collections.abc import Iterator
from dataclasses import KW_ONLY, dataclass
from pathlib import Path

import numpy as np

from floatmoor.io.moordyn.line_types import (friction_damping, moordyn_line_type,
                                              seabed_to_moordyn)

__all__ = ["MoorDynLine", "MoorDynParameters", "MoorDynError", "moordyn_parameters",
           "moordyn_input", "moordyn_system", "open_input", "run_moordyn_forced"]

#: MoorDyn time integrator (its default, 2nd-order Runge-Kutta).
TIME_SCHEME = "RK2"
#: Pseudo-time [s] MoorDyn's stationary initial-condition solver may spend at most (TmaxIC).
#: On the Lindahl chain (40 to 160 segments) its fairlead tension is then within 0.5 % of the
#: dynamic equilibrium; more rarely helps (the solver stagnates) and costs start-up time.
IC_MAX_TIME = 10.0
#: Relative tolerance on uniform sampling of the prescribed motion.
_UNIFORM_RTOL = 1e-6


class MoorDynError(RuntimeError):
    """MoorDyn failed (input rejected, initial condition failed, integration diverged)."""


@dataclass(frozen=True)
class MoorDynLine:
    """One line from a fixed anchor to a coupled fairlead, in floatmoor's conventions (SI, z up).

    ``diameter`` is the diameter the drag coefficients refer to (nominal for chain); buoyancy
    and added mass use the material area ``mass_per_length / material_density``.
    """

    length: float  #: unstretched length [m]
    mass_per_length: float  #: [kg/m]
    axial_stiffness: float  #: EA [N]
    diameter: float  #: drag reference (and seabed contact width) [m]
    material_density: float  #: [kg/m^3]
    normal_drag_coefficient: float  #: on ``diameter`` [-]
    tangential_drag_coefficient: float  #: on ``diameter`` [-]
    added_mass_coefficient: float  #: normal, on the material area [-]
    _: KW_ONLY
    tangential_added_mass_coefficient: float = 0.0  #: on the material area [-]
    internal_damping: float = 0.0  #: axial damping coefficient c_int, T += c_int d(eps)/dt [N s]
    anchor: tuple[float, float, float]  #: fixed end [m]
    fairlead: tuple[float, float, float]  #: initial / mean fairlead position [m]
    water_depth: float  #: seabed at z = -water_depth [m]
    water_density: float = 1000.0  #: [kg/m^3]
    gravity: float = 9.81  #: [m/s^2]
    seabed_stiffness: float = 3e9  #: per m of contact width [Pa/m]
    seabed_damping_ratio: float = 1.0  #: of the line's own mass on the seabed spring [-]
    friction_coefficient: float = 0.0  #: Coulomb [-]
    slip_speed: float = 0.01  #: sliding speed of full friction [m/s]

    def __post_init__(self) -> None:
        positive = ("length", "mass_per_length", "axial_stiffness", "diameter",
                    "material_density", "water_depth", "water_density", "gravity",
                    "slip_speed")
        for name in positive:
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"{name} must be finite and > 0, got {value!r}")
        non_negative = ("normal_drag_coefficient", "tangential_drag_coefficient",
                        "added_mass_coefficient", "tangential_added_mass_coefficient",
                        "internal_damping", "seabed_stiffness", "seabed_damping_ratio",
                        "friction_coefficient")
        for name in non_negative:
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name} must be finite and >= 0, got {value!r}")
        for name in ("anchor", "fairlead"):
            p = tuple(float(c) for c in getattr(self, name))
            if len(p) != 3 or not all(math.isfinite(c) for c in p):
                raise ValueError(f"{name} must be 3 finite coordinates, got {p!r}")
            object.__setattr__(self, name, p)
        if self.anchor[2] < -self.water_depth:
            raise ValueError(f"anchor z = {self.anchor[2]} is below the seabed "
                             f"(z = {-self.water_depth})")

    @property
    def material_area(self) -> float:
        """A_c = m / rho_c [m^2]."""
        return self.mass_per_length / self.material_density

    @property
    def weight_in_water(self) -> float:
        """Submerged weight per length m g (1 - rho_w / rho_c) [N/m]."""
        return self.mass_per_length * self.gravity * (1.0 - self.water_density
                                                      / self.material_density)


@dataclass(frozen=True)
class MoorDynParameters:
    """The values written into MoorDyn's input file for a :class:`MoorDynLine` (see the module
    docstring for the mapping)."""

    diameter: float  #: MoorDyn Diam: volume-equivalent diameter [m]
    mass_per_length: float  #: Mass/m [kg/m]
    axial_stiffness: float  #: EA [N]
    internal_damping: float  #: BA [N s]
    normal_drag_coefficient: float  #: Cd on ``diameter`` [-]
    added_mass_coefficient: float  #: Ca [-]
    tangential_drag_coefficient: float  #: CdAx on pi * ``diameter`` [-]
    tangential_added_mass_coefficient: float  #: CaAx [-]
    seabed_stiffness: float  #: kBot [Pa/m]
    seabed_damping: float  #: cBot [Pa s/m]
    friction_coefficient: float  #: FrictionCoefficient [-]
    friction_damping: float  #: FricDamp [N s/m]
    static_dynamic_friction_scale: float  #: StatDynFricScale [-]


def moordyn_parameters(line: MoorDynLine, segments: int) -> MoorDynParameters:
    """MoorDyn's line-type, seabed and friction values reproducing ``line`` (module docstring;
    the mapping itself is floatmoor.io.moordyn.line_types, which the export uses too)."""
    md = moordyn_line_type(line, line.internal_damping)
    k_bot, c_bot = seabed_to_moordyn(line.seabed_stiffness, line.seabed_damping_ratio, line)
    return MoorDynParameters(
        diameter=md.diameter,
        mass_per_length=md.mass_per_length,
        axial_stiffness=md.axial_stiffness,
        internal_damping=md.internal_damping,
        normal_drag_coefficient=md.normal_drag_coefficient,
        added_mass_coefficient=md.added_mass_coefficient,
        tangential_drag_coefficient=md.tangential_drag_coefficient,
        tangential_added_mass_coefficient=md.tangential_added_mass_coefficient,
        seabed_stiffness=k_bot,
        seabed_damping=c_bot,
        friction_coefficient=line.friction_coefficient,
        friction_damping=friction_damping(line.weight_in_water, line.length, segments,
                                          line.slip_speed),
        static_dynamic_friction_scale=1.0,
    )


def moordyn_input(line: MoorDynLine, *, segments: int, dt: float,
                  fairlead: tuple[float, float, float] | None = None,
                  ic_max_time: float = IC_MAX_TIME, time_scheme: str = TIME_SCHEME,
                  extra_options: dict[str, object] | None = None) -> str:
    """Text of a MoorDyn v2 input file for ``line`` (fairlead point at ``fairlead``, default the
    line's), ``segments`` segments and time step ``dt`` [s]."""
    if segments < 2:
        raise ValueError(f"segments must be >= 2, got {segments}")
    if not (math.isfinite(dt) and dt > 0.0):
        raise ValueError(f"dt must be finite and > 0, got {dt!r}")
    p = moordyn_parameters(line, segments)
    a = line.anchor
    f = line.fairlead if fairlead is None else fairlead
    g = ".17g"  # round-trip precision
    return "\n".join([
        "--------------------- MoorDyn Input File ------------------------------------",
        "floatmoor peer harness (tests/io/moordyn_runner.py)",
        "----------------------- LINE TYPES ------------------------------------------",
        "TypeName  Diam  Mass/m  EA  BA/-zeta  EI  Cd  Ca  CdAx  CaAx",
        "(name)  (m)  (kg/m)  (N)  (N-s/-)  (N-m^2)  (-)  (-)  (-)  (-)",
        f"line  {p.diameter:{g}}  {p.mass_per_length:{g}}  {p.axial_stiffness:{g}}  "
        f"{p.internal_damping:{g}}  0.0  {p.normal_drag_coefficient:{g}}  "
        f"{p.added_mass_coefficient:{g}}  {p.tangential_drag_coefficient:{g}}  "
        f"{p.tangential_added_mass_coefficient:{g}}",
        "---------------------- POINTS --------------------------------",
        "ID  Attachment  X  Y  Z  Mass  Volume  CdA  Ca",
        "(-)  (-)  (m)  (m)  (m)  (kg)  (m^3)  (m^2)  (-)",
        f"1  Fixed  {a[0]:{g}}  {a[1]:{g}}  {a[2]:{g}}  0  0  0  0",
        f"2  Coupled  {f[0]:{g}}  {f[1]:{g}}  {f[2]:{g}}  0  0  0  0",
        "---------------------- LINES --------------------------------------",
        "ID  LineType  AttachA  AttachB  UnstrLen  NumSegs  Outputs",
        "(-)  (-)  (-)  (-)  (m)  (-)  (-)",
        f"1  line  1  2  {line.length:{g}}  {segments:d}  -",
        "---------------------- OPTIONS -----------------------------------------",
        "0  writeLog",
        f"{time_scheme}  tScheme",
        f"{dt:{g}}  dtM",
        f"{line.gravity:{g}}  g",
        f"{line.water_density:{g}}  rho",
        f"{line.water_depth:{g}}  WtrDpth",
        f"{p.seabed_stiffness:{g}}  kBot",
        f"{p.seabed_damping:{g}}  cBot",
        f"{p.friction_coefficient:{g}}  FrictionCoefficient",
        f"{p.friction_damping:{g}}  FricDamp",
        f"{p.static_dynamic_friction_scale:{g}}  StatDynFricScale",
        f"{ic_max_time:{g}}  TmaxIC",
        "1  disableOutput",
        *(f"{value}  {key}" for key, value in (extra_options or {}).items()),
        "----------------------- END -----------------------------------------",
        "",
    ])


@contextlib.contextmanager
def _stdout_to(path: Path) -> Iterator[None]:
    """Redirect the process's file descriptors 1 and 2 (where MoorDyn's C++ code prints its
    messages and its errors) to ``path``. POSIX only; elsewhere MoorDyn prints as it likes."""
    if os.name != "posix":
        yield
        return
    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    sys.stderr.flush()
    libc.fflush(None)
    saved = [os.dup(1), os.dup(2)]
    try:
        with open(path, "ab") as sink:
            os.dup2(sink.fileno(), 1)
            os.dup2(sink.fileno(), 2)
        yield
    finally:
        libc.fflush(None)
        for fd, copy in zip((1, 2), saved):
            os.dup2(copy, fd)
            os.close(copy)


def _as_list(v: np.ndarray) -> list[float]:
    return [float(c) for c in v]


def _console_tail(log: Path, lines: int = 40) -> str:
    try:
        text = log.read_text(errors="replace").rstrip()
    except OSError:
        return ""
    if not text:
        return ""
    return "\n--- MoorDyn console ---\n" + "\n".join(text.splitlines()[-lines:])


@contextlib.contextmanager
def open_input(text: str, position: np.ndarray, velocity: np.ndarray
               ) -> Iterator[tuple[object, Path]]:
    """A MoorDyn system created from the input file ``text`` and initialised with its coupled
    DOFs at ``position`` moving at ``velocity`` (flat, MoorDyn's order of coupled DOFs), and
    the file MoorDyn's console was sent to; closed on exit."""
    import moordyn

    x0 = np.asarray(position, dtype=float).ravel()
    v0 = np.asarray(velocity, dtype=float).ravel()
    if x0.shape != v0.shape:
        raise ValueError("position and velocity must have the same size")
    with tempfile.TemporaryDirectory(prefix="floatmoor_moordyn_") as tmp:
        path = Path(tmp) / "line.dat"
        log = Path(tmp) / "console.txt"
        path.write_text(text)
        try:
            with _stdout_to(log):
                system = moordyn.Create(str(path))
        except RuntimeError as exc:
            raise MoorDynError(f"moordyn.Create failed: {exc}{_console_tail(log)}") from exc
        try:
            # errors only from here on (the banner and input echo went to the file above)
            moordyn.SetVerbosity(system, moordyn.LEVEL_ERR)
            if moordyn.NCoupledDOF(system) != x0.size:
                raise MoorDynError(f"expected {x0.size} coupled DOF, MoorDyn has "
                                   f"{moordyn.NCoupledDOF(system)}")
            try:
                with _stdout_to(log):
                    status = moordyn.Init(system, _as_list(x0), _as_list(v0))
            except RuntimeError as exc:
                raise MoorDynError(f"moordyn.Init failed: {exc}{_console_tail(log)}") from exc
            if status != moordyn.ERRCODE_SUCCESS:
                raise MoorDynError(f"moordyn.Init returned error code {status}"
                                   f"{_console_tail(log)}")
            yield system, log
        finally:
            moordyn.Close(system)


@contextlib.contextmanager
def _open_system(line: MoorDynLine, *, segments: int, dt: float, position: np.ndarray | None,
                 velocity: np.ndarray | None, ic_max_time: float, time_scheme: str,
                 extra_options: dict[str, object] | None) -> Iterator[tuple[object, Path]]:
    """Created and initialised system and the file MoorDyn's console was sent to."""
    x0 = np.asarray(line.fairlead if position is None else position, dtype=float)
    v0 = np.zeros(3) if velocity is None else np.asarray(velocity, dtype=float)
    if x0.shape != (3,) or v0.shape != (3,):
        raise ValueError("position and velocity must be 3-vectors")
    text = moordyn_input(line, segments=segments, dt=dt, fairlead=tuple(x0),
                         ic_max_time=ic_max_time, time_scheme=time_scheme,
                         extra_options=extra_options)
    with open_input(text, x0, v0) as opened:
        yield opened


@contextlib.contextmanager
def moordyn_system(line: MoorDynLine, *, segments: int, dt: float,
                   position: np.ndarray | None = None, velocity: np.ndarray | None = None,
                   ic_max_time: float = IC_MAX_TIME, time_scheme: str = TIME_SCHEME,
                   extra_options: dict[str, object] | None = None) -> Iterator[object]:
    """A created and initialised MoorDyn system for ``line`` (fairlead at ``position``, default
    the line's, moving at ``velocity``, default 0), closed on exit. MoorDyn's line is
    ``moordyn.GetLine(system, 1)``, its fairlead its last node (index ``segments``); MoorDyn
    prints its errors to the console while the caller drives it."""
    with _open_system(line, segments=segments, dt=dt, position=position, velocity=velocity,
                      ic_max_time=ic_max_time, time_scheme=time_scheme,
                      extra_options=extra_options) as (system, _):
        yield system


def _check_motion(time: np.ndarray, position: np.ndarray,
                  velocity: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    t = np.asarray(time, dtype=float)
    x = np.asarray(position, dtype=float)
    v = np.asarray(velocity, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise ValueError("time must be 1-D with at least 2 samples")
    if x.ndim != 2 or x.shape[0] != t.size or v.shape != x.shape:
        raise ValueError(f"position and velocity must have the same shape ({t.size}, dofs), "
                         f"got {x.shape} and {v.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(x)) and np.all(np.isfinite(v))):
        raise ValueError("time, position and velocity must be finite")
    step = (t[-1] - t[0]) / (t.size - 1)
    if not step > 0.0:
        raise ValueError("time must increase")
    if abs(t[0]) > _UNIFORM_RTOL * step:
        raise ValueError(f"time must start at 0, got {t[0]}")
    if np.max(np.abs(np.diff(t) - step)) > _UNIFORM_RTOL * step:
        raise ValueError("time must be uniformly sampled")
    return t, x, v, float(step)


def _coupling_path(x: np.ndarray, v: np.ndarray, step: float,
                   substeps: int) -> tuple[np.ndarray, np.ndarray]:
    """Start positions and secant velocities of the coupling intervals, ``substeps`` per sample
    interval, the intermediate points by cubic Hermite interpolation of (x, v), (n, dofs)
    each."""
    if substeps == 1:
        return x[:-1], np.diff(x, axis=0) / step
    s = np.arange(substeps + 1) / substeps  # local coordinate in [0, 1]
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    pts = (h00[None, :, None] * x[:-1, None, :] + h10[None, :, None] * step * v[:-1, None, :]
           + h01[None, :, None] * x[1:, None, :] + h11[None, :, None] * step * v[1:, None, :])
    start = pts[:, :-1, :].reshape(-1, x.shape[1])
    secant = (np.diff(pts, axis=1) / (step / substeps)).reshape(-1, x.shape[1])
    return start, secant


def run_moordyn_forced(line: MoorDynLine, time: np.ndarray, position: np.ndarray,
                       velocity: np.ndarray, *, segments: int, dt: float, output_every: int = 1,
                       substeps: int = 1, ic_max_time: float = IC_MAX_TIME,
                       time_scheme: str = TIME_SCHEME,
                       extra_options: dict[str, object] | None = None,
                       ) -> tuple[np.ndarray, np.ndarray, float]:
    """Drive MoorDyn's fairlead (a coupled point) along a prescribed path.

    Parameters
    ----------
    line
        The line.
    time
        Sample times [s], shape (n,), uniform, starting at 0.
    position, velocity
        Fairlead position [m] and velocity [m/s] at ``time``, shape (n, 3). MoorDyn computes its
        initial static state with the fairlead at ``position[0]``.
    segments
        Number of MoorDyn line segments.
    dt
        MoorDyn's internal time step dtM [s]; it sub-steps each sample interval at ``dt`` (the
        last sub-step shorter if the interval is not a multiple of ``dt``).
    output_every
        Return every ``output_every``-th sample (``time[::output_every]``).
    substeps
        Coupling intervals per sample interval. 1: the fairlead follows the piecewise-linear
        interpolant of ``position`` (``velocity`` is then used only at t = 0); > 1: the
        cubic-Hermite interpolant of (``position``, ``velocity``), linear between its
        ``substeps`` sub-points.
    ic_max_time
        MoorDyn's TmaxIC [s] (pseudo-time of its stationary initial-condition solver).
    time_scheme
        MoorDyn's tScheme.
    extra_options
        More MoorDyn options, ``{name: value}``, written after (so overriding) the harness's.

    Returns
    -------
    times : ndarray
        Output times [s], ``time[::output_every]``.
    tension : ndarray
        Fairlead tension magnitudes [N] at those times: the norm of the force MoorDyn returns on
        the coupled fairlead (module docstring).
    wall : float
        Wall-clock seconds spent in ``moordyn.Step`` (initialisation excluded).

    Raises
    ------
    MoorDynError
        If MoorDyn rejects the input, fails to initialise, or its integration fails (NaN).
    """
    import moordyn

    if output_every < 1 or substeps < 1:
        raise ValueError("output_every and substeps must be >= 1")
    t, x, v, step = _check_motion(time, position, velocity)
    start, secant = _coupling_path(x, v, step, substeps)
    dt_c = step / substeps
    starts = [_as_list(p) for p in start]
    vels = [_as_list(p) for p in secant]
    t_starts = [float(c) for c in np.arange(start.shape[0]) * dt_c]
    n_out = (t.size - 1) // output_every + 1
    tension = np.empty(n_out)
    step_fn = moordyn.Step
    with _open_system(line, segments=segments, dt=dt, position=x[0], velocity=v[0],
                      ic_max_time=ic_max_time, time_scheme=time_scheme,
                      extra_options=extra_options) as (system, log):
        force = moordyn.Step(system, _as_list(x[0]), _as_list(v[0]), 0.0, 0.0)  # no step
        tension[0] = math.sqrt(sum(c * c for c in force))
        every = output_every * substeps
        k = 0
        i = 0
        try:
            with _stdout_to(log):  # MoorDyn's error lines go into the exception, not the console
                wall_start = _time.perf_counter()
                for i in range(len(starts)):
                    force = step_fn(system, starts[i], vels[i], t_starts[i], dt_c)
                    if (i + 1) % every == 0:
                        k += 1
                        tension[k] = math.sqrt(force[0] ** 2 + force[1] ** 2 + force[2] ** 2)
                wall = _time.perf_counter() - wall_start
        except RuntimeError as exc:
            raise MoorDynError(f"MoorDyn failed near t = {t_starts[i]:.6g} s ({segments} "
                               f"segments, dt = {dt:g} s): {exc}{_console_tail(log)}") from exc
    if not np.all(np.isfinite(tension)):
        raise MoorDynError("MoorDyn returned a non-finite fairlead force")
    return t[::output_every].copy(), tension, wall
