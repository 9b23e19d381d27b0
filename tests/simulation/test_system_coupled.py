"""A floater on a mooring system : lines through free points in coupled runs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled

BUOY = Path(__file__).parents[2] / "cases" / "cylinder_buoy" / "buoy_regular_T1.20.toml"
#: The line the test splits, as the case file writes it.
_LINE1 = 'type = "chain"\nlength = 6.95\nanchor = [-3.4587, 5.9907, -0.9]'
#: Newton tolerances of the body equilibrium (coupled.EQUILIBRIUM_RTOL, 1e-9 of the static
#: force) and the statics (1e-9 of each point's force scale) leave the runs' last bits apart:
#: body motion to 1e-9 m, tensions to 1e-8 of their peak.
BODY_ATOL = 1e-9
TENSION_RTOL = 1e-8


def _split_case(tmp_path, sections: str, sets: list[str]):
    """The buoy case with line 1 written as ``sections`` (the file next to the original, so
    that its database resolves)."""
    text = BUOY.read_text()
    assert _LINE1 in text
    path = BUOY.parent / f"_test_split_{tmp_path.name}.toml"
    path.write_text(text.replace(_LINE1, f"sections = {sections}\n"
                                 "anchor = [-3.4587, 5.9907, -0.9]", 1))
    try:
        return load_case(path, sets)
    finally:
        path.unlink()


@pytest.mark.slow  # 5-10 s: the default-run budget (docs/development.md)
def test_quasi_static_line_split_by_a_joint_runs_as_the_unsplit_line(tmp_path):
    sets = ["simulation.duration=2.0", 'lines.*.model="quasi-static"']
    split = _split_case(tmp_path, '[{ type = "chain", length = 5.8 }, '
                        '{ type = "chain", length = 1.15 }]', sets)
    assert split.is_system
    one = run_coupled(load_case(BUOY, sets)).dataset
    two = run_coupled(split).dataset
    np.testing.assert_allclose(two["body_displacement"].values,
                               one["body_displacement"].values, rtol=0, atol=BODY_ATOL)
    peak = float(one["fairlead_tension"].max())
    np.testing.assert_allclose(two["fairlead_tension"].values, one["fairlead_tension"].values,
                               rtol=0, atol=TENSION_RTOL * peak)
    joint = two["point_force"].sel(point="line1.joint1").values
    assert np.abs(joint).max() <= TENSION_RTOL * peak  # a massless joint carries nothing


def _clump_case(tmp_path, sets: list[str]):
    """The buoy case with a 20 g clump at a joint of line 1."""
    text = BUOY.read_text().replace(
        _LINE1, 'sections = [{ type = "chain", length = 5.8, end = "clump", dynamic = '
        '{ elements = 8 } }, { type = "chain", length = 1.15, dynamic = { elements = 2 } }]\n'
        'anchor = [-3.4587, 5.9907, -0.9]', 1)
    text = text.replace("[[lines]]", '[[points]]\nname = "clump"\nkind = "free"\n'
                        "position = [-0.57, 0.99, -0.72]\nmass = 0.02\nvolume = 2.5e-6\n\n"
                        "[[lines]]", 1)
    path = BUOY.parent / f"_test_clump_{tmp_path.name}.toml"
    path.write_text(text)
    try:
        return load_case(path, sets)
    finally:
        path.unlink()


@pytest.mark.parametrize("model", ["quasi-static",  # dynamic: 26 s, the default budget
                                   pytest.param("dynamic", marks=pytest.mark.slow)])
def test_clump_weight_on_a_buoy_line_runs_coupled(tmp_path, model):
    """A 20 g clump at a joint of line 1, held by its lines."""
    # 0.3 s of the dynamic group: its start, settle and coupling are what is tested here
    duration = 1.0 if model == "quasi-static" else 0.3
    case = _clump_case(tmp_path, [f"simulation.duration={duration}",
                                  f'lines.*.model="{model}"'])
    ds = run_coupled(case).dataset
    assert ds.attrs["status"] == "complete"
    for name in ("point_position", "point_force", "section_end_tension", "body_displacement"):
        assert np.all(np.isfinite(ds[name].values)), name
    clump = case.point("clump")
    g, rho = case.environment.gravity, case.environment.water_density
    submerged = (clump.mass - rho * clump.volume) * g
    # the lines hold the clump: their net force on it is its submerged weight (statics; the
    # dynamic line also carries the clump's inertia, small at these motions)
    force = ds["point_force"].sel(point="clump").values
    tol = 1e-6 * submerged if model == "quasi-static" else 0.05 * submerged
    np.testing.assert_allclose(force[:, 2], submerged, rtol=0, atol=tol)


@pytest.mark.parametrize("model", ["quasi-static",
                                   pytest.param("dynamic", marks=pytest.mark.slow)])
def test_system_run_resumes_bit_identically(tmp_path, monkeypatch, model):
    """The checkpoint holds the groups' states (the statics' warm start, the DG system's
    nodes, points and damping factors): a resumed run is the uninterrupted one bit for bit."""
    import floatmoor.simulation.coupled_run as cr
    from tests.simulation.interrupted import interrupt_run

    monkeypatch.setattr(cr, "CHUNK_STEPS", 5)
    case = _clump_case(tmp_path, [f'lines.*.model="{model}"', "simulation.duration=0.2",
                                  "simulation.output_interval=0.01",
                                  "line_types.chain.internal_damping_ratio=0.2",
                                  'waves={kind = "still"}', "initial={surge = 0.002}"])
    out = tmp_path / "cut.nc"
    interrupt_run(case, out, after_chunks=2)
    with np.load(cr.checkpoint_path(out), allow_pickle=False) as npz:
        assert any(k.startswith("state/group0/") for k in npz.files)
    resumed = run_coupled(case, output=out, resume=True).dataset
    whole = run_coupled(case, output=tmp_path / "whole.nc").dataset
    for name in ("body_displacement", "fairlead_tension", "point_position", "point_force",
                 "section_end_tension", "laid_length"):
        assert np.array_equal(resumed[name].values, whole[name].values), name
