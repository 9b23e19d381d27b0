"""Dimensionless groups of a case's lines (chain-experiment paper eqs. 29-31, section 3.1).

For each line section, with L the unstretched line length, T the characteristic period of
the motion (the prescribed motion's, or the waves' period / peak period) and a its
amplitude (circle radius, largest translation amplitude, half the wave height):

* alpha_1 = C_a rho_w / rho_c, added mass over line mass (eq. 31a; C_a on the material
  area m / rho_c, so C_a = C_MN / C_v of the paper);
* alpha_2 = EA T^2 / (m L^2) = (c T / L)^2, the inverse Mach number squared (eq. 29b, 31b);
* alpha_3 = (1 - rho_w / rho_c) g T^2 / L, weight over inertia (eq. 29c, 31c);
* alpha_4, alpha_5 = C_dt, C_dn rho_w d L / (2 m), tangential and normal drag (eqs. 29d-e;
  31d-e with m = C_v rho_c pi d^2 / 4);
* Re = u d / nu and KC = u T / d with u = 2 pi a / T, the largest end speed (section 3.1).

Groups that need a period are NaN when the case declares none (a table motion, still
water), the Reynolds and Keulegan-Carpenter numbers also when it declares no amplitude.
"""

from __future__ import annotations

import datetime as _dt
import math

import numpy as np
import xarray as xr

from floatmoor._version import __version__
from floatmoor.case.schema import (
    BodyHarmonicMotion, Case, CircularMotion, HarmonicMotion, Section,
)

__all__ = ["cable_groups", "characteristic_motion", "WATER_KINEMATIC_VISCOSITY",
           "GROUP_ATTRIBUTES"]

#: Kinematic viscosity of water [m^2/s] used for Reynolds numbers: the chain-experiment
#: paper's Table 3 value for both model and prototype (fresh and sea water near 20 C).
WATER_KINEMATIC_VISCOSITY = 1.0e-6

#: long_name and units of every variable :func:`cable_groups` returns.
GROUP_ATTRIBUTES: dict[str, dict[str, str]] = {
    "section": {"long_name": "line section, line[index] from the line's start", "units": "1"},
    "line": {"long_name": "mooring line the section belongs to", "units": "1"},
    "alpha_1": {"long_name": "alpha_1 = C_a rho_w / rho_c: added mass over line mass "
                "(chain-experiment paper eq. 31a)", "units": "1"},
    "alpha_2": {"long_name": "alpha_2 = EA T^2 / (m L^2): inverse Mach number squared "
                "(eq. 31b)", "units": "1"},
    "alpha_3": {"long_name": "alpha_3 = (1 - rho_w / rho_c) g T^2 / L: weight over inertia, "
                "inverse Froude number squared (eq. 31c)", "units": "1"},
    "alpha_4": {"long_name": "alpha_4 = C_dt rho_w d L / (2 m): tangential drag (eq. 29d)",
                "units": "1"},
    "alpha_5": {"long_name": "alpha_5 = C_dn rho_w d L / (2 m): normal drag (eq. 29e)",
                "units": "1"},
    "reynolds_number": {"long_name": "Re = u d / nu, u = 2 pi a / T the largest end speed "
                        "(section 3.1)", "units": "1"},
    "keulegan_carpenter_number": {"long_name": "KC = u T / d = 2 pi a / d (section 3.1)",
                                  "units": "1"},
    "volume_coefficient": {"long_name": "C_v = m / (rho_c pi d^2 / 4) (eq. 30)", "units": "1"},
    "line_length": {"long_name": "unstretched length of the line, the characteristic length L",
                    "units": "m"},
    "period": {"long_name": "characteristic period T of the motion", "units": "s"},
    "amplitude": {"long_name": "characteristic amplitude a of the motion", "units": "m"},
    "axial_wave_speed": {"long_name": "longitudinal wave celerity c = sqrt(EA / m)",
                         "units": "m/s"},
}


