"""The one table of names, long names and units of floatmoor's output variables.

Units are UDUNITS strings; every variable and coordinate written to a result dataset takes its
``long_name`` and ``units`` from here (``body_equilibrium_with_drift``: the attributes of
``body_equilibrium`` in a run with second-order wave loads).
"""

from __future__ import annotations

__all__ = ["VARIABLE_ATTRIBUTES", "attributes"]

VARIABLE_ATTRIBUTES: dict[str, dict[str, str]] = {
    # coordinates
    "time": {"long_name": "simulated time", "units": "s"},
    "line": {"long_name": "mooring line name", "units": "1"},
    "component": {"long_name": "global axis (x, y horizontal, z up)", "units": "1"},
    "model": {"long_name": "line model", "units": "1"},
    # per-line constants
    "minimum_breaking_load": {"long_name": "minimum breaking load of the line's type at the "
                              "fairlead (NaN: not given in the case)", "units": "N"},
    # per-line time series
    "fairlead_tension": {"long_name": "line tension at the fairlead", "units": "N"},
    "fairlead_force": {"long_name": "force exerted by the line on the fairlead", "units": "N"},
    "anchor_tension": {"long_name": "line tension at the anchor", "units": "N"},
    "anchor_force": {"long_name": "force exerted by the line on the anchor", "units": "N"},
    "fairlead_position": {"long_name": "fairlead position", "units": "m"},
    "laid_length": {"long_name": "unstretched line length resting on the seabed", "units": "m"},
    "solver_iterations": {"long_name": "Newton iterations (quasi-static, quasi-dynamic) or "
                          "time steps (dynamic) per output sample", "units": "1"},
    # the mooring system: points and sections
    "point": {"long_name": "mooring point name", "units": "1"},
    "point_kind": {"long_name": "kind of mooring point (fixed, free or body)", "units": "1"},
    "section": {"long_name": "line section name, line[index] from the line's start",
                "units": "1"},
    "section_line": {"long_name": "line the section belongs to", "units": "1"},
    "section_type": {"long_name": "line type of the section", "units": "1"},
    "point_position": {"long_name": "position of the mooring point", "units": "m"},
    "point_force": {"long_name": "net force exerted by the lines on the mooring point",
                    "units": "N"},
    "section_start_tension": {"long_name": "section tension at its start (the end towards "
                              "its line's start)", "units": "N"},
    "section_end_tension": {"long_name": "section tension at its end", "units": "N"},
    "section_minimum_breaking_load": {"long_name": "minimum breaking load of the section's "
                                      "line type (NaN: not given in the case)", "units": "N"},
    # floating body (coupled runs)
    "dof": {"long_name": "rigid-body degree of freedom about the reference point (capytaine's "
            "names; rotations about axes parallel to x, y, z)", "units": "1"},
    "body_displacement": {"long_name": "floater displacement from its static equilibrium "
                          "(body_equilibrium): Surge, Sway, Heave [m], Roll, Pitch, Yaw [rad]",
                          "units": "m or rad"},
    "body_equilibrium": {"long_name": "static equilibrium of the moored floater relative to "
                         "the case's position, under its weight, buoyancy (linear hydrostatic "
                         "stiffness), the quasi-static catenaries of its lines in still water "
                         "and the mean rotor thrust of the mean wind if any (no current, wave "
                         "drift or Morison drag): Surge, Sway, Heave [m], Roll, Pitch, Yaw "
                         "[rad]", "units": "m or rad"},
    "body_equilibrium_with_drift": {
        "long_name": "static equilibrium of the moored floater relative to the case's "
                     "position, under its weight, buoyancy (linear hydrostatic stiffness), the "
                     "quasi-static catenaries of its lines in still water, the mean rotor "
                     "thrust of the mean wind if any and the mean wave drift of the sea "
                     "(second_order_force's mean; no current or Morison drag): Surge, Sway, "
                     "Heave [m], Roll, Pitch, Yaw [rad]", "units": "m or rad",
        "mean_wave_drift": "included"},
    "second_order_force": {"long_name": "second-order wave force and moment on the floater "
                           "about its reference point, as applied: its mean unramped (in "
                           "body_equilibrium), the rest ramped with the square of the wave "
                           "ramp", "units": "N (Surge, Sway, Heave), N m (Roll, Pitch, Yaw)"},
    "body_velocity": {"long_name": "floater velocity: Surge, Sway, Heave [m/s], Roll, Pitch, "
                      "Yaw [rad/s]", "units": "m/s or rad/s"},
    # prescribed body motion (forced runs with [motion] kind = "body")
    "prescribed_displacement": {"long_name": "prescribed body displacement about the motion's "
                                "reference point: Surge, Sway, Heave [m], Roll, Pitch, Yaw [rad] "
                                "(Euler angles of R = Rz(yaw) Ry(pitch) Rx(roll))",
                                "units": "m or rad"},
    "prescribed_displacement_rate": {"long_name": "time derivative of the prescribed body "
                                     "displacement: Surge, Sway, Heave [m/s], Roll, Pitch, Yaw "
                                     "Euler-angle rates [rad/s] (not the angular velocity)",
                                     "units": "m/s or rad/s"},
    "wave_elevation": {"long_name": "undisturbed incident wave elevation at the floater's "
                       "reference point", "units": "m"},
    # line shapes at the coarser shape interval
    "shape_time": {"long_name": "time of the line-shape samples", "units": "s"},
    "arc_length": {"long_name": "unstretched arc length from the anchor", "units": "m"},
    "shape_position": {"long_name": "position of the line nodes", "units": "m"},
    "shape_tension": {"long_name": "effective tension along the line", "units": "N"},
}


def attributes(name: str) -> dict[str, str]:
    """A copy of the attributes of variable ``name``."""
    return dict(VARIABLE_ATTRIBUTES[name])
