"""Floater motions of one run: surge, sway, heave [m] and roll, pitch, yaw [deg] from the rest
position, and the incident wave elevation at the reference point."""

from __future__ import annotations

from typing import TYPE_CHECKING


import numpy as np
import xarray as xr

from floatmoor.io.dataset import DOFS
from floatmoor.plots.series import check_series
from floatmoor.plots.style import figure_title, plain_axes, pyplot

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["draw_body_motions", "moving_dofs", "TRANSLATIONS",
           "MOTION_ACTIVE_STD"]

#: A DOF whose standard deviation over the window is below this [m or rad] in every run is
#: not plotted in motion figures (symmetric cases leave sway, roll and yaw at round-off).
MOTION_ACTIVE_STD = 1e-9
#: Degrees of freedom drawn in metres; the others are rotations, drawn in degrees.
TRANSLATIONS = ("Surge", "Sway", "Heave")


def moving_dofs(dataset: xr.Dataset) -> list[str]:
    """The DOFs whose displacement has a standard deviation of at least
    :data:`MOTION_ACTIVE_STD` (m or rad) over the run (symmetric
    cases leave sway, roll and yaw at round-off)."""
    disp = dataset["body_displacement"]
    return [d for d in DOFS if float(disp.sel(dof=d).std("time")) >= MOTION_ACTIVE_STD]


def draw_body_motions(dataset: xr.Dataset, *,
                      ramp_duration: float = 0.0) -> Figure:
    """Floater displacements of the moving DOFs (translations in m, rotations in degrees) and
    the wave elevation, one panel each; the DOFs at rest are named in the title.

    Parameters
    ----------
    dataset
        A floater run's result dataset.
    ramp_duration
        The end of the start-up ramp [s], marked on the panels.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (not saved).

    Raises
    ------
    KeyError
        Without ``body_displacement`` (not a floater run).
    FigureDataError
        When a series is empty or not finite.
    """
    dofs = moving_dofs(dataset)
    still = [d for d in DOFS if d not in dofs]
    waves = "wave_elevation" in dataset
    rows = [*dofs, *(["wave"] if waves else [])]
    plt = pyplot()
    fig, axes = plt.subplots(max(len(rows), 1), 1, figsize=(9.0, 2.0 * max(len(rows), 1) + 0.9),
                             sharex=True, squeeze=False)
    time = check_series(dataset["time"].values, "time")
    for ax, row in zip(axes[:, 0], rows):
        if row == "wave":
            y = check_series(dataset["wave_elevation"].values, "wave elevation")
            ax.plot(time, y, lw=0.9, color="C0")
            ax.set_ylabel("wave elevation [m]")
        else:
            y = check_series(dataset["body_displacement"].sel(dof=row).values, row)
            metres = row in TRANSLATIONS
            ax.plot(time, y if metres else np.degrees(y), lw=0.9, color="C3")
            ax.set_ylabel(f"{row.lower()} [{'m' if metres else 'deg'}]")
        if ramp_duration > 0.0:
            ax.axvspan(0.0, min(ramp_duration, float(time[-1])), color="0.92")
        ax.grid(alpha=0.3)
        plain_axes(ax)
    if not rows:
        axes[0, 0].text(0.5, 0.5, "the floater does not move", transform=axes[0, 0].transAxes,
                        ha="center")
    axes[-1, 0].set_xlabel("time [s]")
    note = (f"\n(at rest, std < {MOTION_ACTIVE_STD:g}: {', '.join(still).lower()})"
            if still else "")
    fig.suptitle(figure_title(dataset.attrs.get("title")) + "\nfloater motions from the rest "
                 "position" + (", ramp shaded" if ramp_duration > 0.0 else "") + note,
                 fontsize=10)
    fig.tight_layout()
    return fig
