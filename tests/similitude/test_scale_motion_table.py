"""``floatmoor scale`` of a case with a motion table: the table is rewritten beside the scaled
case (times x sqrt(lambda), positions x lambda, angles unchanged), exactly reversible, and a
forced run on it is similar to the original."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.case.motion_body import BODY_TABLE_HEADERS
from floatmoor.case.motion_table import HEADER
from floatmoor.cli import main
from floatmoor.similitude.case_scaling import scale_case_file
from floatmoor.similitude.laws import ScaleLaw
from floatmoor.similitude.motion_tables import COLUMN_KINDS, scale_motion_table
from floatmoor.simulation.run import run_case

ROOT = Path(__file__).parents[2]
LINDAHL = ROOT / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
#: The Lindahl prototype law (as in test_lindahl_prototype.PROTOTYPE): every factor different.
PROTOTYPE = ScaleLaw(length=37.6, diameter=76.0 / 2.2,
                     volume_coefficient=(126.5 / 0.076 ** 2) / (0.0818 / 0.0022 ** 2))
#: Exact similitude as in test_scale_case.EXACT_SIMILITUDE: the table's cubic spline scales
#: exactly (times x sqrt(lambda), values x lambda), so what is left is round-off.
EXACT_SIMILITUDE = 1e-6
#: The circle the table traces (the Lindahl case's): radius [m], period [s].
RADIUS, PERIOD = 0.2, 1.25
#: Rows of the table [s]: no row but the first falls on an output sample (every 0.0025 s)
#: within the runs (the next at 2.5075 s): the round trip of the scaled decimals.
ROW_INTERVAL = 0.01003
#: Rows of the forced runs' table [s]: every fourth output sample falls on a row. With linear
#: interpolation the fairlead velocity jumped at the rows, and at a sample on a row the
#: round-off of a scaled row time could pick the other segment's slope: on this snapping chain
#: a 2.4e-3 jump in T / (w L) at the first such sample, 6.6 % of the peak 2.5 s later
#: (measured; the test then kept rows off the samples). The spline's velocity is continuous at
#: the rows: measured 2.4e-10 of the peak (linear interpolation: 2.4e-2 within these 2.5 s).
ROWS_ON_SAMPLES = 0.01
#: The runs last 2.5 s of the model's time (two cycles).
RUN_DURATION = 2.5
#: Scaled table values against the exact products: the snapping to short decimals
#: (floatmoor.similitude.decimals.SNAP_ULPS = 64 ulp, 1.4e-14 relative).
SNAPPED = 2e-14


def _table_case(folder: Path, duration: float = 4.0, every: float = ROW_INTERVAL) -> Path:
    """The Lindahl case driven by a table of its circle (6 decimals), a row every ``every`` [s]."""
    t = np.arange(0.0, duration + 1.0, every)
    w = 2.0 * math.pi / PERIOD
    rows = ["# the Lindahl circle about the fairlead", "time,x,y,z"] + [
        f"{a:.5f},{RADIUS * math.sin(w * a):.6f},0,{RADIUS * math.cos(w * a):.6f}" for a in t]
    (folder / "motion.csv").write_text("\n".join(rows) + "\n")
    text = LINDAHL.read_text().replace("{motion.radius:.2f}", "r").replace(
        "{motion.period:.2f}", "T")
    i, j = text.index("[motion]"), text.index("[simulation]")
    text = (text[:i] + '[motion]\nkind = "table"\nfile = "motion.csv"\nramp_duration = 1.25\n\n'
            + text[j:]).replace("duration = 15.0", f"duration = {duration}")
    case = folder / "case.toml"
    case.write_text(text)
    return case


def _values(path: Path) -> np.ndarray:
    rows = [r for r in path.read_text().splitlines() if r and not r.startswith("#")]
    return np.array([[float(c) for c in r.split(",")] for r in rows[1:]])


def test_a_motion_table_scales_and_back_to_the_original_numbers(tmp_path: Path) -> None:
    case = _table_case(tmp_path)
    there = scale_case_file(case, PROTOTYPE, output=tmp_path / "proto.toml")
    (table,) = there.tables
    assert table.path == tmp_path / "proto_motion.csv"
    assert 'file = "proto_motion.csv"' in there.text
    assert "Motion table proto_motion.csv" in there.text  # the header says so
    assert there.case.motion.file == str(table.path)
    (tmp_path / "proto.toml").write_text(there.text)
    table.path.write_text(table.text)
    old, new = _values(tmp_path / "motion.csv"), _values(table.path)
    np.testing.assert_allclose(new[:, 0], old[:, 0] * math.sqrt(37.6), rtol=SNAPPED)
    np.testing.assert_allclose(new[:, 1:], old[:, 1:] * 37.6, rtol=SNAPPED)
    back = scale_case_file(tmp_path / "proto.toml", PROTOTYPE.inverse(),
                           output=tmp_path / "back.toml")
    (undone,) = back.tables
    undone.path.write_text(undone.text)
    np.testing.assert_array_equal(_values(undone.path), old)  # the same decimals


def test_a_forced_run_on_the_scaled_table_is_similar(tmp_path: Path) -> None:
    case = _table_case(tmp_path, duration=RUN_DURATION, every=ROWS_ON_SAMPLES)
    scaled = scale_case_file(case, PROTOTYPE, output=tmp_path / "proto.toml")
    histories = []
    for c, factor in ((load_case(case), 1.0), (scaled.case, math.sqrt(PROTOTYPE.length))):
        data = run_case(c).dataset
        line = c.lines[0]
        w = line.line_type.mass_per_length * c.environment.gravity
        histories.append((data.time.values / factor,
                          data.fairlead_tension.sel(line=line.name).values / (w * line.length)))
    (tau_m, f_m), (tau_p, f_p) = histories
    np.testing.assert_allclose(tau_p, tau_m, rtol=0.0, atol=1e-12)
    assert f_m.max() > 2.0 * f_m[0]  # the motion loads the line
    assert np.max(np.abs(f_p - f_m)) <= EXACT_SIMILITUDE * np.max(f_m)


def test_the_command_writes_the_table_and_never_overwrites_one(tmp_path: Path,
                                                               capsys) -> None:
    case = _table_case(tmp_path)
    out = tmp_path / "proto.toml"
    argv = ["scale", str(case), "--length-scale", "37.6", "-o", str(out)]
    assert main(argv) == 0
    said = capsys.readouterr().out
    assert "proto_motion.csv" in said
    assert (tmp_path / "proto_motion.csv").exists() and out.exists()
    out.unlink()
    assert main(argv) == 2  # the table exists: refused, nothing written
    err = capsys.readouterr().err
    assert "motion.file" in err and "does not overwrite" in err and "Traceback" not in err
    assert not out.exists()


def test_body_tables_scale_translations_and_keep_rotations() -> None:
    law = ScaleLaw(4.0, 4.0, 1.0)
    for header in BODY_TABLE_HEADERS:
        text = ",".join(header) + "\n0,0,0,0,0,0,0\n1.5,0.25,-0.5,1,10,0.2,-3\n"
        rows = scale_motion_table(text, law, "note").splitlines()
        assert rows[0] == "# note" and rows[1] == ",".join(header)
        assert [float(c) for c in rows[3].split(",")] == [3.0, 1.0, -2.0, 4.0, 10.0, 0.2, -3.0]


def test_every_column_the_readers_take_has_a_scaling_rule() -> None:
    assert set(HEADER) | {c for h in BODY_TABLE_HEADERS for c in h} == set(COLUMN_KINDS)
