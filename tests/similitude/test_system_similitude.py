"""A mooring system with free points and its scaled copy: the chain-rope-chain line
with a clump weight and a buoy of tests/data/systems/clump_buoy_seabed.toml, dynamic, settled
(the default start) and scaled by floatmoor.similitude (the path of ``floatmoor scale``).

The system's relaxation runs on its own time scale sqrt(L / g), L its longest line
(DynamicSystem.settle_time_scale), so the scaled system settles through the same
dimensionless history into the same dimensionless state, and the forced runs from there are
exactly similar. With the former fixed times (2.0 1/s, 0.1 s chunks, kinetic checks every
0.02 s) the scaled system settled in 1.05 times the original's time instead of
sqrt(lambda) = 2, its settled points differed by 3.6e-7 of the line length and its run by
4.8e-5 of the peak tension (this file's cases, measured).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.system import DynamicSystem
from floatmoor.similitude.case_scaling import scale_case_file
from floatmoor.similitude.laws import ScaleLaw
from floatmoor.simulation.run import run_case

SYSTEM = Path(__file__).parents[1] / "data" / "systems" / "clump_buoy_seabed.toml"
#: The line dynamic and coarse (6 elements of order 3 a section: the run takes ~1 s), the
#: anchor moved out so that the clump hangs above the seabed (as in
#: tests/mooring/dg/test_dg_system_start.py; the lower chain still touches down), forced by a
#: short surge-heave motion.
EDITS = {
    'model = "quasi-static"': 'model = "dynamic"',
    "position = [-400.0, 0.0, -100.0]": "position = [-430.0, 0.0, -100.0]",
    "duration = 10.0\noutput_interval = 0.5": "duration = 2.0\noutput_interval = 0.05",
}
TAIL = """
[lines.dynamic]
elements = 6
order = 3

[motion]
kind = "harmonic"
amplitude = [1.0, 0.0, 0.5]
period = 4.0
ramp_duration = 1.0
"""
#: Every factor different from 1 and from each other, as in test_scale_case.DISTORTED.
LAW = ScaleLaw(length=4.0, diameter=2.5, volume_coefficient=1.3)
#: Exact similitude of a settled system: what is left is round-off and the 12 significant
#: digits of the scaled case (measured: 6.2e-11 of the peak tension, the settle time ratio
#: sqrt(lambda) to 1e-15 and the settled points to 1e-15 of the line length). The bound is far
#: below what the former fixed settle times left (module docstring).
SYSTEM_SIMILITUDE = 1e-8


def _cases(tmp_path: Path):
    text = SYSTEM.read_text()
    for old, new in EDITS.items():
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "system.toml"
    path.write_text(text + TAIL)
    return load_case(path), scale_case_file(path, LAW, output=tmp_path / "scaled.toml").case


def _dimensionless(case) -> tuple[np.ndarray, np.ndarray]:
    """t / T and T_fairlead / (w L), w the weight per length in air of the bottom chain and L
    the line's length."""
    data = run_case(case).dataset
    assert data.attrs["status"] == "complete"
    line = case.lines[0]
    w = line.sections[0].line_type.mass_per_length * case.environment.gravity
    period = float(np.max(case.motion.period))
    return (data.time.values / period,
            data.fairlead_tension.sel(line=line.name).values / (w * line.length))


def test_scaled_system_settles_to_the_scaled_state_in_the_scaled_time(tmp_path: Path) -> None:
    original, scaled = _cases(tmp_path)
    a, b = DynamicSystem.from_case(original), DynamicSystem.from_case(scaled)
    assert {p.name for p in a.points if p.kind == "free"} == {"clump", "buoy"}
    assert a.settle_report.converged and b.settle_report.converged
    assert math.isclose(b.settle_time_scale(), math.sqrt(LAW.length) * a.settle_time_scale(),
                        rel_tol=1e-12)
    print(f"\nsettled in {a.settle_report.time:.4f} s and {b.settle_report.time:.4f} s")
    assert abs(b.settle_report.time / a.settle_report.time - math.sqrt(LAW.length)) \
        <= SYSTEM_SIMILITUDE
    length = original.lines[0].length
    moved = np.abs(b.x / LAW.length - a.x).max() / length
    print(f"settled points differ by {moved:.1e} of the line length")
    assert moved <= SYSTEM_SIMILITUDE


def test_scaled_system_run_is_exactly_similar(tmp_path: Path) -> None:
    original, scaled = _cases(tmp_path)
    tau, f = _dimensionless(original)
    tau_s, f_s = _dimensionless(scaled)
    np.testing.assert_allclose(tau_s, tau, rtol=0.0, atol=1e-12)
    assert np.ptp(f) > 0.1 * np.max(f)  # a dynamic response, not a line at rest
    difference = float(np.max(np.abs(f_s - f)) / np.max(f))
    print(f"\nT / (w L) differs by {difference:.1e} of the peak")
    assert difference <= SYSTEM_SIMILITUDE
