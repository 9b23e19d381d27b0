"""Coupled runs end to end on the moored buoy (docs/cases/cylinder_buoy.md): the dataset a run writes, its
partial file, and the waves and initial offset of a case file."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.coupling import CoupledCase
from floatmoor.case.load import load_case
from floatmoor.errors import SolverError
from floatmoor.io.netcdf import read_dataset
from floatmoor.simulation.coupled_run import run_coupled, settings_from_case
from tests.simulation.interrupted import interrupt_run, stop_mid_step
from tests.conftest import CASES

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
QS = ['lines.*.model="quasi-static"']


def test_buoy_in_regular_waves_writes_a_labelled_dataset(tmp_path) -> None:
    case = load_case(BUOY_CASE, QS + [
        "simulation.duration=4.0", "simulation.output_interval=0.02",
        "simulation.time_step=0.01",
        'waves={kind = "regular", height = 0.04, period = 1.2, ramp_duration = 1.2}'])
    view = CoupledCase.of(case)
    assert view.time_step == 0.01 and view.waves.ramp_duration == 1.2 and view.steps_per_output == 2
    out = tmp_path / "buoy.nc"
    result = run_coupled(case, output=out)
    ds = read_dataset(out)
    assert result.status == "complete" and ds.attrs["status"] == "complete"
    assert ds.sizes["time"] == 201 and list(ds["dof"].values) == [
        "Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]
    for name in ("body_displacement", "body_velocity", "wave_elevation", "fairlead_tension",
                 "anchor_tension"):
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
        assert np.all(np.isfinite(ds[name].values))
    assert "case_toml" in ds.attrs and "floatmoor_version" in ds.attrs and "created" in ds.attrs
    # the recorded elevation is the incident one at the reference point (unramped)
    from floatmoor.waves.realisation import realise_sea

    sea = realise_sea(view.waves.settings, case.environment.water_depth, case.environment.gravity,
                case.simulation.duration)
    np.testing.assert_allclose(ds["wave_elevation"].values, sea.elevation(ds["time"].values),
                               rtol=0.0, atol=1e-12)
    # the wave reaches its amplitude after the ramp; the body moves, the lines are loaded
    late = ds["time"].values > 2.0
    assert abs(np.abs(ds["wave_elevation"].values[late]).max() - 0.02) < 1e-3
    assert np.ptp(ds["body_displacement"].sel(dof="Heave").values[late]) > 0.01
    assert np.all(ds["fairlead_tension"].values > 0.0)


def test_free_decay_starts_from_the_offset_at_rest() -> None:
    case = load_case(BUOY_CASE, QS + ["simulation.duration=1.0", "simulation.output_interval=0.02",
                                      'waves={kind = "still"}',
                                      "initial={surge = 0.03, pitch_deg = 2.0}"])
    ds = run_coupled(case).dataset
    x0 = ds["body_displacement"].isel(time=0).values
    assert abs(x0[0] - 0.03) < 1e-12 and abs(x0[4] - np.radians(2.0)) < 1e-12
    # a run without a file holds its equilibrium too: the body starts at it plus the offset
    assert ds["body_equilibrium"].attrs["units"] == "m or rad"
    assert ds["body_equilibrium"].values[2] < -3e-3  # the chains sink the buoy 3.6 mm
    assert np.all(ds["body_velocity"].isel(time=0).values == 0.0)
    assert np.all(ds["wave_elevation"].values == 0.0)


#: The interrupted runs: two quasi-dynamic lines (their state), 2 s in 5 chunks of 40 steps.
RESUMED = ['lines.*.model="quasi-dynamic"', 'lines.line2.model="quasi-static"',
           "simulation.duration=2.0",
           "simulation.output_interval=0.02", "simulation.time_step=0.01",
           "simulation.shape_output_interval=0.2",
           'waves={kind = "regular", height = 0.04, period = 1.2}']


@pytest.fixture(scope="module")
def whole_resumed(tmp_path_factory):
    """The uninterrupted run of ``RESUMED`` in chunks of 40 steps, which both interrupted
    runs below must resume to: its dataset."""
    import floatmoor.simulation.coupled_run as cr

    out = tmp_path_factory.mktemp("whole") / "whole.nc"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(cr, "CHUNK_STEPS", 40)
        return run_coupled(load_case(BUOY_CASE, RESUMED), output=out).dataset


def test_interrupted_run_resumes_to_identical_results(tmp_path, monkeypatch,
                                                      whole_resumed) -> None:
    """Interrupted after a few chunks (3 of 5, checkpoint at every chunk), resumed, the output
    equals an uninterrupted run's exactly; a quasi-dynamic line exercises the line state."""
    import floatmoor.simulation.coupled_run as cr

    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    case = load_case(BUOY_CASE, RESUMED)
    whole = whole_resumed
    out = tmp_path / "cut.nc"
    interrupt_run(case, out)
    partial = read_dataset(out)
    assert partial.attrs["status"].startswith("interrupted")
    assert cr.checkpoint_path(out).is_file()
    assert np.array_equal(partial["body_equilibrium"].values, whole["body_equilibrium"].values)
    resumed = run_coupled(case, output=out, resume=True).dataset
    assert not cr.checkpoint_path(out).exists()
    for name in ("body_equilibrium", "body_displacement", "fairlead_tension", "wave_elevation",
                 "laid_length", "shape_position", "shape_tension"):
        assert np.array_equal(resumed[name].values, whole[name].values), name


