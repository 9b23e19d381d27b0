"""What floatmoor's line solvers give a deck written for another program (the MoorDyn exporter,
:func:`floatmoor.io.moordyn.exporter.export_case`, which sits below the models and takes these
answers as an argument: docs/development.md#1-package-layout-and-import-order).

* each section with the DG discretisation it runs with, stepped explicitly: where the case
  leaves it to the accuracy, :func:`floatmoor.mooring.dg.resolution.resolve_settings` as the
  run makes it (an independent line's rule on its catenary, a line system's sections' own);
* the smallest DG time step of those sections (:meth:`CableProperties.time_step`, the function
  the DG line steps with: the axial wave, explicit internal damping and explicit seabed
  contact, ``max_time_step``);
* the free points' static equilibrium (:func:`floatmoor.mooring.statics_solver.case_statics`,
  body points at rest), or why there is none.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from floatmoor.errors import SolverError
from floatmoor.io.moordyn.exporter import DeckNumerics
from floatmoor.mooring.dg.cable import CableProperties
from floatmoor.mooring.dg.resolution import resolve_settings
from floatmoor.mooring.statics_solver import case_statics

__all__ = ["deck_numerics"]


def _explicit_numerics(section: Any, line: Any, independent: bool, env: Any, bed: Any) -> Any:
    """The section with the DG discretisation it runs with, stepped explicitly."""
    st = section.dynamic
    if not st.resolved:
        speed = 0.0
        if independent:
            speed = CableProperties.from_section(section, env, bed).transverse_wave_speed(
                np.asarray(line.anchor, dtype=float), np.asarray(line.fairlead, dtype=float))
        st = resolve_settings(st, section.length, speed, several_sections=not independent)
    return replace(section, dynamic=replace(st, time_integration="explicit"))


def _statics(case: Any) -> tuple[dict[str, tuple[float, float, float]] | None, str | None]:
    """(free points' positions at the static equilibrium or None, why there is none or None)."""
    free = [p.name for p in case.points if p.kind == "free"]
    if not free:
        return None, None
    try:
        statics = case_statics(case)
        solution = statics.solve() if statics is not None else None
    except SolverError as exc:
        return None, " ".join(str(exc).split())
    if solution is None:
        return None, None
    return {n: tuple(float(c) for c in solution.position(n))  # type: ignore[misc]
            for n in free if n in solution.point_names}, None


def deck_numerics(case: Any) -> DeckNumerics:
    """The solvers' answers a deck of ``case`` (a :class:`floatmoor.case.schema.Case`) is
    written with (see the module's docstring).

    Raises
    ------
    SolverError
        A section's discretisation or time step cannot be had (the statics' failure is
        returned, not raised: the deck keeps the case's positions).
    """
    free_positions, failure = _statics(case)
    env, bed = case.environment, case.seabed
    line_of = {line.name: line for line in case.lines}
    sections = tuple(_explicit_numerics(s, line_of[s.line], case.is_independent(line_of[s.line]),
                                        env, bed) for s in case.sections)
    time_step = min(CableProperties.from_section(sec, env, bed).time_step(sec.dynamic)
                    for sec in sections)
    return DeckNumerics(sections=sections, time_step=time_step, free_positions=free_positions,
                        statics_failure=failure)
