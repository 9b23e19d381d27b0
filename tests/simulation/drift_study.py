"""The seed cases with and without second-order wave loads (docs/validation/second_order.md).

Reads the run files of a sweep over the line model and ``waves.second_order`` (commands on that
page) and prints the page's tables: per run the mean surge (the static equilibrium plus the mean
displacement after the ramp), the surge standard deviation in the low-frequency band around the
surge resonance (113 s here) and in the wave band, the low-frequency peak of the surge PSD, and
each line's fairlead tension mean, standard deviation and maximum.

Usage: ``python -m tests.simulation.drift_study RUNS_DIR [RUNS_DIR ...]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import xarray as xr

from floatmoor.post.spectra import welch_psd

#: The low-frequency band of the semisubmersible's surge [Hz]: around its resonance (113 s,
#: 0.0088 Hz), below the wave band (LC34's and LC43's spectra hold 99.7 % of their variance
#: above 0.25 rad/s = 0.040 Hz).
LOW_BAND_HZ = (0.004, 0.025)
#: The wave band [Hz] (0.25-1.85 rad/s, the seas' components).
WAVE_BAND_HZ = (0.04, 0.30)
#: Welch segment [s]: 0.00083 Hz resolution, 10 segments of a 3 h record with half overlap.
SEGMENT_S = 1200.0


def band_std(psd: xr.DataArray, band: tuple[float, float]) -> float:
    """Standard deviation of the part of a one-sided PSD (over ``frequency`` [Hz]) in a band."""
    f = psd["frequency"].values
    sel = (f >= band[0]) & (f <= band[1])
    return float(np.sqrt(np.trapezoid(psd.values[sel], f[sel])))


def run_figures(path: Path, start: float) -> dict[str, float]:
    """The table figures of one run file, from ``start`` [s] on."""
    with xr.open_dataset(path) as ds:
        after = ds.sel(time=slice(start, None))
        surge = after["body_displacement"].sel(dof="Surge")
        psd = welch_psd(ds["body_displacement"].sel(dof="Surge"), start=start,
                        segment_duration=SEGMENT_S)
        f = psd["frequency"].values
        low = (f >= LOW_BAND_HZ[0]) & (f <= LOW_BAND_HZ[1])
        out = {
            "mean_surge_m": float(ds["body_equilibrium"].sel(dof="Surge")) + float(surge.mean()),
            "equilibrium_surge_m": float(ds["body_equilibrium"].sel(dof="Surge")),
            "surge_std_m": float(surge.std()),
            "surge_low_std_m": band_std(psd, LOW_BAND_HZ),
            "surge_wave_std_m": band_std(psd, WAVE_BAND_HZ),
            "surge_low_peak_m2_per_hz": float(psd.values[low].max()),
            "surge_low_peak_s": float(1.0 / f[low][np.argmax(psd.values[low])]),
            "cpu_s": float(ds.attrs.get("wall_time_s", "nan")),
        }
        tension = after["fairlead_tension"] if "fairlead_tension" in after else \
            np.sqrt((after["fairlead_force"] ** 2).sum("component"))
        for line in ds["line"].values:
            t = tension.sel(line=line) / 1e3
            out[f"{line}_mean_kN"] = float(t.mean())
            out[f"{line}_std_kN"] = float(t.std())
            out[f"{line}_max_kN"] = float(t.max())
    return out


def _label(path: Path) -> str:
    return path.stem.replace("lines.all.model=", "").replace("_waves.second_order=", ", ")


def main(argv: list[str] | None = None) -> None:
    args = sys.argv[1:] if argv is None else argv
    for folder in map(Path, args):
        files = sorted(folder.glob("*.nc"))
        if not files:
            continue
        with xr.open_dataset(files[0]) as ds:
            print(f"\n## {ds.attrs['title'].split(' [')[0]}")
        start = 600.0  # the 60 s ramp and the surge transient (5 resonance periods) left out
        rows = {_label(p): run_figures(p, start) for p in files}
        print(f"\n(from t = {start:g} s)\n")
        print("| run | mean surge [m] | surge STD [m] | low-freq. [m] | wave-freq. [m] | "
              "LF PSD peak [m^2/Hz] at [s] | " + " | ".join(
                  f"{ln} mean / STD / max [kN]" for ln in ("line1", "line2")) + " |")
        print("| --- " * 8 + "|")
        for label, r in rows.items():
            print(f"| {label} | {r['mean_surge_m']:.2f} | {r['surge_std_m']:.2f} | "
                  f"{r['surge_low_std_m']:.2f} | {r['surge_wave_std_m']:.2f} | "
                  f"{r['surge_low_peak_m2_per_hz']:.0f} at {r['surge_low_peak_s']:.0f} | "
                  + " | ".join(f"{r[f'{ln}_mean_kN']:.0f} / {r[f'{ln}_std_kN']:.1f} / "
                               f"{r[f'{ln}_max_kN']:.0f}" for ln in ("line1", "line2"))
                  + " |")


if __name__ == "__main__":
    main()
