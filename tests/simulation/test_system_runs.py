"""Forced-motion runs of mooring systems: lines of several sections with a clump
weight and a buoy, solved together, quasi-static and dynamic."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.mooring.statics_solver import SystemStatics, build_static_system
from floatmoor.simulation.forced import run_forced_motion
from tests.conftest import LINDAHL_CASE

SYSTEM = Path(__file__).parents[1] / "data" / "systems" / "clump_buoy.toml"
MOTION = 'motion={kind = "harmonic", amplitude = [2.0, 0.0, 1.0], period = 10.0}'
#: Newton tolerance of the system statics on the force residual (statics_solver.FORCE_RTOL
#: is 1e-9 of each point's force scale): forces compared to this, relative.
STATICS_RTOL = 1e-8


def _qs_run(*extra: str):
    case = load_case(SYSTEM, [MOTION, "simulation.duration=12.0", *extra])
    return case, run_forced_motion(case).dataset


def test_quasi_static_system_run_is_the_statics_at_every_sample():
    case, ds = _qs_run()
    statics = SystemStatics(build_static_system(case.points, case.lines, case.environment,
                                                case.seabed))
    for k in (0, 7, 15, 24):
        fairlead = ds["point_position"].sel(point="fairlead").values[k]
        sol = statics.solve({"fairlead": fairlead})
        for name in ("clump", "buoy"):
            np.testing.assert_allclose(ds["point_position"].sel(point=name).values[k],
                                       sol.position(name), rtol=0, atol=1e-6)
        for j, label in enumerate(sol.section_names):
            np.testing.assert_allclose(
                ds["section_end_tension"].sel(section=label).values[k], sol.end_tension[j],
                rtol=STATICS_RTOL)
    # the line's fairlead force is its last section's force on the fairlead point
    np.testing.assert_allclose(ds["fairlead_tension"].sel(line="line1").values,
                               ds["section_end_tension"].sel(section="line1[2]").values,
                               rtol=0, atol=0)
    np.testing.assert_allclose(ds["point_force"].sel(point="fairlead").values,
                               ds["fairlead_force"].sel(line="line1").values, rtol=0, atol=0)


def test_free_points_are_in_equilibrium_of_lines_weight_and_buoyancy():
    case, ds = _qs_run()
    g, rho = case.environment.gravity, case.environment.water_density
    for name in ("clump", "buoy"):
        p = case.point(name)
        net_load = np.array([0.0, 0.0, (p.mass - rho * p.volume) * g])  # what the lines carry
        forces = ds["point_force"].sel(point=name).values
        scale = np.abs(ds["section_end_tension"].values).max()
        np.testing.assert_allclose(forces, np.broadcast_to(net_load, forces.shape),
                                   rtol=0, atol=STATICS_RTOL * scale)


def test_line_split_by_a_massless_joint_is_the_same_catenary(tmp_path):
    """A catenary through a massless joint is the same catenary: the two-section Lindahl chain
    gives the one-section chain's fairlead force (quasi-static)."""
    text = LINDAHL_CASE.read_text().replace(
        'type = "chain"\nlength = 33.0                  # m, unstretched',
        'sections = [{ type = "chain", length = 12.0 }, { type = "chain", length = 21.0 }]')
    path = tmp_path / "split.toml"
    path.write_text(text)
    sets = ["simulation.duration=3.0", 'lines.*.model="quasi-static"']
    one = run_forced_motion(load_case(LINDAHL_CASE, sets)).dataset
    two = run_forced_motion(load_case(path, sets)).dataset
    scale = float(one["fairlead_tension"].max())
    np.testing.assert_allclose(two["fairlead_force"].values, one["fairlead_force"].values,
                               rtol=0, atol=STATICS_RTOL * scale)
    np.testing.assert_allclose(two["anchor_force"].values, one["anchor_force"].values,
                               rtol=0, atol=STATICS_RTOL * scale)
    # the joint carries nothing: its net line force is zero
    joint = two["point_force"].sel(point="chain.joint1").values
    assert np.abs(joint).max() <= STATICS_RTOL * scale


