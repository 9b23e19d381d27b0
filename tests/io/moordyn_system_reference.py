"""MoorDyn's finest records of the two test systems, stored so the peer tests need not rerun
MoorDyn (a 200-segment run is ~15 min): tests/data/systems/NAME_moordyn.nc.

Regenerate (one system at a time, minutes each)::

    PYTHONPATH=. python -m tests.io.moordyn_system_reference lazy_wave_buoy chain_rope_chain_clump

Each file is MoorDyn 2.7 (the ``moordyn`` package) run by :mod:`tests.io.moordyn_system_runner`
on the deck ``floatmoor export moordyn`` writes for the case, at :data:`REFERENCE_SETTINGS`
(segments per section a multiple of the exported elements x order = 50, dtM as stability needs,
coupling interval :data:`~tests.io.moordyn_system_runner.COUPLING_INTERVAL` or finer), its
coupled point on the case's harmonic motion, sampled at the case's output interval. Variables:
the fairlead tension as the force on the body (MoorDyn's coupled force less its end node's
inertia) and as MoorDyn returns it, and the free points' positions; float32 (0.01 N, 10 um).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import xarray as xr

from floatmoor.case.load import load_case
from floatmoor.io.netcdf import read_dataset, write_dataset
from tests.io.moordyn_system_runner import SystemRun, run_moordyn_system

SYSTEMS = Path(__file__).parents[1] / "data" / "systems"
#: name -> (segment multiple of the exported 50 per section, dtM [s], coupling substeps per
#: 0.02 s sample): MoorDyn's finest runs, 200 segments per section (~13 min each; stable dtM
#: 3e-5 s at 100 segments, 1.5e-5 s at 200).
REFERENCE_SETTINGS = {
    "chain_rope_chain_clump": (4.0, 1.5e-5, 100),
    "lazy_wave_buoy": (4.0, 1.5e-5, 100),
}

__all__ = ["REFERENCE_SETTINGS", "reference_path", "reference_dataset", "read_reference"]


def reference_path(name: str) -> Path:
    """The stored record of system ``name``."""
    return SYSTEMS / f"{name}_moordyn.nc"


def reference_dataset(name: str, run: SystemRun, substeps: int) -> xr.Dataset:
    """The dataset stored for ``run`` (MoorDyn's record of system ``name``)."""
    f32 = np.float32
    points = sorted(run.point_position)
    segments = sorted(set(run.segments.values()))
    ds = xr.Dataset(
        {"fairlead_tension": ("time", run.fairlead_tension("line1").astype(f32),
                              {"units": "N", "long_name": "line1 fairlead tension: force on "
                               "the body (MoorDyn's coupled force less its end node's M a)"}),
         "fairlead_tension_moordyn": ("time", run.fairlead_tension(
             "line1", inertia=False).astype(f32),
             {"units": "N", "long_name": "line1 fairlead tension as MoorDyn returns it "
              "(|net force of the end node|)"}),
         "point_position": (("time", "point", "xyz"),
                            np.stack([run.point_position[n] for n in points], axis=1).astype(f32),
                            {"units": "m", "long_name": "free point positions"})},
        coords={"time": ("time", run.time, {"units": "s", "long_name": "time"}),
                "point": ("point", points, {"long_name": "free point name"}),
                "xyz": ("xyz", ["x", "y", "z"], {"long_name": "global axis"})},
        attrs={"title": f"MoorDyn record of tests/data/systems/{name}.toml",
               "source": "MoorDyn 2.7 (moordyn package) by tests/io/moordyn_system_runner.py "
                         "on the floatmoor export moordyn deck",
               "segments_per_section": ",".join(str(n) for n in segments),
               "dtM_s": float(run.dt),
               "coupling_interval_s": float(run.time[1] - run.time[0]) / substeps,
               "moordyn_wall_s": float(run.wall),
               "regenerate": "PYTHONPATH=. python -m tests.io.moordyn_system_reference "
                             + name})
    return ds


def read_reference(name: str) -> xr.Dataset:
    """The stored record of system ``name``."""
    return read_dataset(reference_path(name))


def main(names: list[str]) -> None:
    """Run MoorDyn on each named system and store its record."""
    for name in names:
        scale, dt, substeps = REFERENCE_SETTINGS[name]
        case = load_case(SYSTEMS / f"{name}.toml")
        sim = case.simulation
        t = np.arange(round(sim.duration / sim.output_interval) + 1) * sim.output_interval
        run = run_moordyn_system(case, t, segment_scale=scale, dt=dt, substeps=substeps)
        write_dataset(reference_dataset(name, run, substeps), reference_path(name))
        print(f"{name}: {reference_path(name)} (MoorDyn {run.wall:.0f} s)")


if __name__ == "__main__":
    main(sys.argv[1:] or sorted(REFERENCE_SETTINGS))
