"""The whole MoorDyn flow on MoorDyn's own decks and floatmoor's cases: every imported deck
loads; import -> export -> import gives the same case; MoorDyn 2.7 reads and initialises the
exported decks (and gives the original deck's fairlead forces on them); the imported cases run
with every line model they allow and refuse the others cleanly."""

from __future__ import annotations

import math

import pytest

from floatmoor.case.load import load_case
from floatmoor.cli import main
from floatmoor.io.moordyn.parser import read_deck
from tests.io.moordyn_decks import (DECKS, IMPORTABLE, INDEPENDENT, REPO, SYSTEMS,
                                    TEST_IC_TIME, differences, export_file, import_file,
                                    moordyn_initial_forces)

#: MoorDyn's static solution of the same mooring from two decks: its initial-condition solve
#: stops at threshIC-level residuals (6e-6 measured on OC3 at equal segment counts), and WD0050's
#: 82 segments become 85 (17 elements of order 5): 3e-4 measured.
SAME_MOORING_RTOL = 1e-3
#: The shipped cases MoorDyn can represent (lines of one type, fixed anchors, body fairleads):
#: Lindahl's chain, the quasi-dynamic verification lines, the DeepCwind lines (their floater is
#: not exported: its fairleads are coupled points).
SHIPPED = ("lindahl/lindahl_r0.20_T1.25.toml", "qd_verification/s1_d1.toml",
           "qd_verification/s2_d2.toml", "qd_verification/s3_d1.toml",
           "deepcwind/deepcwind_lc34.toml")


@pytest.mark.parametrize("name", IMPORTABLE)
def test_every_imported_deck_loads(name, tmp_path):
    deck = read_deck(DECKS / name)
    case = load_case(import_file(name, tmp_path))
    assert [line.name for line in case.lines] == [f"line{ln.number}" for ln in deck.lines]
    assert [p.name for p in case.points] == [f"point{p.number}" for p in deck.points]
    kinds = {"fixed": "fixed", "coupled": "body", "body": "body", "free": "free"}
    assert [p.kind for p in case.points] == [kinds[p.attachment] for p in deck.points]
    assert case.is_system == (name in SYSTEMS)


@pytest.mark.parametrize("name", IMPORTABLE)
def test_import_export_import_gives_the_same_case(name, tmp_path):
    first = load_case(import_file(name, tmp_path))
    exported = export_file(first, tmp_path / "exported.dat")
    again = load_case(import_file(str(exported), tmp_path))
    assert differences(first, again) == []


@pytest.mark.parametrize("name", list(IMPORTABLE))
def test_moordyn_initialises_the_export_of_an_imported_deck(name, tmp_path):
    pytest.importorskip("moordyn")
    case = load_case(import_file(name, tmp_path))
    path = export_file(case, tmp_path / "exported.dat", {"TmaxIC": repr(TEST_IC_TIME)})
    status, forces = moordyn_initial_forces(path)
    assert status == 0
    assert len(forces) == 3 * sum(p.kind == "body" for p in case.points)
    assert all(math.isfinite(f) for f in forces)


@pytest.mark.parametrize("name", ["oc3_hywind_lines.txt", "wd0050_chain.txt"])
def test_moordyn_gives_the_same_fairlead_forces_on_the_deck_and_its_round_trip(name, tmp_path):
    """The mapping carries the physics: MoorDyn's static fairlead forces on the original deck
    and on export(import(deck)) agree."""
    pytest.importorskip("moordyn")
    case = load_case(import_file(name, tmp_path))
    path = export_file(case, tmp_path / "exported.dat")
    copy = tmp_path / name  # MoorDyn writes its .log and .out files next to the deck
    copy.write_bytes((DECKS / name).read_bytes())
    status_a, original = moordyn_initial_forces(copy)
    status_b, exported = moordyn_initial_forces(path)
    assert status_a == status_b == 0
    scale = max(abs(f) for f in original)
    assert max(abs(a - b) for a, b in zip(original, exported)) < SAME_MOORING_RTOL * scale