def characteristic_motion(case: Case) -> tuple[float, float, str]:
    """The period T [s], amplitude a [m] of a case's motion and where they come from.

    NaN where the case declares none.
    """
    motion, nan = case.motion, math.nan
    if isinstance(motion, CircularMotion):
        return motion.period, motion.radius, "circular motion: period and radius"
    if isinstance(motion, (HarmonicMotion, BodyHarmonicMotion)):
        period = motion.cycle_period
        moving = [a for a, p in zip(motion.amplitude[:3], motion.period[:3]) if a > 0.0]
        if period is None:
            return nan, nan, "harmonic motion with several periods: no one period"
        return period, max(moving) if moving else nan, \
            "harmonic motion: period and largest translation amplitude"
    if motion is not None:
        return nan, nan, f"{motion.kind} motion: no declared period"
    settings = getattr(case.waves, "settings", None)
    if hasattr(settings, "height"):
        return settings.period, 0.5 * settings.height, "regular waves: period, half height"
    if hasattr(settings, "hs"):
        return settings.tp, 0.5 * settings.hs, "irregular waves: peak period, half Hs"
    return nan, nan, "no motion and no waves: no period"


def _section_groups(case: Case, section: Section, length: float, period: float,
                    amplitude: float) -> dict[str, float]:
    # In float64 with IEEE semantics: extreme but valid inputs (a period of 1e308 s, a diameter
    # of 1e-300 m) give an infinite or zero group, which `floatmoor check` prints, rather than
    # an OverflowError or ZeroDivisionError.
    with np.errstate(all="ignore"):
        return _groups(case, section, np.float64(length), np.float64(period),
                       np.float64(amplitude))


def _groups(case: Case, section: Section, length: np.float64, period: np.float64,
            amplitude: np.float64) -> dict[str, float]:
    lt, env = section.line_type, case.environment
    m, rho_w = np.float64(lt.mass_per_length), np.float64(env.water_density)
    rho_c, diameter = np.float64(lt.material_density), np.float64(lt.diameter)
    drag = 0.5 * rho_w * diameter * length / m  # alpha_4,5 / C_d (eq. 29d-e)
    speed = 2.0 * math.pi * amplitude / period
    return {
        "alpha_1": lt.added_mass_coefficient * rho_w / rho_c,
        "alpha_2": lt.axial_stiffness * period ** 2 / (m * length ** 2),
        "alpha_3": (1.0 - rho_w / rho_c) * env.gravity * period ** 2 / length,
        "alpha_4": lt.tangential_drag_coefficient * drag,
        "alpha_5": lt.normal_drag_coefficient * drag,
        "reynolds_number": speed * diameter / WATER_KINEMATIC_VISCOSITY,
        "keulegan_carpenter_number": speed * period / diameter,
        "volume_coefficient": m / (rho_c * math.pi * diameter ** 2 / 4.0),
        "line_length": length,
        "period": period,
        "amplitude": amplitude,
        "axial_wave_speed": lt.axial_wave_speed,
    }


def cable_groups(case: Case) -> xr.Dataset:
    """The dimensionless groups of every line section of ``case`` (dimension ``section``).

    Every variable has ``units`` and ``long_name``; the attributes say where the period and
    amplitude come from, and carry the case text, floatmoor version and creation time.

    Parameters
    ----------
    case
        The case (its lines, line types, environment and motion).

    Returns
    -------
    xarray.Dataset
        The groups of each section.
    """
    period, amplitude, origin = characteristic_motion(case)
    rows = [_section_groups(case, s, line.length, period, amplitude)
            for line in case.lines for s in line.sections]
    labels = [s.label for s in case.sections]
    coords = {"section": ("section", np.array(labels, dtype=str), GROUP_ATTRIBUTES["section"]),
              "line": ("section", np.array([s.line for s in case.sections], dtype=str),
                       GROUP_ATTRIBUTES["line"])}
    names = list(rows[0]) if rows else [k for k in GROUP_ATTRIBUTES
                                        if k not in ("section", "line")]
    data = {name: ("section", np.array([r[name] for r in rows], dtype=float),
                   GROUP_ATTRIBUTES[name]) for name in names}
    attrs = {
        "title": case.title, "case_file": case.source, "case_toml": case.text,
        "characteristic_motion": origin,
        "kinematic_viscosity": WATER_KINEMATIC_VISCOSITY,
        "floatmoor_version": __version__,
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    return xr.Dataset(data, coords=coords, attrs=attrs)
