"""Work and output sized by the input are bounded before they start, and extreme input gives
one line and status 2 rather than a traceback, a hang or a flooded terminal.

Titles: a format spec's width and precision and the filled title's length are bounded (a
``{motion.radius:300000000.2f}`` title took a gigabyte). Text from a file printed by the
command line is escaped (:func:`floatmoor.terminal_text.shown`); a UTF-8 byte order mark at
the start of a case is dropped. ``floatmoor check`` is linear in the number of lines. A closed
standard output ends any command quietly.
"""

from __future__ import annotations

import subprocess
import sys
import re
import time

import pytest

from floatmoor.case.load import load_case
from floatmoor.case.title import MAX_SPEC_FIELD, MAX_TITLE_CHARS
from floatmoor.cli import EXIT_BROKEN_PIPE, main
from floatmoor.errors import CaseError
from tests.cli.many_lines import many_lines_case
from tests.conftest import LINDAHL_CASE, REPO


def _status_2_one_line(capsys, argv) -> str:
    status = main(argv)
    captured = capsys.readouterr()
    assert status == 2, captured.err
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("floatmoor: error: "), captured.err
    assert captured.out == ""
    return lines[0]


# -- titles ------------------------------------------------------------------------------------

@pytest.mark.parametrize("title, words", [
    ("{motion.radius:300000000.2f}", f"width at most {MAX_SPEC_FIELD}"),
    ("{motion.radius:99999999999}", f"width at most {MAX_SPEC_FIELD}"),
    ("{motion.radius:.65f}", f"precision at most {MAX_SPEC_FIELD}"),
    ("{motion.radius:>100000}", f"width at most {MAX_SPEC_FIELD}"),
    ("x" * (MAX_TITLE_CHARS + 1), f"at most {MAX_TITLE_CHARS} characters"),
    ("{motion.radius:64.60f}" * 20, f"at most {MAX_TITLE_CHARS} characters"),
])
def test_a_title_cannot_size_the_output(capsys, title, words):
    """It took 1 GB in check, wrote a 200 MB file in run, and 99999999999 raised MemoryError."""
    start = time.perf_counter()
    line = _status_2_one_line(capsys, ["check", str(LINDAHL_CASE), "--set", f'title="{title}"'])
    assert "title: expected" in line and words in line
    assert len(line) < 2500
    assert time.perf_counter() - start < 30.0


def test_widths_up_to_the_bound_still_format():
    case = load_case(LINDAHL_CASE, [f'title="r = {{motion.radius:>{MAX_SPEC_FIELD}.3f}}"'])
    assert case.title == "r = " + " " * (MAX_SPEC_FIELD - 5) + "0.200"


def test_a_title_with_terminal_escapes_is_printed_escaped(capsys):
    """``run`` and ``check`` printed ESC ] 0; ... BEL raw: the terminal obeyed it."""
    status = main(["check", str(LINDAHL_CASE), "--set", 'title="\\u001b]0;owned\\u0007 x\\r"'])
    out = capsys.readouterr().out
    assert status == 0
    assert "\x1b" not in out and "\x07" not in out and "\r" not in out
    assert 'valid case "\\x1b]0;owned\\x07 x\\x0d"' in out


def test_the_run_summary_escapes_the_title():
    from floatmoor.post.summary import format_summary

    text = format_summary({"title": "a\x1b[2Jb", "lines": {}})
    assert text.splitlines()[0] == "a\\x1b[2Jb"


def test_an_error_quoting_file_text_is_one_escaped_line(capsys):
    line = _status_2_one_line(capsys, ["check", str(LINDAHL_CASE), "--set",
                                       'title="{motion.radius:\\u001b[2J}"'])
    assert "\x1b" not in line and "\\x1b[2J" in line


