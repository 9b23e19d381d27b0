"""Benchmark baseline: extract the stored references from today's runs (see README.md here).

    python tests/data/references/make_references.py buoy RUN.nc WALL_WHOLE_S
        -> buoy_T1.20_dynamic_10xp5.json and buoy_T1.20_motion.csv

Statistics after the ramp: samples with t >= ramp_duration (the window floatmoor's run summary
uses), population standard deviation (numpy's default, as the summary).
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import xarray as xr

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[2]


def commit() -> str:
    return subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True,
                          text=True, check=True).stdout.strip()


def write_motion_csv(ds: xr.Dataset, path: Path, every: int = 1) -> None:
    """Body 6-DOF displacement as a ``[motion] kind = "body"`` table (rotations in degrees)."""
    t = ds["time"].values[::every]
    d = ds["body_displacement"].values[::every].copy()
    d[:, 3:] = np.degrees(d[:, 3:])
    with open(path, "w") as f:
        f.write("time,surge,sway,heave,roll_deg,pitch_deg,yaw_deg\n")
        for ti, row in zip(t, d):
            f.write(f"{ti:.10g}," + ",".join(f"{v:.9g}" for v in row) + "\n")


def line_stats(ds: xr.Dataset, start: float) -> dict:
    sel = ds["time"].values >= start
    out = {}
    for name in ds["line"].values:
        ten = ds["fairlead_tension"].sel(line=name).values[sel]
        out[str(name)] = {"fairlead_tension_std_N": float(np.std(ten)),
                          "fairlead_tension_max_N": float(np.max(ten)),
                          "fairlead_tension_mean_N": float(np.mean(ten))}
    return out


def buoy(run: Path, wall_whole: float) -> None:
    ds = xr.open_dataset(run)
    ramp = 20.0
    sel = ds["time"].values >= ramp
    disp = ds["body_displacement"]
    heave = disp.sel(dof="Heave").values[sel]
    pitch = disp.sel(dof="Pitch").values[sel]
    # the body's rest position is its static equilibrium with the lines (displacement 0 at
    # t = 0): the replay rotates about the reference point there, from the fairleads there
    fair = {str(n).split(".")[0]: ds["point_position"].sel(point=n).values[0]
            for n, k in zip(ds["point"].values, ds["point_kind"].values) if k == "body"}
    case_fairlead_line3 = np.array([0.2575, 0.0, 0.0])
    c0 = fair["line3"] - case_fairlead_line3
    motion = "buoy_T1.20_motion.csv"
    write_motion_csv(ds, HERE / motion)
    ref = {
        "case": "cases/cylinder_buoy/buoy_regular_T1.20.toml",
        "overrides": [],
        "line_model": "dynamic, 10 elements of order 5, cfl 0.8 (as shipped)",
        "floatmoor_commit": commit(),
        "duration_s": float(ds.attrs["simulated_time_s"]),
        "ramp_duration_s": ramp,
        "window": f"t >= {ramp:g} s (after the cosine wave ramp) to the end, every output "
                  "sample (0.01 s); std = population standard deviation",
        "lines": line_stats(ds, ramp),
        "heave_std_m": float(np.std(heave)),
        "pitch_std_rad": float(np.std(pitch)),
        "pitch_std_deg": float(np.degrees(np.std(pitch))),
        "wall_time_loop_s": float(ds.attrs["wall_time_s"]),
        "wall_time_whole_s": wall_whole,
        "wall_per_simulated_loop": float(ds.attrs["wall_time_s"]) / 60.0,
        "wall_per_simulated_whole": wall_whole / 60.0,
        "motion_file": motion,
        "motion_reference_point_m": [float(c) for c in c0],
        "fairlead_at_rest_m": {k: [float(c) for c in v] for k, v in fair.items()},
        "motion_note": "the body's 6-DOF displacement at the output interval (0.01 s), "
                       "from the body's rest position (its static equilibrium with the lines: the "
                       "case's reference point moved by motion_reference_point_m), rotations "
                       "R = Rz(yaw) Ry(pitch) Rx(roll) about it: a [motion] kind = \"body\" table "
                       "(file = this csv, reference_point = motion_reference_point_m, "
                       "ramp_duration = 0) with each line's fairlead at fairlead_at_rest_m "
                       "replays the recorded fairlead positions within 3e-10 m",
    }
    (HERE / "buoy_T1.20_dynamic_10xp5.json").write_text(json.dumps(ref, indent=2) + "\n")
    print(json.dumps(ref, indent=2))


if __name__ == "__main__":
    if sys.argv[1] in ("fairleads", "deepcwind"):
        pass
    elif sys.argv[1] == "buoy":
        buoy(Path(sys.argv[2]), float(sys.argv[3]))
    else:
        raise SystemExit(f"unknown command {sys.argv[1]}")


def fairleads(run: Path, out: Path, reference_point, start: float = 0.0, every: int = 1) -> None:
    """Each line's fairlead position and velocity as the coupled run moved it (body points with
    the body's recorded displacement and velocity: v = x'[:3] + omega x (p - c), omega the
    recorded rotational velocity, as floatmoor's floater moves its points)."""
    ds = xr.open_dataset(run)
    t = ds["time"].values
    sel = (t >= start)
    idx = np.flatnonzero(sel)[::every]
    x = ds["body_displacement"].values[idx]
    v = ds["body_velocity"].values[idx]
    c0 = np.asarray(reference_point, dtype=float)
    names = [str(n).split(".")[0] for n, k in zip(ds["point"].values, ds["point_kind"].values)
             if k == "body"]
    pos = np.stack([ds["point_position"].sel(point=f"{n}.fairlead").values[idx] for n in names])
    vel = v[None, :, :3] + np.cross(v[None, :, 3:], pos - (c0 + x[:, :3])[None])
    out_ds = xr.Dataset(
        {"fairlead_position": (("line", "time", "component"), pos,
                               {"units": "m", "long_name": "fairlead position (body point)"}),
         "fairlead_velocity": (("line", "time", "component"), vel,
                               {"units": "m s-1", "long_name": "fairlead velocity (body point)"}),
         "fairlead_tension": (("line", "time"),
                              ds["fairlead_tension"].sel(line=names).values[:, idx],
                              {"units": "N", "long_name": "fairlead tension of the coupled run"})},
        coords={"time": ("time", t[idx] - t[idx][0], {"units": "s", "long_name":
                                                      "time from the first sample"}),
                "line": names, "component": ["x", "y", "z"]},
        attrs={"source_run_case": ds.attrs.get("case_file", ""),
               "source_run_overrides": ds.attrs.get("case_overrides", ""),
               "source_time_offset_s": float(t[idx][0]),
               "floatmoor_commit": commit()})
    out_ds.to_netcdf(out)  # scipy backend here: no compression
    print(out, out.stat().st_size)


