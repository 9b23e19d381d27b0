"""Loading valid case files: values, defaults, unit conversion, overrides."""

from __future__ import annotations

import math

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.case.schema import CircularMotion, HarmonicMotion, TableMotion
from floatmoor.errors import CaseError
from tests.conftest import ACCURACY_DEFAULT, CASES, LINDAHL_CASE


def test_lindahl_case_values():
    case = load_case(LINDAHL_CASE)
    assert case.environment.water_depth == 3.0
    assert case.environment.seabed_z == -3.0
    (line,) = case.lines
    assert line.name == "chain" and line.model == "dynamic"
    assert line.dynamic.elements == 10 and line.dynamic.order == 5
    assert line.anchor == (0.0, 0.0, -3.0) and line.fairlead == (32.554, 0.0, 0.3)
    assert line.line_type.tangential_added_mass_coefficient == 0.0  # default
    # wave celerity sqrt(EA/m) about 350 m/s (docs/cases/lindahl.md)
    assert line.line_type.axial_wave_speed == pytest.approx(349.64, abs=0.01)
    # submerged weight m g (1 - rho_w/rho_c)
    assert line.line_type.weight_in_water(case.environment) == pytest.approx(
        0.0818 * 9.81 * (1 - 1000 / 7800), rel=1e-14)
    assert isinstance(case.motion, CircularMotion)
    assert case.motion.cycle_period == 1.25
    assert "Lindahl" in case.text and case.overrides == ()


def test_overrides_by_name_and_new_subtable():
    case = load_case(LINDAHL_CASE, [
        "motion.period=3.5", "lines.chain.length=33.5", "lines.chain.anchor=[0.1, 0.0, -3.0]",
        "lines.chain.quasi_static.tolerance=1e-10", "motion.phase_deg=90.0",
    ])
    assert case.motion.period == 3.5
    assert case.lines[0].length == 33.5 and case.lines[0].anchor == (0.1, 0.0, -3.0)
    assert case.lines[0].quasi_static.tolerance == 1e-10
    assert case.motion.phase == pytest.approx(math.pi / 2)  # degrees in, radians inside
    assert case.overrides[0] == "motion.period=3.5"


def test_override_replacing_the_motion_table(tmp_path):
    case = load_case(LINDAHL_CASE, [
        'motion={kind = "harmonic", amplitude = [0.1, 0.0, 0.05], period = 2.0}'])
    assert isinstance(case.motion, HarmonicMotion)
    assert case.motion.period == (2.0, 2.0, 2.0) and case.motion.cycle_period == 2.0
    assert case.motion.ramp_duration == 2.0  # default: the longest moving period


def test_case_without_motion_is_static():
    text = LINDAHL_CASE.read_text()
    start, end = text.index("[motion]"), text.index("[simulation]")
    from floatmoor.case.load import parse_case
    import tomllib

    raw = tomllib.loads(text[:start] + text[end:])
    raw["title"] = "Lindahl chain at rest"  # its own names the motion's keys
    case = parse_case(raw, source="inline")
    assert case.motion is None


def test_table_motion_from_csv(tmp_path):
    csv = tmp_path / "motion.csv"
    csv.write_text("# surge and heave\ntime,x,y,z\n0.0,0,0,0\n10.0,0.5,0,-0.1\n20.0,0,0,0\n")
    case_file = tmp_path / "case.toml"
    text = LINDAHL_CASE.read_text().replace(  # the title's placeholders name circular keys
        "circular motion r = {motion.radius:.2f} m, T = {motion.period:.2f} s", "tabled motion")
    start, end = text.index("[motion]"), text.index("[simulation]")
    case_file.write_text(text[:start] + '[motion]\nkind = "table"\nfile = "motion.csv"\n\n'
                         + text[end:])
    case = load_case(case_file)
    assert isinstance(case.motion, TableMotion)
    np.testing.assert_array_equal(case.motion.time, [0.0, 10.0, 20.0])
    np.testing.assert_array_equal(case.motion.displacement[1], [0.5, 0.0, -0.1])
    # a table shorter than the run is an error naming simulation.duration
    with pytest.raises(CaseError) as info:
        load_case(case_file, ["simulation.duration=25.0"])
    assert info.value.key == "simulation.duration"
    # a malformed row names the CSV file and the row
    csv.write_text("time,x,y,z\n0.0,0,0,0\n10.0,abc,0,0\n")
    with pytest.raises(CaseError) as info:
        load_case(case_file)
    assert info.value.key == "motion.file" and "row 3" in info.value.expected


def test_loading_does_not_mutate_input():
    import tomllib
    from floatmoor.case.load import parse_case

    raw = tomllib.loads(LINDAHL_CASE.read_text())
    before = repr(raw)
    parse_case(raw, source="inline", overrides=("motion.period=2.0",))
    assert repr(raw) == before