def test_run_interrupted_mid_step_checkpoints_its_last_consistent_state(tmp_path, monkeypatch,
                                                                        whole_resumed) -> None:
    """Interrupted inside a body step of its third chunk, before the wall-clock checkpoint
    interval (here endless: only the start's is written), a run still leaves a checkpoint:
    the state at the end of its second chunk, from which the resumed run's output equals an
    uninterrupted run's bit for bit. A run failing at the same point leaves none (resumed, it
    would fail again), not even the start's."""
    import floatmoor.simulation.coupled_run as cr

    monkeypatch.setattr(cr, "CHUNK_STEPS", 40)
    monkeypatch.setattr(cr, "CHECKPOINT_INTERVAL_S", float("inf"))
    case = load_case(BUOY_CASE, RESUMED)
    whole = whole_resumed
    # two memory lines, advanced twice per step: 160 calls a chunk; stop between the lines
    calls = 2 * 160 + 4 * 13 + 2
    failed = tmp_path / "failed.nc"
    stop_mid_step(case, failed, monkeypatch, calls, SolverError("line went unstable"))
    assert read_dataset(failed).attrs["status"].startswith("failed")
    assert not cr.checkpoint_path(failed).exists()
    out = tmp_path / "cut.nc"
    stop_mid_step(case, out, monkeypatch, calls, KeyboardInterrupt())
    assert read_dataset(out).attrs["status"].startswith("interrupted")
    with np.load(cr.checkpoint_path(out), allow_pickle=False) as state:
        assert state["progress/done"] == 2 * 40
        assert state["progress/n_done"] == 2 * 40 // 2 + 1
    resumed = run_coupled(case, output=out, resume=True).dataset
    assert not cr.checkpoint_path(out).exists()
    for name in ("body_displacement", "body_velocity", "fairlead_tension", "wave_elevation",
                 "laid_length", "shape_position", "shape_tension"):
        assert np.array_equal(resumed[name].values, whole[name].values), name


