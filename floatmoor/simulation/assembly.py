"""A case assembled once into the moored system a run advances.

:func:`assemble` turns a validated case into a :class:`MooredSystem`: its points, its lines
(each model object built from the line's sections), and for a case with a ``[floater]`` the
Cummins body on those lines at its static equilibrium, the sea, and the loads on the body
other than the lines (:class:`BodyLoads`: ramped wave excitation, second-order wave loads,
rotor thrust, Morison drag).
The forced-motion and coupled runs take that object and only step and record it; nothing in
their time loops builds models.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.body.kinematics import generalised_force, points_state
from floatmoor.body.model import build_body
from floatmoor.body.morison import MorisonDrag
from floatmoor.case.coupling import CoupledCase
from floatmoor.case.schema import Case, Point
from floatmoor.case.sea import WaveCase
from floatmoor.errors import CaseError, FloatmoorError, FloatmoorWarning, SolverError
from floatmoor.hydro.database import load_for_case
from floatmoor.hydro.excitation_transfer import ExcitationInterpolator
from floatmoor.hydro.second_order import (
    DirectionError, DriftLookup, QTFLookup, drift_source, missing_coefficients, route_text,
)
from floatmoor.hydro.state_space.storage import has_state_space
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.quasidynamic import QuasiDynamicLine
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.mooring.statics_solver import case_statics
from floatmoor.mooring.stepping import PathStepper
from floatmoor.motion.rigid_body import prescribed_fairlead_state, start_line
from floatmoor.simulation.coupled import MooredBody, equilibrium
from floatmoor.simulation.groups import SystemGroup, body_point_line, system_groups
from floatmoor.waves.excitation_series import WaveExcitation
from floatmoor.waves.realisation import WaveField, realise_sea
from floatmoor.waves.second_order import (
    MeanDriftForce, NewmanForce, QTFForce, SecondOrderForce, newman_on_grid,
)
from floatmoor.wind.force import RotorThrust

__all__ = ["MooredSystem", "BodyLoads", "assemble", "build_line_models", "CoupledSettings",
           "settings_from_case", "key_origin", "start_positions", "refuse_long_runs"]

_MODELS = {"quasi-static": QuasiStaticLine.from_case,
           "quasi-dynamic": QuasiDynamicLine.from_case, "dynamic": DynamicLine.from_case}


@dataclass(frozen=True)
class CoupledSettings:
    """Options of a coupled run that its case file does not give. What the case gives (the
    body step, the sea, the initial offset) the run takes from the case itself
    (:class:`floatmoor.case.coupling.CoupledCase`), checked once by its reader."""

    database: str | Path | None = None  #: default: hydrodb/<hydro.database>.nc
    linear_damping: NDArray[np.float64] | None = None  #: B_1 (6, 6)
    quadratic_damping: NDArray[np.float64] | None = None  #: B_2 (6, 6)


def settings_from_case(case: Case) -> CoupledSettings:
    """The options of a plain run of ``case``: none beyond the case (its database, no
    additional damping)."""
    return CoupledSettings()


def build_line_models(case: Case) -> list[PathStepper | None]:
    """One model object per independent line (one section from a fixed to a body point), as
    the case chooses; None for the lines of a system group (:mod:`.groups`). Each starts with
    its fairlead where the case's motion puts it at t = 0 (:func:`~floatmoor.motion.rigid_body.
    start_line`); a quasi-dynamic line whose fairlead moves then starts in that motion
    (:meth:`QuasiDynamicLine.start_moving`, docs/theory/quasi_dynamic.md#the-start-of-a-run)."""
    models: list[PathStepper | None] = []
    for line in case.lines:
        if not case.is_independent(line):
            models.append(None)
            continue
        model = _MODELS[line.model](start_line(case.motion, line), case.environment,
                                    case.seabed)
        if case.motion is not None:
            model.start_moving(
                lambda t, line=line: prescribed_fairlead_state(case.motion, line, t),
                case.simulation.output_interval)
        models.append(model)
    return models


def start_positions(case: Case) -> dict[str, NDArray[np.float64]] | None:
    """The body points of the lines solved as systems that the case's motion moves at t = 0,
    name -> position there [m] (None when it moves none: the groups start at rest)."""
    if case.motion is None:
        return None
    used = {n for line in case.lines if not case.is_independent(line)
            for s in line.sections for n in (s.start, s.end)}
    moved = {}
    for point in case.points:
        if point.kind != "body" or point.name not in used:
            continue
        position = prescribed_fairlead_state(case.motion, body_point_line(case, point.name),
                                             np.zeros(1))[0][0]
        if not np.array_equal(position, np.asarray(point.position, dtype=float)):
            moved[point.name] = position
    return moved or None


def refuse_long_runs(case: Case, models: Sequence[PathStepper | None],
                     groups: Sequence[SystemGroup] = ()) -> None:
    """Refuse, before the first step, a dynamic line (or a system's line with the shortest
    step) whose explicit steps over the run would exceed ``MAX_DYNAMIC_STEPS``
    (:meth:`DynamicLine.refuse_long_work`).

    Raises
    ------
    CaseError
    """
    what = f"the run (simulation.duration {case.simulation.duration:g} s)"
    for model in [*models, *(g.solver for g in groups)]:
        if model is not None:
            model.refuse_long_work(case.simulation.duration, what, case.source)


def key_origin(case: Case, key: str) -> str:
    """The case file, with the ``--set`` that last set ``key`` (or a table above it)."""
    origin = case.source
    for text in case.overrides:
        path = text.split("=", 1)[0].strip()
        if key == path or key.startswith(path + "."):
            origin = f"{case.source} (--set {text})"
    return origin


class BodyLoads:
    """The loads on the body other than its lines: the wave excitation (with its cosine ramp),
    the second-order wave loads (their mean unramped, the rest ramped with the square of the
    wave ramp: docs/theory/hydrodynamics.md#the-ramp-and-the-start), the rotor thrust
    (unramped: the body starts at the mean-thrust equilibrium) and the Morison drag, each
    tabulated at the body's half-steps of a chunk by :meth:`prepare` and looked up by
    :meth:`__call__` at the Runge-Kutta stage times."""

    def __init__(self, excitation: WaveExcitation | None, rotor: RotorThrust | None,
                 drag: MorisonDrag | None, ramp_duration: float, time_step: float,
                 second_order: SecondOrderForce | None = None) -> None:
        self.excitation = excitation
        self.rotor = rotor
        self.drag = drag
        self.second_order = second_order
        self.ramp_duration = float(ramp_duration)
        self.time_step = float(time_step)
        self._t0 = math.nan
        self._wave = np.zeros((1, 6))
        self._drift = np.zeros((0, 6))

    def ramp(self, t: float) -> float:
        """The excitation's cosine ramp factor at ``t`` [-]."""
        ramp = self.ramp_duration
        if ramp <= 0.0 or t >= ramp:
            return 1.0
        return 0.5 - 0.5 * math.cos(math.pi * t / ramp)

    def prepare(self, t0: float, steps: int) -> None:
        """Tabulate the loads at the half-steps of ``steps`` body steps from ``t0``."""
        h = 0.5 * self.time_step
        self._t0 = t0
        if self.excitation is not None:
            self._wave = self.excitation.series(t0 + h * np.arange(2 * steps + 1))
        if self.second_order is not None:
            self._drift = self.second_order.series(t0 + h * np.arange(2 * steps + 1))
        if self.rotor is not None:
            self.rotor.prepare(t0, 2 * steps + 1, h)
        if self.drag is not None:
            self.drag.prepare(t0, 2 * steps + 1, h, ramp=self.ramp)

    def __call__(self, t: float, x: NDArray[np.float64], v: NDArray[np.float64]
                 ) -> NDArray[np.float64]:
        """The 6-DOF load at stage time ``t`` (a half-step of the prepared chunk) [N, N m]."""
        k = int(round((t - self._t0) / (0.5 * self.time_step)))
        f = self.ramp(t) * self._wave[k] if self.excitation is not None else np.zeros(6)
        if self.second_order is not None:
            f = f + self._ramped_drift(t, self._drift[k])
        if self.rotor is not None:
            f = f + self.rotor.force(k, x, v)
        if self.drag is not None:
            f = f + self.drag.force(k, x, v)
        return f

    def _ramped_drift(self, t: float, value: NDArray[np.float64]) -> NDArray[np.float64]:
        mean = self.second_order.mean
        return mean + self.ramp(t) ** 2 * (value - mean)

    def second_order_force(self, t: float) -> NDArray[np.float64]:
        """The second-order wave load applied at ``t`` [N, N m] (6,): from the prepared chunk
        at its half-steps, evaluated directly otherwise (before the first chunk)."""
        if self.second_order is None:
            raise ValueError("the body has no second-order wave loads")
        k = (t - self._t0) / (0.5 * self.time_step)
        j = int(round(k)) if math.isfinite(k) else -1
        if 0 <= j < len(self._drift) and abs(k - j) < 1e-6:
            return self._ramped_drift(t, self._drift[j])
        return self._ramped_drift(t, self.second_order(t))


@dataclass
class MooredSystem:
    """A case's mooring system, and its floater when it has one, ready to run.

    Attributes
    ----------
    case
        The case it was assembled from.
    points
        Every point of the system (``case.points``).
    line_models
        Forced-motion runs: the model of each independent line (None for a line of a system
        group); empty for a floater case, whose lines are in ``moored``.
    groups
        Forced-motion runs: the lines joined through free points or of several sections,
        with their solvers (:func:`~floatmoor.simulation.groups.system_groups`).
    moored
        The body on its lines (started at its equilibrium plus the initial offset), or None.
    loads
        The body's loads other than the lines, or None.
    sea
        The wave field of a coupled run, or None.
    equilibrium
        The body's static equilibrium on its lines (6,) [m, rad], or None; with second-order
        wave loads it includes their mean.
    database
        The hydrodynamic database of the floater, or None.
    second_order
        The run's description of its second-order wave loads (result attributes), empty
        without them.
    """

    case: Case
    points: tuple[Point, ...]
    line_models: list[PathStepper | None] = field(default_factory=list)
    groups: list[SystemGroup] = field(default_factory=list)
    moored: MooredBody | None = None
    loads: BodyLoads | None = None
    sea: WaveField | None = None
    equilibrium: NDArray[np.float64] | None = None
    database: xr.Dataset | None = None
    second_order: dict[str, str] = field(default_factory=dict)


def _excitation(sea: WaveField, ds: xr.Dataset, case: Case) -> WaveExcitation | None:
    """The first-order excitation of the sea (zero for components outside the database's
    frequencies); a direction outside the database's is refused (CaseError)."""
    if sea.n_components == 0:
        return None
    interp = ExcitationInterpolator(ds)
    w_db = ds["omega"].values
    inside = (sea.omega >= w_db[0]) & (sea.omega <= w_db[-1])
    X = np.zeros((sea.n_components, 6), dtype=complex)
    for beta in np.unique(sea.direction):
        sel = inside & (sea.direction == beta)
        if np.any(sel):
            try:
                X[sel] = interp(sea.omega[sel], float(beta))
            except ValueError as err:
                raise CaseError(key_origin(case, "waves.direction_deg"), "waves.direction_deg",
                                "a wave direction the excitation forces of "
                                f"{ds.attrs.get('path', 'the database')} cover",
                                str(err)) from None
    return WaveExcitation(sea, X)


def _second_order(case: Case, waves: WaveCase, sea: WaveField, ds: xr.Dataset
                  ) -> tuple[SecondOrderForce | None, dict[str, str]]:
    """The second-order wave force of the run and its description (result attributes), or
    (None, {}); refused before any run starts when the database cannot give it.

    Raises
    ------
    CaseError
        Naming the case file, the key, the database, what was expected and what was found.
    """
    model, route = waves.second_order, waves.drift_coefficients
    if model == "none":
        return None, {}
    path = ds.attrs.get("path", "the database")
    missing = missing_coefficients(ds, model, route)
    if missing is not None:
        if model == "full":
            raise CaseError(key_origin(case, "waves.second_order"), "waves.second_order",
                            '"none", "mean" or "newman", or "full" with a database holding '
                            "the difference-frequency QTF (qtf_difference: import it with "
                            "'floatmoor hydro import')", f'"full" with {path}, which has '
                            f"{missing}")
        other = [r for r in ("far_field", "near_field") if r != route][0]
        if missing_coefficients(ds, model, other) is None:
            raise CaseError(key_origin(case, "waves.drift_coefficients"),
                            "waves.drift_coefficients", f'"{other}", or a database holding '
                            f"the {route.replace('_', ' ')} mean drift",
                            f'"{route}" with {path}, which has {missing}')
        raise CaseError(key_origin(case, "waves.second_order"), "waves.second_order",
                        f'"none", or a database holding mean drift coefficients for "{model}" '
                        "(add them with 'floatmoor hydro build CASE --drift', or import "
                        "WAMIT .8/.9 files)", f'"{model}" with {path}, which has {missing}')
    directions = np.unique(sea.direction)
    what = "QTF" if model == "full" else f"{route.replace('_', ' ')} mean drift"
    try:
        if model == "full":
            lookup = QTFLookup(ds)
            qtf = lookup.at(float(directions[0])) if directions.size else None
            force: SecondOrderForce = QTFForce(sea, lookup.grid, qtf) if qtf is not None \
                else MeanDriftForce(sea, np.zeros((0, 6)))
        else:
            drifts = DriftLookup(ds, route)
            drift = drifts.at(sea.omega, sea.direction)  # refuses NaN where the sea needs D
            if model == "mean":
                force = MeanDriftForce(sea, drift)
            elif directions.size == 1:  # a long-crested sea: from the band amplitudes
                force = newman_on_grid(sea, drifts.omega, drifts.column(float(directions[0])))
            else:
                force = NewmanForce(sea, drift, drifts.covers(sea.omega))
    except DirectionError as err:
        raise CaseError(key_origin(case, "waves.direction_deg"), "waves.direction_deg",
                        f"a sea the {what} coefficients of {path} cover", str(err)) from None
    except ValueError as err:
        raise CaseError(key_origin(case, "waves.second_order"), "waves.second_order",
                        f'"none", or a database whose {what} coefficients are usable',
                        f'"{model}" with {path}: {err}') from None
    source = drift_source(ds)
    current = "not applicable (coefficients not computed by floatmoor)"
    if source == "floatmoor" and model != "full":
        from floatmoor.hydro.drift_build import drift_is_current

        try:
            is_current = drift_is_current(ds, case)
        except FloatmoorError as err:
            is_current, current = False, f"unknown ({err})"
        else:
            current = "yes" if is_current else "no"
        if not is_current:
            warnings.warn(f"{path}: the mean drift coefficients were computed with another "
                          f"mass or mooring than {case.source}'s (drift_inputs_hash differs); "
                          "the run uses them as they are (for this case's: 'floatmoor hydro "
                          "build CASE --drift')", FloatmoorWarning, stacklevel=3)
    attrs = {"second_order": model, "second_order_coefficients": route_text(ds, model, route),
             "drift_source": source, "drift_inputs_current": current}
    return force, attrs


def _system_force(case: Case, centre: NDArray[np.float64]
                  ) -> Callable[[NDArray[np.float64]], NDArray[np.float64]] | None:
    """The 6-DOF static force on the body of the lines solved as systems, as a function of
    the body's displacement (None without such lines); the statics warm-start from the
    last call, as the equilibrium's Newton steps are small."""
    try:
        statics = case_statics(case)
    except SolverError as err:
        raise CaseError(case.source, "lines", "a mooring system with a static equilibrium",
                        str(err)) from None
    if statics is None:
        return None
    system = statics.system
    arms = system.positions[system.body_index] - centre

    def force(x: NDArray[np.float64]) -> NDArray[np.float64]:
        positions, _ = points_state(x, np.zeros(6), arms, centre)
        try:
            solution = statics.solve(positions)
        except SolverError as err:
            raise CaseError(case.source, "lines", "a mooring system with a static "
                            "equilibrium with the floater", str(err)) from None
        return generalised_force(x, solution.point_force[system.body_index], arms)

    return force


def assemble(case: Case, settings: CoupledSettings | None = None) -> MooredSystem:
    """Assemble a case's moored system.

    Parameters
    ----------
    case
        A validated case.
    settings
        A floater case's coupled-run settings (:class:`~floatmoor.simulation.coupled_run.
        CoupledSettings`); required when the case has a ``[floater]``, ignored otherwise.

    Raises
    ------
    CaseError
        When the floater asks for a state-space radiation its database does not hold, the
        sea's direction is outside the database's, or the case asks for second-order wave
        loads the database cannot give (:func:`_second_order`).
    HydroDatabaseError
        When the floater's database is missing, damaged, stale or fails a check the case
        does not accept, or has no excitation forces for the case's waves.
    """
    if case.floater is None:
        models = build_line_models(case)
        groups = system_groups(case, start_positions(case))
        refuse_long_runs(case, models, groups)
        return MooredSystem(case=case, points=case.points, line_models=models, groups=groups)
    if settings is None:
        raise ValueError("a floater case is assembled with its CoupledSettings")
    env = case.environment
    view = CoupledCase.of(case)
    dt = view.time_step
    # the case's database, refused when missing, damaged or built from other inputs
    ds = load_for_case(case, settings.database)
    if case.floater.radiation == "state-space" and not has_state_space(ds):
        raise CaseError(key_origin(case, "floater.radiation"), "floater.radiation",
                        '"convolution", or "state-space" with a database holding a state-space '
                        "realisation of K(t) (add one with 'floatmoor hydro fit-state-space "
                        f"{case.hydro.database if case.hydro else 'NAME'}')",
                        f'"state-space" with {ds.attrs.get("path", "the database")}, which '
                        "holds none")
    sea = realise_sea(view.waves.settings, env.water_depth, env.gravity, case.simulation.duration)
    # before the body: a sea on a database without excitation forces (or without the
    # second-order coefficients the case asks for) is refused at once
    excitation = _excitation(sea, ds, case)
    second, second_attrs = _second_order(case, view.waves, sea, ds)
    body = build_body(case.floater, ds, env, dt, linear_damping=settings.linear_damping,
                      quadratic_damping=settings.quadratic_damping)
    rotor = RotorThrust(case.wind, case.simulation.duration) if case.wind is not None else None
    loads = BodyLoads(excitation, rotor, None, view.waves.ramp_duration, dt, second)
    centre = np.asarray(case.floater.reference_point, dtype=float)
    # built as for a fresh start, so that a checkpoint's state fits the same operators
    moored = MooredBody(body, case.lines, env, case.seabed, centre, loads, case=case)
    solo = np.array([case.is_independent(ln) for ln in case.lines], dtype=bool)
    mean_force = None if rotor is None else rotor.steady_force()
    if second is not None:  # the mean drift is in the start equilibrium, and unramped
        mean_force = second.mean if mean_force is None else mean_force + second.mean
    x_eq = equilibrium(body, [ln for ln, s in zip(case.lines, solo) if s],
                       moored.arms[solo] if len(solo) else moored.arms, centre, env, case.seabed,
                       mean_force=mean_force, system_force=_system_force(case, centre))
    moored.start(x_eq + np.asarray(view.initial_offset, dtype=float))
    refuse_long_runs(case, moored.models)
    moored.equilibrium_position = x_eq
    if case.floater.drag is not None:
        loads.drag = MorisonDrag(case.floater, case.floater.drag, env.water_density, sea,
                                 current=env.current_velocity, mean_displacement=x_eq)
    return MooredSystem(case=case, points=case.points, moored=moored, loads=loads, sea=sea,
                        equilibrium=x_eq, database=ds, second_order=second_attrs)
