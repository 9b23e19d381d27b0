"""Static line tension against the minimum breaking load (MBL) of the line type, before a run
(a run's largest tension against the MBL: :mod:`floatmoor.post.run_strength`).

``floatmoor check`` and ``floatmoor run`` solve each line's static catenary at the mean (or
rest) fairlead position. The fairlead tension is the largest along a static line that sinks
(the effective tension grows with height by the weight of the line above), so it is the one
compared with the MBL. A static tension at or above the MBL is bad input: the line would
break before anything moves.

Without an MBL the tension cannot be checked, but the axial strain T / EA at the fairlead can
be judged: above :data:`STRAIN_WARNING_WITHOUT_MBL` the line would already have broken if it
were chain or HMPE rope, so ``check`` prints a warning asking for the MBL (not an error: fibre
ropes such as polyester and nylon do stretch that far before breaking).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from floatmoor.case.schema import Case
from floatmoor.errors import CaseError, SolverError
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.mooring.statics_solver import StaticSolution, case_statics

__all__ = ["StaticLineLoad", "static_line_loads", "system_statics_at_rest", "check_static_below_mbl",
           "refuse_static_breaking", "strain_warnings", "STRAIN_WARNING_WITHOUT_MBL"]

#: Static fairlead strain T / EA above which a line without an MBL gets a warning [-].
#: The linear-elastic strain at the MBL, MBL / EA, is about 1 % for studless chain (0.8 % for
#: grade R3 at 150 mm to 1.4 % for R5 at 76 mm: MBL of DNV-OS-E302, EA of DNV-OS-E301 as
#: fitted in NREL MoorPy's MoorProps_default.yaml) and 1.8 % for HMPE rope, but 7 % for
#: polyester and ~20 % for nylon (quasi-static EA / MBL of 56.5, 14 and 5 in the same file).
#: 2 % is beyond the breaking strain of chain and HMPE and within that of polyester and
#: nylon, which is why it is a warning and not an error.
STRAIN_WARNING_WITHOUT_MBL = 0.02


@dataclass(frozen=True)
class StaticLineLoad:
    """Static catenary of one line at its mean fairlead position, against its MBL.

    ``fairlead_tension``, ``anchor_tension`` and ``laid_length`` are None (and ``failure``
    says why) when the static solution failed.
    """

    line: str
    line_type: str
    axial_stiffness: float  #: EA [N]
    minimum_breaking_load: float | None  #: [N]
    fairlead_tension: float | None = None  #: [N]
    anchor_tension: float | None = None  #: [N]
    laid_length: float | None = None  #: [m]
    failure: str = ""

    @property
    def strain(self) -> float | None:
        """Axial strain at the fairlead, T / EA [-]."""
        if self.fairlead_tension is None:
            return None
        return self.fairlead_tension / self.axial_stiffness

    @property
    def tension(self) -> float | None:
        """The larger end tension [N]: the fairlead's for a line that sinks (the effective
        tension grows with height), either end's for a section between free points."""
        if self.fairlead_tension is None or self.anchor_tension is None:
            return None
        return max(self.fairlead_tension, self.anchor_tension)

    @property
    def ratio(self) -> float | None:
        """Largest end tension over the MBL [-]."""
        if self.tension is None or self.minimum_breaking_load is None:
            return None
        return self.tension / self.minimum_breaking_load

    @property
    def safety_factor(self) -> float | None:
        """MBL over the fairlead tension [-]."""
        if self.tension is None or self.minimum_breaking_load is None:
            return None
        if self.tension <= 0.0:
            return math.inf
        return self.minimum_breaking_load / self.tension