def test_run_stopped_in_its_first_chunk_resumes_from_the_start(tmp_path, monkeypatch) -> None:
    """Interrupted before any chunk is complete, the checkpoint is the initial state."""
    case = load_case(BUOY_CASE, [*QS, 'lines.line1.model="quasi-dynamic"',
                                 "simulation.duration=0.4",
                                 "simulation.output_interval=0.02",
                                 'waves={kind = "regular", height = 0.04, period = 1.2}'])
    whole = run_coupled(case).dataset
    out = tmp_path / "cut.nc"
    stop_mid_step(case, out, monkeypatch, calls=7, error=KeyboardInterrupt())
    assert read_dataset(out).sizes["time"] == 1
    resumed = run_coupled(case, output=out, resume=True).dataset
    for name in ("body_displacement", "fairlead_tension", "laid_length"):
        assert np.array_equal(resumed[name].values, whole[name].values), name


@pytest.mark.parametrize("model", ["quasi-static", "quasi-dynamic",  # dynamic: 15 s, slow
                                   pytest.param("dynamic", marks=pytest.mark.slow)])
def test_line_shapes_of_a_coupled_run(model) -> None:
    """With ``shape_output_interval`` a coupled run records every line's shape: its ends at
    the anchor and at the moving fairlead, its end tension the fairlead tension."""
    case = load_case(BUOY_CASE, [f'lines.*.model="{model}"',
        "simulation.duration=0.6", "simulation.output_interval=0.02",
        "simulation.shape_output_interval=0.2", 'waves={kind = "regular", height = 0.04, '
        'period = 1.2, ramp_duration = 0.0}'])
    ds = run_coupled(case).dataset
    assert ds.sizes["shape_time"] == 4
    for name in ("shape_position", "shape_tension", "arc_length"):
        assert ds[name].attrs["units"] and ds[name].attrs["long_name"]
    at_shapes = ds["time"].values[::10]
    np.testing.assert_allclose(ds["shape_time"].values, at_shapes, atol=1e-12)
    for i, line in enumerate(case.lines):
        shape = ds["shape_position"].isel(line=i).values
        fair = ds["fairlead_position"].isel(line=i).values[::10]
        # the end nodes: a dynamic line imposes its ends weakly (mm off on these stiff chains);
        # the lines with memory were driven along the predicted fairlead path (um off)
        tol = {"dynamic": 2e-3, "quasi-dynamic": 1e-5, "quasi-static": 1e-9}[model]
        assert np.abs(shape[:, 0] - np.asarray(line.anchor)).max() <= tol
        assert np.abs(shape[:, -1] - fair).max() <= tol
        tension = ds["shape_tension"].isel(line=i).values[:, -1]
        # the dynamic line's fairlead force is its end flux, the node tension plus the
        # Lax-Friedrichs penalty Z (v_fairlead - v_node): a few % on these stiff chains
        np.testing.assert_allclose(tension, ds["fairlead_tension"].isel(line=i).values[::10],
                                   rtol=5e-2 if model == "dynamic" else 1e-9)


def test_wind_thrust_offsets_the_equilibrium_and_pushes_downwind() -> None:
    """DeepCwind in still water with a steady 13.05 m/s wind on the rotor: the mean thrust
    (605.9 kN, NREL 5 MW table) shifts the equilibrium downwind, and the body stays there."""
    case = load_case(CASES / "deepcwind" / "deepcwind_free_decay.toml", [
        "simulation.duration=20.0", "simulation.output_interval=0.5",
        "simulation.time_step=0.1", "initial={}",
        'wind={mean_speed = 13.05, spectrum = "steady"}'])
    ds = run_coupled(case).dataset
    calm = run_coupled(load_case(CASES / "deepcwind" / "deepcwind_free_decay.toml", [
        "simulation.duration=1.0", "simulation.output_interval=0.5",
        "simulation.time_step=0.1", "initial={}"])).dataset
    surge = ds["body_displacement"].sel(dof="Surge").values
    pitch = ds["body_displacement"].sel(dof="Pitch").values
    # starts at equilibrium: drifts by millimetres (the thrust acts at the pitched hub, the
    # equilibrium takes it upright)
    print(f"surge drift {np.abs(surge).max():.2e} m, pitch {np.abs(pitch).max():.2e} rad")
    assert np.abs(surge).max() < 5e-3 and np.abs(pitch).max() < 5e-4
    # the downwind line 2 (anchor on +x) slackens, the upwind lines 1 and 3 tighten
    t_wind = ds["fairlead_tension"].isel(time=0).values
    t_calm = calm["fairlead_tension"].isel(time=0).values
    assert t_wind[0] > t_calm[0] and t_wind[1] < t_calm[1]
    # horizontal line forces balance the 605.9 kN thrust at equilibrium
    fx = ds["fairlead_force"].isel(time=0).sel(component="x").values.sum()
    assert abs(fx + 605.9e3) < 0.01 * 605.9e3
    # the stored equilibrium is the thrust's: metres downwind of the calm one
    shift = ds["body_equilibrium"].values - calm["body_equilibrium"].values
    print(f"equilibrium shift by the thrust: surge {shift[0]:.3f} m, pitch {shift[4]:.4f} rad")
    assert shift[0] > 1.0