@pytest.mark.parametrize("relative", SHIPPED + ("../tests/data/systems/clump_buoy.toml",))
def test_moordyn_initialises_the_export_of_a_shipped_case(relative, tmp_path):
    pytest.importorskip("moordyn")
    case = load_case(REPO / "cases" / relative)
    path = export_file(case, tmp_path / "exported.dat", {"TmaxIC": repr(TEST_IC_TIME)})
    status, forces = moordyn_initial_forces(path)
    assert status == 0
    body = [p for p in case.points if p.kind == "body"]
    assert len(forces) == 3 * len(body) > 0
    # every line pulls its fairlead down (weight) and towards its anchor
    for i, p in enumerate(body):
        fx, fy, fz = forces[3 * i:3 * i + 3]
        anchors = [case.point(s.start).position for s in case.sections if s.end == p.name]
        ax, ay, _ = anchors[0]
        assert fz < 0.0
        assert fx * (ax - p.position[0]) + fy * (ay - p.position[1]) > 0.0


#: The dynamic runs of the two floating-platform decks cost 12-27 s each (stiff lines, small
#: explicit steps): slow; the shallow chain's dynamic run stays in the default run.
#: Decks whose dynamic run is slow (seconds to tens of seconds): their quasi-static and
#: quasi-dynamic runs, and the dynamic run of the other decks, stay in the default run.
_DEAR_DYNAMIC = {"oc3_hywind_lines.txt", "mhk_rm1_floating.dat", "wd0050_chain.txt"}


@pytest.mark.parametrize("name, model", [
    pytest.param(name, model, marks=pytest.mark.slow) if model == "dynamic" and
    name in _DEAR_DYNAMIC else (name, model)
    for name in INDEPENDENT for model in ("quasi-static", "quasi-dynamic", "dynamic")])
def test_imported_independent_lines_run_with_every_model(name, model, tmp_path, capsys):
    case_path = import_file(name, tmp_path)
    out = tmp_path / "run.nc"
    code = main(["run", str(case_path), "--quiet", "-o", str(out),
                 "--set", "simulation.duration=0.1", "--set", f'lines.*.model="{model}"'])
    assert code == 0, capsys.readouterr().err
    import xarray as xr

    with xr.open_dataset(out) as ds:
        tension = ds["fairlead_tension"]
        assert tension.sizes["line"] == len(read_deck(DECKS / name).lines)
        assert float(tension.min()) > 0.0


@pytest.mark.parametrize("name", SYSTEMS)
def test_imported_systems_run_dynamic(name, tmp_path, capsys):
    """Free points: the dynamic model runs them (MoorDyn's decks are dynamic); their point
    positions are recorded. (Unsettled: relaxing the tripod takes minutes of wall time at
    its stiffest section's step, and is not what is tested here.)"""
    case_path = import_file(name, tmp_path)
    out = tmp_path / "run.nc"
    code = main(["run", str(case_path), "--quiet", "-o", str(out),
                 "--set", "simulation.duration=0.1", "--set", "lines.*.dynamic.settle=false"])
    assert code == 0, capsys.readouterr().err
    import numpy as np
    import xarray as xr

    deck = read_deck(DECKS / name)
    with xr.open_dataset(out) as ds:
        assert ds.sizes["point"] == len(deck.points)
        assert ds.sizes["section"] == len(deck.lines)
        assert np.isfinite(ds["point_position"].values).all()


@pytest.mark.parametrize("name", SYSTEMS)
@pytest.mark.parametrize("model, message", [
    ("quasi-static", "needs a line that sinks"),
    ("quasi-dynamic", "the quasi-dynamic model solves one section from a fixed point to a body"),
])
def test_imported_systems_refuse_the_models_they_do_not_allow(name, model, message, tmp_path,
                                                              capsys):
    """These decks' lines are neutrally buoyant or buoyant (no catenary) and end at free
    points (no quasi-dynamic line): status 2, one line, nothing written."""
    case_path = import_file(name, tmp_path)
    out = tmp_path / "run.nc"
    code = main(["run", str(case_path), "--quiet", "-o", str(out),
                 "--set", "simulation.duration=0.1", "--set", f'lines.*.model="{model}"'])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    assert message in err and str(case_path) in err
    assert not out.exists()
