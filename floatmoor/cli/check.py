"""``floatmoor check CASE``: validate a case and print what follows from it (static
tensions against the breaking loads, the discretisation of dynamic lines, the floater, its
database, the motion and the dimensionless groups)."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING

from floatmoor.case.load import load_case  # numpy loads here, with the command (floatmoor.cli)
from floatmoor.case.schema import Case
from floatmoor.cli.status import EXIT_OK
from floatmoor.terminal_text import MESSAGE_LIMIT, shown

if TYPE_CHECKING:
    from floatmoor.mooring.static_strength import StaticLineLoad

__all__ = ["check_command"]


def check_command(args: argparse.Namespace) -> int:
    """``floatmoor check``: load the case, print what follows from it; the exit status."""
    from floatmoor.mooring.static_strength import check_static_below_mbl, static_line_loads

    import warnings

    from floatmoor.errors import ImplausibleInputWarning

    with warnings.catch_warnings(record=True) as implausible:  # printed with the case
        warnings.simplefilter("always", ImplausibleInputWarning)
        case = load_case(args.case, args.overrides)
    mesh_rows = _check_mesh(case)
    loads = static_line_loads(case)
    check_static_below_mbl(case, loads)
    description = _describe(case, loads)  # (may still refuse the case: a line's settle)
    print(f"{shown(args.case)}: valid case \"{shown(case.title)}\"")
    for w in implausible:
        if issubclass(w.category, ImplausibleInputWarning):
            print(f"  warning: {shown(str(w.message), MESSAGE_LIMIT)}")
        else:  # not ours: as it would have been shown
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    print(description)
    if mesh_rows:
        print("\n".join(mesh_rows))
    return EXIT_OK


def _check_mesh(case: Case) -> list[str]:
    """For a hull read from a mesh file that ``hydro build`` will solve on: read it and run
    the mesh checks as the build does before solving (floatmoor.hydro.build.checked_mesh),
    so that ``check`` refuses what the build would refuse without solving
    (:class:`floatmoor.io.bem_data.BemFileError`); the build's summary of the mesh."""
    if case.floater is None or case.hydro is None or case.hydro.source != "bem" \
            or case.floater.geometry is None or case.floater.geometry.kind != "mesh":
        return []
    from floatmoor.hydro.build import checked_mesh
    from floatmoor.hydro.mesh_checks import summary_lines

    checked = checked_mesh(case.floater, case.hydro, case.environment)
    info = checked.mesh.source.as_dict()
    return [f"  {row}" for row in summary_lines(info, [c.as_dict()
                                                       for c in checked.mesh_checks or ()])]


def _describe_system(case: Case) -> list[str]:
    """The static equilibrium at rest of the lines joined through free points or of several
    sections: point positions and net loads, section end tensions and laid lengths."""
    import numpy as np

    from floatmoor.errors import SolverError
    from floatmoor.mooring.static_strength import system_statics_at_rest

    try:
        sol = system_statics_at_rest(case)
    except SolverError as err:
        return [f"  mooring system: no static solution: {err}"]
    if sol is None:
        return []
    rows = [f"  mooring system at rest ({sol.iterations} Newton iterations, force residual "
            f"{sol.residual:.2g}):",
            f"    {'point':<18}{'kind':<7}{'x [m]':>10}{'y [m]':>10}{'z [m]':>10}"
            f"{'F_lines [kN]':>14}{'seabed [kN]':>13}"]
    kinds = {p.name: p.kind for p in case.points}
    for k, name in enumerate(sol.point_names):
        x, y, z = sol.positions[k]
        seabed = f"{sol.seabed_reaction[k] / 1e3:>13.4g}" if sol.on_seabed[k] else f"{'-':>13}"
        rows.append(f"    {name:<18}{kinds[name]:<7}{x:>10.3f}{y:>10.3f}{z:>10.3f}"
                    f"{np.linalg.norm(sol.point_force[k]) / 1e3:>14.4g}{seabed}")
    rows.append(f"    {'section':<18}{'type':<12}{'profile':<11}{'T_start [kN]':>13}"
                f"{'T_end [kN]':>12}{'on seabed [m]':>15}")
    types = {s.label: s.line_type.name for s in case.sections}
    for j, name in enumerate(sol.section_names):
        rows.append(f"    {name:<18}{types[name]:<12}{sol.profile_types[j]:<11}"
                    f"{sol.start_tension[j] / 1e3:>13.5g}{sol.end_tension[j] / 1e3:>12.5g}"
                    f"{sol.laid_length[j]:>15.4g}")
    return rows