@pytest.mark.parametrize("model", ["quasi-static", "dynamic"])
def test_system_run_records_points_sections_and_shapes(model):
    case = load_case(SYSTEM, [MOTION, "simulation.duration=2.0", "motion.ramp_duration=1.0",
                              f'lines.*.model="{model}"',
                              "simulation.shape_output_interval=1.0"])
    ds = run_forced_motion(case).dataset
    assert ds.attrs["status"] == "complete"
    assert list(ds["section"].values) == ["line1[0]", "line1[1]", "line1[2]"]
    assert list(ds["point_kind"].values) == ["fixed", "free", "free", "body"]
    for name in ("point_position", "point_force", "section_start_tension",
                 "section_end_tension"):
        assert np.all(np.isfinite(ds[name].values)), name
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
    # the line's shape runs from the anchor through the clump and buoy to the fairlead (the
    # DG nodes meet their end points weakly, to the discretisation error: ~1e-4 m here)
    tol = 1e-6 if model == "quasi-static" else 1e-3
    shape = ds["shape_position"].sel(line="line1").values[-1]
    points = ds["point_position"].isel(time=-1)
    np.testing.assert_allclose(shape[0], points.sel(point="anchor").values, atol=tol)
    np.testing.assert_allclose(shape[-1], points.sel(point="fairlead").values, atol=tol)
    for name in ("clump", "buoy"):
        distance = np.linalg.norm(shape - points.sel(point=name).values, axis=1).min()
        assert distance < tol, (name, distance)


def test_section_breaking_at_rest_is_bad_input(tmp_path, capsys):
    """An MBL below a section's static tension (from the system's equilibrium) is refused
    before the run: status 2, one message naming the key, nothing written."""
    out = tmp_path / "out.nc"
    status = main(["run", str(SYSTEM), "-o", str(out), "--quiet",
                   "--set", "line_types.rope.minimum_breaking_load=2.0e5"])
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and not out.exists()
    assert len(err) == 1 and "line_types.rope.minimum_breaking_load" in err[0]
    assert "section 'line1[1]'" in err[0]


EXAMPLE = Path(__file__).parents[2] / "cases" / "systems" / "three_line_clump_buoy.toml"


def test_shipped_three_line_system_is_mirror_symmetric_under_its_motion():
    """Surge, heave and pitch keep the xz-plane a plane of symmetry: lines 2 and 3 (at +-120
    degrees) carry the same tensions, their free points move as mirror images, and the body
    points follow the rigid-body motion."""
    from floatmoor.motion.rigid_body import body_points_state

    case = load_case(EXAMPLE)
    ds = run_forced_motion(case).dataset
    assert ds.attrs["status"] == "complete"
    peak = float(ds["fairlead_tension"].max())
    np.testing.assert_allclose(ds["fairlead_tension"].sel(line="line2").values,
                               ds["fairlead_tension"].sel(line="line3").values,
                               rtol=0, atol=STATICS_RTOL * peak)
    for a, b in (("clump2", "clump3"), ("buoy2", "buoy3")):
        pa = ds["point_position"].sel(point=a).values
        pb = ds["point_position"].sel(point=b).values * np.array([1.0, -1.0, 1.0])
        np.testing.assert_allclose(pa, pb, rtol=0, atol=1e-6)
    names = [p.name for p in case.points if p.kind == "body"]
    rest = np.array([case.point(n).position for n in names])
    expected, _ = body_points_state(case.motion, rest, ds["time"].values)
    for k, name in enumerate(names):
        np.testing.assert_allclose(ds["point_position"].sel(point=name).values,
                                   expected[:, k], rtol=0, atol=1e-12)


def test_run_summary_judges_each_section_against_its_own_type():
    from floatmoor.post.summary import format_summary, run_summary

    case = load_case(EXAMPLE, ["simulation.duration=20.0"])
    ds = run_forced_motion(case).dataset
    summary = run_summary(case, ds)
    rope = summary["sections"]["line1[1]"]
    assert rope["minimum_breaking_load_N"] == 6.0e6  # the rope's, not the chain's
    window = ds["time"].values >= summary["lines"]["line1"]["fairlead_tension_N"]["window_start"]
    both = np.maximum(ds["section_start_tension"].sel(section="line1[1]").values,
                      ds["section_end_tension"].sel(section="line1[1]").values)[window]
    assert rope["max_tension_N"] == both.max()
    assert rope["max_tension_over_mbl"] == both.max() / 6.0e6
    assert "line1[1]" in format_summary(summary)