def test_time_integration_and_accuracy_keys():
    """``[lines.dynamic] time_integration`` and ``accuracy``: defaults, values, and
    what is refused, with the key path and what was found."""
    default = load_case(LINDAHL_CASE).lines[0].dynamic
    assert default.time_integration == "explicit" and default.accuracy == 0.01  # the file's
    bare = load_case(CASES / "systems" / "three_line_clump_buoy.toml").lines[0].dynamic
    assert (bare.elements, bare.order, bare.time_integration) == (None, None, "auto")
    auto = load_case(LINDAHL_CASE, ACCURACY_DEFAULT).lines[0].dynamic  # "auto" = left out
    assert (auto.elements, auto.order, auto.time_integration) == (None, None, "auto")
    st = load_case(LINDAHL_CASE, ['lines.chain.dynamic.time_integration="implicit"',
                                  "lines.chain.dynamic.accuracy=0.05"]).lines[0].dynamic
    assert st.time_integration == "implicit" and st.accuracy == 0.05
    for override, found in (('lines.chain.dynamic.elements="many"', '"many"'),
                            ('lines.chain.dynamic.order="auto3"', '"auto3"'),
                            ('lines.chain.dynamic.time_integration="rk4"', '"rk4"'),
                            ("lines.chain.dynamic.accuracy=0.0", "0.0"),
                            ("lines.chain.dynamic.accuracy=0.3", "0.3"),
                            ('lines.chain.dynamic.accuracy="1%"', '"1%"')):
        with pytest.raises(CaseError) as err:
            load_case(LINDAHL_CASE, [override])
        key = override.split("=")[0].replace("lines.chain", "lines[0]")
        assert key in str(err.value) and found.strip('"') in str(err.value), str(err.value)


def test_case_file_replaced_by_a_fifo_after_the_look_does_not_block(tmp_path, monkeypatch):
    """The case file is opened without blocking and looked at again once open: a FIFO put in
    place of the regular file between the look and the open is refused, not waited on."""
    import os
    import stat as stat_module
    import threading
    from pathlib import Path

    from floatmoor.case import files
    from floatmoor.case.files import CaseFileKindError, read_case_text

    fifo = tmp_path / "case.toml"
    os.mkfifo(fifo)
    real_stat = os.stat

    class _Regular:  # what the first look saw: a regular file
        st_mode = stat_module.S_IFREG | 0o644

    monkeypatch.setattr(files.os, "stat", lambda p, *a, **k: _Regular()
                        if Path(p) == fifo else real_stat(p, *a, **k))
    outcome = []

    def read() -> None:
        try:
            read_case_text(fifo)
        except CaseFileKindError as err:
            outcome.append(str(err))

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(5.0)
    if reader.is_alive():  # blocked opening the FIFO: release it before failing
        os.close(os.open(fifo, os.O_WRONLY | os.O_NONBLOCK))
        reader.join(5.0)
    assert outcome and "FIFO" in outcome[0]


@pytest.mark.parametrize("override, key, expected", [
    ("floater.drag.strip_length=-1.0", "floater.drag.strip_length", "a finite number > 0 [m]"),
    ('floater.drag.preset="oc4"', "floater.drag.preset", 'one of "deepcwind_oc4", "none"'),
    ("floater.drag.member_axial=-0.1", "floater.drag.member_axial", "a finite number >= 0 [-]"),
    ('floater.drag.kinematics_interval="often"', "floater.drag.kinematics_interval",
     'a finite number >= 0 [s] or "auto"'),
])
def test_drag_keys_are_read_like_every_other_key(override, key, expected):
    """[floater.drag] goes through the reader: the error names the key itself and says what
    it expected (it named the table and quoted DragSettings' ValueError)."""
    with pytest.raises(CaseError) as info:
        load_case(CASES / "deepcwind" / "deepcwind_lc43.toml", [override])
    assert info.value.key == key and info.value.expected.startswith(expected)


def test_drag_preset_and_overrides_are_the_settings():
    case = load_case(CASES / "deepcwind" / "deepcwind_lc43.toml",
                     ['floater.drag={preset = "deepcwind_oc4", member_axial = 0.2, '
                      'kinematics_interval = "auto"}'])
    drag = case.floater.drag
    assert drag.coefficients.column_transverse == 0.6 and drag.coefficients.member_axial == 0.2
    assert drag.kinematics_interval is None and drag.strip_length == 2.0


@pytest.mark.parametrize("diameter", ["1e300", "1e-300"])
def test_a_cylinder_draft_from_the_mass_beyond_a_float_names_the_diameter(diameter):
    """The draft a cylinder floats at, mass / (rho pi R^2), overflows (R^2 beyond a float) or
    divides by zero (R^2 below one): the reader refuses the diameter instead of raising a
    Python OverflowError / ZeroDivisionError with a traceback."""
    with pytest.raises(CaseError) as error:
        load_case(CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml",
                  [f"floater.geometry.diameter={diameter}"])
    assert error.value.key == "floater.geometry.diameter"
    assert "finite draft > 0" in str(error.value)


@pytest.mark.parametrize("case, override, key", [
    ("systems/three_line_clump_buoy.toml", "simulation.shape_output_interval=1e308",
     "simulation.shape_output_interval"),
    ("lindahl/lindahl_r0.20_T1.25.toml", "simulation.time_step=1e-320",
     "simulation.time_step"),
    ("deepcwind/deepcwind_lc34.toml", "waves.omega_max=1e308", "waves.omega_max"),
])
def test_a_ratio_beyond_a_float_is_a_case_error(case, override, key):
    """An interval ratio or a wave-component count that overflows a float (round(inf),
    floor(inf) raised OverflowError with a traceback) is refused, naming the key."""
    with pytest.raises(CaseError) as error:
        load_case(CASES / case, [override])
    assert error.value.key == key, str(error.value)