def _describe(case: Case, loads: list[StaticLineLoad]) -> str:
    """Derived quantities: weights, wave speeds, static tensions at the mean position against
    the minimum breaking loads, and the discretisation and time step of dynamic lines."""
    from floatmoor.motion.rigid_body import start_line
    from floatmoor.mooring.dg.line import DynamicLine
    from floatmoor.mooring.static_strength import strain_warnings

    rows = [f"  {'line':<14}{'model':<14}{'length':>9}{'span':>9}{'w [N/m]':>10}"
            f"{'c_axial':>10}{'T_fair':>11}{'T_anch':>11}{'on seabed':>11}"]
    notes = []
    by_name = {load.line: load for load in loads}
    for line in case.lines:
        if not case.is_independent(line):
            types = " + ".join(f"{s.line_type.name} {s.length:g} m" for s in line.sections)
            rows.append(f"  {line.name:<14}{line.model:<14}{line.length:>9.4g}"
                        f"{line.span:>9.4g}  system: {types} (statics below)")
            continue
        load = by_name[line.name]
        if load.failure:
            static = f"  static solution failed: {load.failure}"
        else:
            static = (f"{load.fairlead_tension:>11.5g}{load.anchor_tension:>11.5g}"
                      f"{load.laid_length:>11.4g}")
        rows.append(f"  {line.name:<14}{line.model:<14}{line.length:>9.4g}{line.span:>9.4g}"
                    f"{line.line_type.weight_in_water(case.environment):>10.4g}"
                    f"{line.line_type.axial_wave_speed:>10.4g}{static}")
        if line.model == "dynamic":
            # as the run builds it: in the motion's pose at t = 0
            dg = DynamicLine.from_case(start_line(case.motion, line), case.environment,
                                       case.seabed)
            st, given = dg.settings, line.dynamic
            implicit = (f"implicit steps of at most {dg.time_step:.3g} s (accuracy "
                        f"{100 * st.accuracy:g} % of the fairlead tension)")
            if st.time_integration == "explicit":
                steps = f"time step {dg.time_step:.3g} s (cfl {st.cfl:g})"
            elif dg.auto is None:
                steps = implicit
            else:
                steps = (f"{implicit} or explicit steps of {dg.auto.explicit_step:.3g} s "
                         f"(cfl {st.cfl:g}), whichever cost less, period by period")
            chosen = ("" if given.elements is not None and given.order is not None
                      else f", chosen for {100 * st.accuracy:g} % accuracy")
            notes.append(f"  {line.name}: {st.elements} elements of order {st.order} "
                         f"({st.elements * (st.order + 1)} nodes{chosen}), {steps}, seabed "
                         f"contact {st.seabed_contact}")
    notes.extend(_describe_system(case))
    rows.append("  (m, N, m/s; tensions of the static catenary at the mean fairlead position)")
    rows.extend(notes)
    rows.append(f"  {'line':<14}{'T_fair [N]':>12}{'strain T/EA':>13}{'MBL [N]':>12}"
                f"{'T/MBL':>9}{'safety factor':>15}")
    for load in loads:
        if load.failure:
            rows.append(f"  {load.line:<14}  no static solution: tension and strain unknown")
            continue
        mbl = load.minimum_breaking_load
        strain = f"{100.0 * load.strain:.3g} %"
        rows.append(f"  {load.line:<14}{load.fairlead_tension:>12.5g}{strain:>13}"
                    + (f"{mbl:>12.5g}{load.ratio:>9.4g}{load.safety_factor:>15.4g}"
                       if mbl is not None else f"{'no MBL':>12}{'-':>9}{'-':>15}"))
    rows.append("  (static fairlead tension against the minimum breaking load of the line "
                "type; safety factor = MBL / T)")
    rows.extend(f"  {w}" for w in strain_warnings(loads))
    if case.floater is not None:
        fl = case.floater
        geo = fl.geometry
        if geo is None:
            kind = "no hull geometry (hydrostatics from the imported database)"
        else:
            kind = (f"mesh {geo.file} ({geo.format}, {geo.length_unit}, SHA-256 "
                    f"{geo.sha256[:12]}, symmetry {', '.join(geo.symmetry) or 'none'}, "
                    f"{len(geo.columns)} Morison columns, {len(geo.members)} members)") \
                if geo.kind == "mesh" else geo.kind
        rows.append(f"  floater: {fl.name}, {kind}, mass {fl.mass:.6g} kg, centre of "
                    f"mass z = {fl.centre_of_mass[2]:.6g} m"
                    + (f", draft {geo.draft:.6g} m" if geo is not None and geo.kind == "cylinder"
                       else "") + f", radiation {fl.radiation}")
        rows.append("  (line fairleads: body-fixed points at rest)")
    if case.hydro is not None:
        accepted = case.hydro.accept_failed_checks
        built = (f"{len(case.hydro.frequencies)} frequencies, {len(case.hydro.directions)} "
                 "directions" if case.hydro.source == "bem" else "imported (floatmoor hydro "
                 "import)")
        from floatmoor.hydro.database import database_path

        rows.append(f"  hydro: database {case.hydro.database} ({database_path(case)}), {built}"
                    + (f"; accepts failed checks: {', '.join(accepted)}" if accepted else ""))
        if case.hydro.source == "bem" and case.floater is not None:
            from floatmoor.hydro.checks import haskind_requirement

            geo = case.floater.geometry
            need = haskind_requirement(geo.kind, geo.kind != "mesh" or "xz" in geo.symmetry,
                                       case.hydro.directions)
            if need is not None:
                rows.append(f"  hydro: the built database's haskind check will be n/a: {need}")
    if case.motion is not None:
        rows.append(f"  motion: {case.motion.kind}, ramp {case.motion.ramp_duration:g} s; "
                    f"duration {case.simulation.duration:g} s, output every "
                    f"{case.simulation.output_interval:g} s")
        rows.extend(_start_pose_rows(case))
    rows.extend(_describe_groups(case))
    return "\n".join(rows)


