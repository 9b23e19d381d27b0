"""Sizes the input controls are bounded at load (status
2, before anything is allocated), extreme values give messages instead of tracebacks or
hangs, and the messages say what is wrong."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from floatmoor.case import limits
from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.errors import CaseError
from tests.conftest import CASES, LINDAHL_CASE, REPO

QUASI_STATIC = 'lines.chain.model="quasi-static"'
DEEPCWIND = CASES / "deepcwind" / "deepcwind_lc43.toml"


def _cli(*args: str, timeout: float = 60.0, cwd=REPO) -> subprocess.CompletedProcess:
    """The command in a subprocess (a hang fails by timeout, not by blocking the suite)."""
    return subprocess.run([sys.executable, "-m", "floatmoor.cli", *args], capture_output=True,
                          text=True, timeout=timeout, cwd=cwd,
                          env={**os.environ, "PYTHONPATH": str(REPO)})


def _refused(capsys, case, *overrides: str, command: str = "check") -> str:
    status = main([command, str(case), *(a for o in overrides for a in ("--set", o))])
    err = capsys.readouterr().err
    assert status == 2, err
    assert len(err.strip().splitlines()) == 1 and err.startswith("floatmoor: error: ")
    return err


@pytest.mark.parametrize("override, key, words", [
    ("simulation.duration=1e6", "simulation.duration", "output samples"),
    ("simulation.duration=1e308", "simulation.duration", "output samples"),
    ("simulation.output_interval=1e-300", "simulation.output_interval", "output samples"),
    ("lines.chain.dynamic.max_time_step=1e-300", "lines[0].dynamic.max_time_step",
     "steps over simulation.duration"),
    ("line_types.chain.axial_stiffness=1e308", "line_types.chain.axial_stiffness",
     "axial wave speed"),
    ("simulation.shape_output_interval=0.0025", "simulation.shape_output_interval",
     "shape values"),  # with 10000 elements below
])
def test_sizes_of_a_forced_run_are_bounded_at_load(capsys, override, key, words):
    extra = ["lines.chain.dynamic.elements=10000"] if "shape" in override else []
    err = _refused(capsys, LINDAHL_CASE, override, *extra)
    assert f"{key}: expected" in err and words in err


@pytest.mark.parametrize("override, key", [
    ("waves.frequency_step=1e-9", "waves.frequency_step"),
    ('waves.spacing="random-in-bin"', "waves.n_components"),  # needs n_components: no bound
    ("wind.cutoff_hz=1e9", "wind.cutoff_hz"),
    ("hydro.frequency_ranges=[[0.8, 9.2, 10000000000]]", "hydro.frequency_ranges[0][2]"),
    ("hydro.panel_size=1e-9", "hydro.panel_size"),
    ("hydro.panel_size=1e-300", "hydro.panel_size"),  # its square underflows to 0
])
def test_components_and_frequencies_are_bounded_at_load(capsys, override, key):
    overrides = [override]
    if "random-in-bin" in override:
        overrides.append(f"waves.n_components={limits.MAX_WAVE_COMPONENTS + 1}")
    err = _refused(capsys, DEEPCWIND, *overrides)
    assert f"{key}: expected" in err


def test_a_run_too_short_for_its_wave_band_is_bad_input(capsys):
    """2 pi / 1 s puts no JONSWAP component in LC34's [0.25, 1.85] rad/s: refused at load,
    naming simulation.duration (it was an uncaught ValueError of the wave realisation)."""
    err = _refused(capsys, CASES / "deepcwind" / "deepcwind_lc34.toml", "simulation.duration=1.0")
    assert "simulation.duration: expected a frequency step that puts at least one wave" in err


def test_shipped_cases_are_within_the_bounds():
    paths = [p for p in sorted(CASES.glob("*/*.toml")) if "[environment]" in p.read_text()]
    assert len(paths) >= 10  # (the published_*.toml files are reference values, not cases)
    for path in paths:
        load_case(path)  # raises if a bound is too tight for a case we ship


def test_deep_nesting_is_a_case_error_not_a_recursion_error(tmp_path, capsys):
    case = tmp_path / "deep.toml"
    case.write_text("a = " + "[" * 3000 + "]" * 3000 + "\n")
    err = _refused(capsys, case)
    assert "nested at most" in err
    shallow_but_deep = tmp_path / "deep2.toml"
    shallow_but_deep.write_text("a = " + "[" * 40 + "]" * 40 + "\n")
    assert "nested at most" in _refused(capsys, shallow_but_deep)
    deep_value = "[" * 3000 + "]" * 3000
    _refused(capsys, LINDAHL_CASE, f"description={deep_value}")
    status = main(["sweep", str(LINDAHL_CASE), "--grid", f"motion.period={deep_value}"])
    assert status == 2 and "Traceback" not in capsys.readouterr().err


SHORT = ["--set", QUASI_STATIC, "--set", "simulation.output_interval=0.05",
         "--set", "simulation.duration=1.5", "--set", "motion.ramp_duration=0.5"]


def test_huge_motion_period_does_not_hang(tmp_path):
    # was: the file written, then ~1e299 passes of the cycle loop
    result = _cli("run", str(LINDAHL_CASE), "--quiet", "--json", "-o", str(tmp_path / "o.nc"),
                  "--set", "motion.period=1e308", *SHORT, timeout=60)
    assert result.returncode == 0, result.stderr
    assert '"mean_cycle_max": null' in result.stdout and '"n_cycles": 0' in result.stdout


def test_period_longer_than_the_run_gives_no_cycle_statistics(tmp_path, capsys):
    # was: one fake "mean cycle maximum" for a 1e9 s period in a 1.5 s run
    status = main(["run", str(LINDAHL_CASE), "--quiet", "--json", "-o", str(tmp_path / "o.nc"),
                   "--set", "motion.period=1e9", *SHORT])
    out = capsys.readouterr().out
    assert status == 0
    assert '"mean_cycle_max": null' in out and '"n_cycles": 0' in out


def test_anchor_at_the_fairlead_is_one_load_error_for_every_motion(capsys):
    same = "lines.chain.anchor=[32.554, 0.0, 0.3]"
    circular = _refused(capsys, LINDAHL_CASE, same)
    harmonic = _refused(capsys, LINDAHL_CASE, same, 'motion={kind="harmonic", '
                        'amplitude=[0.1, 0, 0], period=1.0}', command="run")
    for err in (circular, harmonic):
        assert "lines[0].anchor: expected a point apart from the fairlead" in err
        assert "vertical" not in err


def test_a_key_swept_twice_is_an_error(tmp_path, capsys):
    out = tmp_path / "c.nc"
    status = main(["sweep", str(LINDAHL_CASE), "--grid", "motion.period=1.0,2.0",
                   "--grid", "motion.period=3.0", "-o", str(out)])
    err = capsys.readouterr().err
    assert status == 2 and "a key swept once" in err and not out.exists()


def test_malformed_scheduler_is_bad_input_before_running(tmp_path, capsys):
    out = tmp_path / "c.nc"
    status = main(["sweep", str(LINDAHL_CASE), "--grid", "motion.period=1.0,2.0",
                   "--scheduler", "notaurl", "-o", str(out), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2 and "--scheduler: expected a scheduler address" in err
    assert not out.exists()


@pytest.mark.slow  # ~10 s: the 5 s connection timeout plus Dask's start-up
def test_unreachable_scheduler_fails_fast_with_one_line(tmp_path):
    pytest.importorskip("distributed")
    start = time.perf_counter()
    result = _cli("sweep", str(LINDAHL_CASE), "--grid", "motion.period=1.0,2.0", "--quiet",
                  "--scheduler", "tcp://127.0.0.1:1", "-o", str(tmp_path / "c.nc"),
                  timeout=60)
    assert time.perf_counter() - start < 25  # Dask's default wait is 30 s
    assert result.returncode == 1
    assert "cannot reach the Dask scheduler" in result.stderr
    assert "Traceback" not in result.stderr
    assert not (tmp_path / "c.nc").exists()  # nothing ran: no campaign file of pending runs


@pytest.mark.parametrize("module", ["numpy", "floatmoor.mooring.static_strength"])
def test_ctrl_c_during_imports_exits_130_with_one_line(module):
    # the interrupt is raised by an import hook, at the moment the module is imported
    script = (
        "import sys\n"
        "class Interrupt:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        f"        if name == {module!r}:\n"
        "            raise KeyboardInterrupt\n"
        "sys.meta_path.insert(0, Interrupt())\n"
        f"sys.argv = ['floatmoor', 'check', {str(LINDAHL_CASE)!r}]\n"
        "from floatmoor.cli import run\n"
        "run()\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            timeout=60, env={**os.environ, "PYTHONPATH": str(REPO)})
    assert result.returncode == 130
    assert result.stderr.strip().startswith("floatmoor: interrupted")
    assert len(result.stderr.strip().splitlines()) == 1


def test_nesting_depth_counts_without_recursion():
    value = []
    for _ in range(5000):
        value = [value]
    assert limits.nesting_depth(value) > limits.MAX_NESTING_DEPTH
    assert limits.nesting_depth({"a": {"b": [1]}}) == 3


def test_case_error_for_a_value_the_loader_copies(capsys):
    # a bound refused value is named with the --set that set it
    err = _refused(capsys, LINDAHL_CASE, "simulation.output_interval=1e-300")
    assert "(--set simulation.output_interval=1e-300)" in err
    with pytest.raises(CaseError):
        load_case(LINDAHL_CASE, ["simulation.duration=1e308"])


@pytest.mark.parametrize("period", ["1e-300", "1e308"])
def test_wave_period_beyond_the_dispersion_relation_is_a_case_error(capsys, period):
    # found by the mutation corpus: Newton's RuntimeError came out as a traceback
    err = _refused(capsys, CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml",
                   f"waves.period={period}")
    assert "waves.period: expected a wave period for which the dispersion relation" in err


def test_huge_motion_radius_is_one_line_without_numpy_warnings(capsys):
    """motion.radius = 1e308 overflows while the fairlead's path is sampled: one line, no
    RuntimeWarning before it (pytest turns a floatmoor warning into an error)."""
    err = _refused(capsys, CASES / "lindahl" / "lindahl_r0.20_T1.25.toml", "motion.radius=1e308")
    assert "motion.radius: expected a motion that keeps the fairlead of line 'chain' above " \
           "the seabed" in err