def test_hydro_info_escapes_the_database_attributes(tmp_path, capsys):
    """A database is a file from elsewhere: its recorded attributes are file text."""
    import xarray as xr

    with xr.open_dataset(REPO / "hydrodb" / "cylinder_buoy.nc") as ds:
        ds = ds.load()
    ds.attrs["floater"] = "cyl\x1b]0;owned\x07"
    ds.to_netcdf(tmp_path / "evil.nc")
    assert main(["hydro", "info", str(tmp_path / "evil.nc")]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out
    assert "floater cyl\\x1b]0;owned\\x07 (cylinder)" in out


def test_a_byte_order_mark_at_the_start_of_a_case_is_dropped(tmp_path, capsys):
    """A UTF-8 BOM (written by some Windows editors) gave a bare 'syntax error'."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + LINDAHL_CASE.read_bytes())
    assert main(["check", str(path)]) == 0
    assert "valid case" in capsys.readouterr().out
    assert load_case(path).text == LINDAHL_CASE.read_text()


# -- check is linear in the number of lines -----------------------------------------------------

def _time_per_lookup(case) -> float:
    """The shortest of several timings of a lookup of every point, per lookup [s]."""
    names = [p.name for p in case.points] * 5
    best = float("inf")
    for _ in range(7):
        start = time.perf_counter()
        for name in names:
            case.point(name)
        best = min(best, time.perf_counter() - start)
    return best / len(names)


def test_point_lookup_does_not_grow_with_the_number_of_points(tmp_path):
    """Case.point scanned every point: a lookup per line end made loading quadratic (8x the
    points made a lookup 8x slower)."""
    small = load_case(many_lines_case(tmp_path, 150))
    large = load_case(many_lines_case(tmp_path, 1200))
    assert len(large.points) == 8 * len(small.points)
    assert _time_per_lookup(large) < 3.0 * _time_per_lookup(small)


def test_check_time_grows_linearly_with_the_lines(tmp_path, capsys):
    """check on a 5000-line case took 36 s: 4x the lines must take less than 8x the time
    (CPU time of this process: wall time on a loaded machine made it fail at 9x)."""
    small, large = many_lines_case(tmp_path, 150), many_lines_case(tmp_path, 600)
    assert main(["check", str(small)]) == 0  # compiles and imports outside the timing

    def timed(path) -> float:
        start = time.process_time()
        assert main(["check", str(path)]) == 0
        return time.process_time() - start

    t_small = min(timed(small), timed(small))
    t_large = timed(large)
    capsys.readouterr()
    assert t_large < 8.0 * t_small, (t_small, t_large)


# -- a closed standard output --------------------------------------------------------------------

@pytest.mark.parametrize("args", [["check", str(LINDAHL_CASE)], ["hydro", "info", "{db}"]])
def test_a_closed_pipe_ends_the_command_quietly(args):
    """``floatmoor check ... | head`` ended in a BrokenPipeError traceback."""
    db = REPO / "hydrodb" / "cylinder_buoy.nc"
    argv = [a.format(db=db) for a in args]
    proc = subprocess.Popen([sys.executable, "-m", "floatmoor", *argv], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, cwd=REPO)
    proc.stdout.close()  # the reader has gone before the first line is written
    _, err = proc.communicate(timeout=120)
    assert b"Traceback" not in err and b"BrokenPipe" not in err, err
    assert err == b""
    assert proc.returncode == EXIT_BROKEN_PIPE


# -- the work of a dynamic line is estimated before its first step --------------------------------

def test_an_unphysical_gravity_is_refused_at_load(capsys):
    """g = 1e-9 made the chain's settle last 11 sqrt(L / g) = 2e6 s: a 0.5 s run hung."""
    line = _status_2_one_line(capsys, ["check", str(LINDAHL_CASE), "--set",
                                       "environment.gravity=1e-9"])
    assert "environment.gravity: expected a finite number >= 1 and <= 30 [m/s^2]" in line


@pytest.mark.parametrize("command, overrides, what", [
    ("check", ["lines.chain.dynamic.cfl=1e-6"], "for the initial settle"),
    ("run", ["lines.chain.dynamic.cfl=1e-5", "lines.chain.dynamic.settle=false"], "for the run"),
])
def test_a_dynamic_line_step_count_is_bounded_before_it_starts(capsys, tmp_path, command,
                                                               overrides, what):
    """cfl = 1e-6 ran with no estimate (hours in the settle): refused at once, with the
    estimate and the key that sets the step."""
    from floatmoor.mooring.dg.line import MAX_DYNAMIC_STEPS

    out = tmp_path / "out.nc"
    argv = [command, str(LINDAHL_CASE), *(a for o in overrides for a in ("--set", o))]
    argv += ["-o", str(out), "--quiet"] if command == "run" else []
    start = time.perf_counter()
    line = _status_2_one_line(capsys, argv)
    assert time.perf_counter() - start < 60.0
    assert line.startswith(f"floatmoor: error: {LINDAHL_CASE}")
    assert "lines.chain.dynamic.cfl: expected numerics giving at most " \
        f"{MAX_DYNAMIC_STEPS:.3g} explicit steps" in line
    assert what in line and "steps" in line.split("found")[-1]
    assert list(tmp_path.iterdir()) == []


def test_a_dynamic_systems_step_count_is_bounded_before_it_settles(capsys, tmp_path):
    """The same for lines of several sections joined at points (a DG system), named by the
    case's line whose section has the shortest step."""
    from floatmoor.mooring.dg.line import MAX_DYNAMIC_STEPS

    system = LINDAHL_CASE.parents[1] / "systems" / "three_line_clump_buoy.toml"
    out = tmp_path / "out.nc"
    start = time.perf_counter()
    line = _status_2_one_line(capsys, ["run", str(system), "-o", str(out), "--quiet", "--set",
                                       'lines.*.model="dynamic"', "--set",
                                       "lines.*.dynamic.cfl=1e-6"])
    assert time.perf_counter() - start < 60.0
    assert re.search(r"lines\.line\d\.dynamic\.cfl: expected numerics giving at most "
                     + re.escape(f"{MAX_DYNAMIC_STEPS:.3g} explicit steps"), line), line
    assert "the system's initial settle" in line
    assert list(tmp_path.iterdir()) == []


# -- extreme values: one line and status 2, not a traceback ------------------------------------

DEEPCWIND = LINDAHL_CASE.parents[1] / "deepcwind" / "deepcwind_lc43.toml"


@pytest.mark.parametrize("argv, says", [
    (["check", str(LINDAHL_CASE), "--set", 'motion={kind="table", file="a\\u0000b"}'],
     "motion.file: expected a path to a regular file"),
    (["check", str(DEEPCWIND), "--set",
      "floater.geometry.columns.1.heave_plate_diameter=1e308"],
     "floater.geometry: expected dimensions giving a finite wetted area"),
    (["check", str(DEEPCWIND), "--set", "floater.mass=1e308"],
     "floater.mass: expected a mass and centre of mass whose weight"),
    (["check", str(DEEPCWIND), "--set", "floater.centre_of_mass=[0, 0, 1e308]"],
     "floater.centre_of_mass: expected a mass and centre of mass"),
    (["export", "moordyn", str(LINDAHL_CASE), "--set", 'lines.chain.name="a\\nb"', "-o",
      "{tmp}/deck.dat"], "lines[0].name: expected a name without control"),
    (["scale", str(LINDAHL_CASE), "--length-scale", "1e308", "-o", "{tmp}/s.toml"],
     "--length-scale: expected a number from 1e-06 to 1e+06"),
    (["scale", str(LINDAHL_CASE), "--match", "elastic", "--length-scale", "1e150", "-o",
      "{tmp}/s.toml"], "--length-scale: expected a number from 1e-06 to 1e+06"),
])
def test_extreme_values_are_one_line_and_status_2(capsys, tmp_path, argv, says):
    """Each was a traceback: ValueError (embedded null byte), OverflowError (wetted area,
    scale factors), LinAlgError (the equilibrium of an infinite weight), ValueError (a
    newline in an exported deck's note)."""
    line = _status_2_one_line(capsys, [a.replace("{tmp}", str(tmp_path)) for a in argv])
    assert says in line
    assert list(tmp_path.iterdir()) == []


def test_an_infinite_static_force_is_bad_input_not_a_linalg_error():
    """The equilibrium solve of a non-finite static force raised LinAlgError (SVD did not
    converge); whatever got past loading, it is a CaseError at floater."""
    from types import SimpleNamespace

    import numpy as np

    from floatmoor.simulation.coupled import equilibrium

    body = SimpleNamespace(static_force=np.array([0.0, 0.0, -np.inf, 0.0, 0.0, 0.0]),
                           stiffness=np.eye(6))
    case = load_case(LINDAHL_CASE)
    with pytest.raises(CaseError) as info:
        equilibrium(body, [], np.zeros((0, 3)), np.zeros(3), case.environment, case.seabed)
    assert info.value.key == "floater"


def test_the_radiation_kernel_samples_are_bounded_before_allocation():
    """simulation.time_step = 1e-9 on the buoy asked np.linspace for 2.29 TiB of kernel."""
    import xarray as xr

    from floatmoor.body.model import MAX_KERNEL_SAMPLES, build_body

    case = load_case(LINDAHL_CASE.parents[1] / "cylinder_buoy" / "buoy_regular_T1.00.toml")
    with xr.open_dataset(REPO / "hydrodb" / "cylinder_buoy.nc") as ds:
        start = time.perf_counter()
        with pytest.raises(CaseError) as info:
            build_body(case.floater, ds.load(), case.environment, 1e-7)
    assert time.perf_counter() - start < 10.0
    assert info.value.key == "simulation.time_step"
    assert f"at most {MAX_KERNEL_SAMPLES:.3g} samples of the radiation kernel" in \
        info.value.expected


def test_moordyn_import_escapes_the_deck_text_it_quotes(tmp_path, capsys):
    """A deck line with a terminal escape is refused (a text deck has no control characters:
    floatmoor.io.moordyn.parser), and the refusal quotes it escaped, in one line."""
    deck = (REPO / "tests" / "data" / "moordyn" / "oc3_hywind_lines.txt").read_text()
    assert "writeLog" in deck
    path = tmp_path / "deck.txt"
    path.write_text(deck.replace("writeLog", "write\x1b]0;owned\x07Log"))
    assert main(["import", "moordyn", str(path), "-o", str(tmp_path / "case.toml")]) == 2
    captured = capsys.readouterr()
    assert "\x1b" not in captured.err and "\x07" not in captured.err
    assert "write\\x1b]0;owned\\x07Log" in captured.err
    assert len(captured.err.strip().splitlines()) == 1
    assert not (tmp_path / "case.toml").exists()
