"""The one table of names, long names and units of floatmoor's output variables.

Units are UDUNITS strings; every variable and coordinate written to a result dataset takes its
``long_name`` and ``units`` from here.
"""

from __future__ import annotations

__all__ = ["VARIABLE_ATTRIBUTES", "attributes"]

VARIABLE_ATTRIBUTES: dict[str, dict[str, str]] = {
    # coordinates
    "time": {"long_name": "simulated time", "units": "s"},
    "line": {"long_name": "mooring line name", "units": "1"},
    "component": {"long_name": "global axis (x, y horizontal, z up)", "units": "1"},
    "model": {"long_name": "line model", "units": "1"},
    # per-line time series
    "fairlead_tension": {"long_name": "line tension at the fairlead", "units": "N"},
    "fairlead_force": {"long_name": "force exerted by the line on the fairlead", "units": "N"},
    "anchor_tension": {"long_name": "line tension at the anchor", "units": "N"},
    "anchor_force": {"long_name": "force exerted by the line on the anchor", "units": "N"},
    "fairlead_position": {"long_name": "fairlead position", "units": "m"},
    "laid_length": {"long_name": "unstretched line length resting on the seabed", "units": "m"},
    "solver_iterations": {"long_name": "Newton iterations of the quasi-static catenary",
                          "units": "1"},
}


def attributes(name: str) -> dict[str, str]:
    """A copy of the attributes of variable ``name``."""
    return dict(VARIABLE_ATTRIBUTES[name])