def test_member_drag_of_the_case_damps_heave() -> None:
    """The DeepCwind case's [floater.drag] (docs/cases/deepcwind.md, quasi-dynamic paper Table 6) damps a heave decay that the
    potential flow alone barely damps; a bad preset is a case error naming the key."""
    from floatmoor.errors import CaseError

    base = ["simulation.duration=12.0", "simulation.output_interval=0.5",
            "simulation.time_step=0.1", "initial={heave = 2.0}"]
    deep = CASES / "deepcwind" / "deepcwind_free_decay.toml"
    heave = {}
    for preset in ("deepcwind_oc4", "none"):
        ds = run_coupled(load_case(deep, base + [f'floater.drag.preset="{preset}"'])).dataset
        heave[preset] = ds["body_displacement"].sel(dof="Heave").values
    # after half a heave period (17.4 s / 2) the trough is shallower with drag
    print(f"heave trough: with drag {heave['deepcwind_oc4'].min():.3f} m, without "
          f"{heave['none'].min():.3f} m")
    assert abs(heave["deepcwind_oc4"].min()) < 0.95 * abs(heave["none"].min())  # observed 0.90
    with pytest.raises(CaseError, match="floater.drag"):
        load_case(deep, ['floater.drag.preset="nonsense"'])


@pytest.mark.parametrize("name", ["deepcwind_lc34", "deepcwind_lc43"])
def test_three_hour_sea_state_cases_start(name) -> None:
    """The LC34 / LC43 case files load, reuse the shipped database, and run their first
    seconds: JONSWAP sea (LC43 with the NPD rotor wind) on the moored DeepCwind."""
    case = load_case(CASES / "deepcwind" / f"{name}.toml", ["simulation.duration=6.0"])
    assert case.simulation.duration == 6.0 and case.waves.settings.hs in (10.5, 7.1)
    ds = run_coupled(case).dataset
    assert ds.attrs["status"] == "complete" and np.all(np.isfinite(ds["fairlead_tension"]))
    assert (case.wind is not None) == (name == "deepcwind_lc43")
    if case.wind is not None:  # a turbulent wind needs a run long enough for its band
        from floatmoor.errors import CaseError

        with pytest.raises(CaseError, match="cutoff_hz"):
            load_case(CASES / "deepcwind" / f"{name}.toml", ["simulation.duration=4.0"])


def test_a_body_step_the_case_reader_accepts_is_run() -> None:
    """The body step is checked once, by the case reader (a step dividing the output
    interval to 1e-6 of the ratio); the time loop took its own, tighter check (1e-9) and
    refused with a ValueError a case that had loaded."""
    case = load_case(BUOY_CASE, QS + ["simulation.duration=0.2", "simulation.output_interval=0.02",
                                      "simulation.time_step=0.0100000001", 'waves={kind = "still"}'])
    assert CoupledCase.of(case).steps_per_output == 2
    ds = run_coupled(case).dataset
    assert ds.sizes["time"] == 11 and np.all(np.isfinite(ds["body_displacement"].values))
