"""Resuming from a checkpoint of plain arrays gives the uninterrupted run's results bit for
bit with dynamic lines (with implicit internal damping, or the implicit time integration)
beside a quasi-static one too (the
quasi-dynamic and state-space cases are in test_coupled_run.py and test_state_space_run.py;
the damping's frozen factors, which a coupled run rebuilds often, in
tests/mooring/dg/test_model_state_arrays.py)."""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.simulation.interrupted import interrupt_run
from tests.conftest import CASES

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"


@pytest.mark.parametrize("overrides,kept", [
    # the damping's frozen factors are kept (14 s: slow, for the default run's time budget)
    pytest.param(['lines.line2.model="quasi-static"',
                  "line_types.chain.internal_damping_ratio=0.2"], "state/line0/damping_info",
                 marks=pytest.mark.slow, id="internal-damping"),
    # the implicit integration's acceleration variable, step level and factored Jacobian
    (['lines.*.dynamic.time_integration="implicit"', "lines.*.dynamic.max_time_step=0.0025"],
     "state/line0/implicit_band"),
], ids=["internal-damping", "implicit-integration"])
def test_dynamic_lines_resume_bit_identically(tmp_path, monkeypatch, overrides,
                                              kept) -> None:
    import floatmoor.simulation.coupled_run as cr

    monkeypatch.setattr(cr, "CHUNK_STEPS", 5)
    case = load_case(BUOY_CASE, [
        'lines.*.model="dynamic"', "lines.*.dynamic.elements=4", "lines.*.dynamic.order=3",
        *overrides, "simulation.duration=0.2", "simulation.output_interval=0.01",
        'waves={kind = "still"}', "initial={surge = 0.002}"])
    out = tmp_path / "cut.nc"
    interrupt_run(case, out, after_chunks=2)
    with np.load(cr.checkpoint_path(out), allow_pickle=False) as npz:
        assert "state/line0/positions" in npz.files
        assert kept in npz.files
        if kept.endswith("damping_info"):
            assert float(npz[kept][0]) == 1.0  # valid factors
    resumed = run_coupled(case, output=out, resume=True).dataset
    whole = run_coupled(case, output=tmp_path / "whole.nc").dataset
    for name in ("body_displacement", "body_velocity", "fairlead_tension", "anchor_tension",
                 "laid_length"):
        assert np.array_equal(resumed[name].values, whole[name].values), name