def deepcwind(run: Path, wall_whole: float, paths_duration: float = 600.0) -> None:
    """LC34 with dynamic lines: per-line fairlead tension statistics after the ramp, wall time,
    and the fairlead paths of the first ``paths_duration`` s for the lines-alone comparison."""
    ds = xr.open_dataset(run)
    ramp = 60.0  # s, [waves] ramp_duration of the case
    duration = float(ds.attrs["simulated_time_s"])
    ref = {
        "case": "cases/deepcwind/deepcwind_lc34.toml",
        "overrides": ["lines.*.model=\"dynamic\""],
        "line_model": "dynamic, the defaults (10 elements of order 5, cfl 0.8)",
        "floatmoor_commit": commit(),
        "duration_s": duration,
        "ramp_duration_s": ramp,
        "window": f"t >= {ramp:g} s (after the wave ramp) to the end, every output sample "
                  "(0.5 s); std = population standard deviation",
        "lines": line_stats(ds, ramp),
        "wall_time_loop_s": float(ds.attrs["wall_time_s"]),
        "wall_time_whole_s": wall_whole,
        "wall_per_simulated_loop": float(ds.attrs["wall_time_s"]) / duration,
        "wall_per_simulated_whole": wall_whole / duration,
    }
    fair = ds["point_position"].sel(point="line2.fairlead").values[0]
    c0 = fair - np.array([40.868, 0.0, -14.0])
    end = int(round(paths_duration / 0.5)) + 1
    sub = ds.isel(time=slice(0, end))
    tmp = HERE / "_deepcwind_tmp.nc"
    sub.to_netcdf(tmp)
    try:
        fairleads(tmp, HERE / "deepcwind_lc34_fairleads_600s.nc", c0)
    finally:
        tmp.unlink()
    ref["fairlead_paths_file"] = "deepcwind_lc34_fairleads_600s.nc"
    ref["fairlead_paths_note"] = (f"the first {paths_duration:g} s (ramp included), every 0.5 s: "
                                  "each line's fairlead position and velocity as the coupled "
                                  "run moved it, for lines-alone replays")
    ref["rest_reference_point_m"] = [float(c) for c in c0]
    (HERE / "deepcwind_lc34_dynamic_10xp5.json").write_text(json.dumps(ref, indent=2) + "\n")
    print(json.dumps(ref, indent=2))


if __name__ == "__main__" and sys.argv[1] == "deepcwind":
    deepcwind(Path(sys.argv[2]), float(sys.argv[3]))

if __name__ == "__main__" and sys.argv[1] == "fairleads":
    fairleads(Path(sys.argv[2]), Path(sys.argv[3]), json.loads(sys.argv[4]),
              float(sys.argv[5]) if len(sys.argv) > 5 else 0.0,
              int(sys.argv[6]) if len(sys.argv) > 6 else 1)