def static_line_loads(case: Case) -> list[StaticLineLoad]:
    """The static catenary of every independent line of ``case`` at its mean (or rest)
    fairlead, then every section of the other lines from the system's static equilibrium
    (:func:`system_statics_at_rest`).

    What ``floatmoor check`` prints and ``run`` checks against the MBL before anything moves
    (docs/guide/running.md#line-strength): a static tension at or above it is bad input. A
    line or section without a static solution is listed with the failure, not raised, so
    that the others are still reported.

    Parameters
    ----------
    case
        A validated case.

    Returns
    -------
    list of StaticLineLoad
        The independent lines in file order, then the other lines' sections (named by
        their labels): tensions [N] and laid length [m], or ``failure`` saying why there
        is no static solution.
    """
    out = []
    for line in case.lines:
        if not case.is_independent(line):
            continue
        base = dict(line=line.name, line_type=line.line_type.name,
                    axial_stiffness=line.line_type.axial_stiffness,
                    minimum_breaking_load=line.line_type.minimum_breaking_load)
        try:
            sol = QuasiStaticLine.from_case(line, case.environment, case.seabed).solve(
                np.asarray(line.fairlead))
        except SolverError as err:
            out.append(StaticLineLoad(**base, failure=str(err)))
            continue
        out.append(StaticLineLoad(**base, fairlead_tension=float(sol.fairlead_tension),
                                  anchor_tension=float(sol.anchor_tension),
                                  laid_length=float(sol.laid_length)))
    return out + _section_loads(case)


def system_statics_at_rest(case: Case) -> StaticSolution | None:
    """The static equilibrium at rest of the lines that are not independent (every model:
    the equilibrium is the same physics), or None when every line is independent.

    Raises
    ------
    SolverError
        When there is none (naming the point), or a section floats.
    """
    statics = case_statics(case)
    return None if statics is None else statics.solve()


def _section_loads(case: Case) -> list[StaticLineLoad]:
    sections = [s for ln in case.lines if not case.is_independent(ln) for s in ln.sections]
    try:
        solution = system_statics_at_rest(case)
    except SolverError as err:
        solution, failure = None, str(err)
    out = []
    for s in sections:
        base = dict(line=s.label, line_type=s.line_type.name,
                    axial_stiffness=s.line_type.axial_stiffness,
                    minimum_breaking_load=s.line_type.minimum_breaking_load)
        if solution is None:
            out.append(StaticLineLoad(**base, failure=failure))
            continue
        j = solution.section_names.index(s.label)
        out.append(StaticLineLoad(**base, fairlead_tension=float(solution.end_tension[j]),
                                  anchor_tension=float(solution.start_tension[j]),
                                  laid_length=float(solution.laid_length[j])))
    return out


def check_static_below_mbl(case: Case, loads: list[StaticLineLoad]) -> None:
    """Refuse a line whose static fairlead tension reaches its MBL.

    Raises
    ------
    CaseError
        Naming the line, its type's ``minimum_breaking_load`` key, the tension and the MBL.
    """
    for load in loads:
        ratio = load.ratio
        if ratio is not None and ratio >= 1.0:
            what = "section" if "[" in load.line else "line"
            raise CaseError(case.source, f"line_types.{load.line_type}.minimum_breaking_load",
                            f"a minimum breaking load above the static tension of "
                            f"{what} '{load.line}' ({load.tension:.6g} N)",
                            f"{load.minimum_breaking_load!r} N (T / MBL = {ratio:.3g}: the "
                            "line breaks at rest)")


def refuse_static_breaking(case: Case) -> None:
    """:func:`check_static_below_mbl` for a case about to run; no work when no line type
    gives an MBL.

    Raises
    ------
    CaseError
        As :func:`check_static_below_mbl`.
    """
    if any(s.line_type.minimum_breaking_load is not None for s in case.sections):
        check_static_below_mbl(case, static_line_loads(case))


def strain_warnings(loads: list[StaticLineLoad]) -> list[str]:
    """Warnings for lines without an MBL whose static strain is beyond
    :data:`STRAIN_WARNING_WITHOUT_MBL`."""
    out = []
    for load in loads:
        strain = load.strain
        if load.minimum_breaking_load is None and strain is not None \
                and strain > STRAIN_WARNING_WITHOUT_MBL:
            out.append(f"warning: line '{load.line}' is stretched {strain:.1%} at the fairlead "
                       f"(T / EA), beyond the ~1-2 % at which chain and HMPE rope break; give "
                       f"line_types.{load.line_type}.minimum_breaking_load to check its "
                       "tension")
    return out