def _describe_groups(case: Case) -> list[str]:
    """The dimensionless groups of each line section (floatmoor.similitude.groups)."""
    from floatmoor.similitude.groups import cable_groups

    groups = cable_groups(case)
    names = ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5", "reynolds_number",
             "keulegan_carpenter_number")
    heads = ("alpha_1", "alpha_2", "alpha_3", "alpha_4", "alpha_5", "Re", "KC")
    rows = [f"  dimensionless groups (chain-experiment paper eqs. 29-31; "
            f"{groups.attrs['characteristic_motion']}, T = {float(groups.period[0]):.4g} s, "
            f"a = {float(groups.amplitude[0]):.4g} m):" if groups.sizes["section"] else
            "  dimensionless groups: no lines",
            f"    {'section':<16}" + "".join(f"{h:>11}" for h in heads)]
    values = [groups[n].values for n in names]  # numpy once: xarray indexing per cell is slow
    for i, label in enumerate(groups.section.values):
        rows.append(f"    {label:<16}" + "".join(f"{float(v[i]):>11.4g}" for v in values))
    return rows if groups.sizes["section"] else rows[:1]


def _start_pose_rows(case: Case) -> list[str]:
    """A note when the motion does not start at rest (a table without a ramp whose first row
    is not the rest pose): the lines start in that pose, and the statistics include it."""
    import numpy as np

    from floatmoor.motion.rigid_body import prescribed_fairlead_state

    offsets = [float(np.linalg.norm(prescribed_fairlead_state(case.motion, line, np.zeros(1))[0][0]
                                    - np.asarray(line.fairlead, dtype=float)))
               for line in case.lines if case.point(line.end).kind == "body"]
    if not offsets or max(offsets) == 0.0:
        return []
    return [f"  (the motion starts away from rest: the lines start, settled, at its pose at "
            f"t = 0, fairleads up to {max(offsets):.4g} m from rest; without a ramp the "
            "statistics include the record from t = 0)"]
