"""The figure of a floater's response amplitude operators (:mod:`floatmoor.hydro.rao`):
|RAO| against the wave period, one panel per DOF, for ``floatmoor rao --plot``."""

from __future__ import annotations

import math
import os

import numpy as np
import xarray as xr

from floatmoor.hydro.rao import DOFS
from floatmoor.plots.style import plain_axes, pyplot, save_figure

__all__ = ["plot_rao"]


def plot_rao(x: xr.DataArray, path: str | os.PathLike[str], title: str = "") -> None:
    """|RAO| against the wave period, one panel per DOF, one curve per wave direction
    (translations in m/m, rotations in deg/m), saved to ``path``."""
    plt = pyplot()
    fig, axes = plt.subplots(2, 3, figsize=(11, 6), sharex=True)
    period = 2.0 * np.pi / x["omega"].values
    for i, (ax, dof) in enumerate(zip(axes.ravel(), DOFS)):
        for b, beta in enumerate(x["wave_direction"].values):
            scale = 1.0 if i < 3 else 180.0 / math.pi
            ax.plot(period, scale * np.abs(x.values[:, b, i]),
                    label=f"{math.degrees(beta):g} deg")
        ax.set_title(dof)
        ax.set_ylabel("m/m" if i < 3 else "deg/m")
        plain_axes(ax)
    for ax in axes[1]:
        ax.set_xlabel("wave period [s]")
    if x.sizes["wave_direction"] <= 8:
        axes[0, 0].legend(fontsize="small")
    fig.suptitle(title or "response amplitude operators")
    save_figure(fig, path)
