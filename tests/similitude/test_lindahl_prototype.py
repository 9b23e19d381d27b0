"""The Lindahl chain in water with drag and its 1240 m prototype: the dimensionless
fairlead tension histories T / (w L) against t / T agree when every group is kept (the drag
and added-mass coefficients scaled by eqs. 38 and 42) and differ through the groups that are
not: drag coefficients left as they are (alpha_4, alpha_5: what a Reynolds-dependent C_d
does) or sea water in the prototype (alpha_3).

The runs start as the cases do, from the line settled by the DG relaxation, which runs on the
line's own time scale sqrt(L / g) (DynamicLine.settle_time_scale) and so scales with it; when
it ran on fixed times (20 1/s, 0.1 s chunks) it left the prototype 4.8e-3 of the peak tension
apart. Without the relaxation (``settle = false``) the histories agree as closely.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.mooring.dg import line as dg_line
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.similitude.case_scaling import scale_case_file
from floatmoor.similitude.laws import ScaleLaw
from floatmoor.simulation.run import run_case

ROOT = Path(__file__).parents[2]
LINDAHL_T350 = ROOT / "cases" / "lindahl" / "lindahl_r0.20_T3.50.toml"
LINDAHL_T125 = ROOT / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"

#: The 1240 m, 76 mm stud chain (chain-experiment paper section 3.1, Table 3): lambda =
#: 1240.8 / 33 (the 1:37.6 of its conclusions), beta = 76 / 2.2, phi = C_v,p / C_v,m from
#: the measured masses per length.
PROTOTYPE = ScaleLaw(
    length=37.6, diameter=76.0 / 2.2,
    volume_coefficient=(126.5 / 0.076 ** 2) / (0.0818 / 0.0022 ** 2))
#: Exact similitude as in test_scale_case.EXACT_SIMILITUDE (2.0e-10 measured here settled,
#: 1.7e-10 with settle = false).
EXACT_SIMILITUDE = 1e-6
#: Differences that are physics, not round-off: with the model's drag coefficients the
#: prototype's T / (w L) departs by 10 % of the peak, in sea water by 3 % (measured; the
#: bounds only say they are far above EXACT_SIMILITUDE).
GROUP_EFFECT = 0.01


def _dimensionless(case) -> tuple[np.ndarray, np.ndarray]:
    data = run_case(case).dataset
    line = case.lines[0]
    w = line.line_type.mass_per_length * case.environment.gravity
    return (data.time.values / case.motion.period,
            data.fairlead_tension.sel(line=line.name).values / (w * line.length))


def _differences(tmp_path: Path, model_file: Path, variants) -> dict[str, float]:
    """Largest |T/(wL) difference| over the last cycle, over the model's peak there."""
    tau, f_model = _dimensionless(load_case(model_file))
    last = tau >= tau[-1] - 1.0
    out = {}
    for label, law, keep in variants:
        scaled = scale_case_file(model_file, law, output=tmp_path / f"{label}.toml",
                                 keep_coefficients=keep).case
        tau_p, f_p = _dimensionless(scaled)
        np.testing.assert_allclose(tau_p, tau, rtol=0.0, atol=1e-12)
        out[label] = float(np.max(np.abs(f_p - f_model)[last]) / np.max(f_model[last]))
    return out


def test_model_and_prototype_agree_when_the_groups_do(tmp_path: Path) -> None:
    """The settled Lindahl chain (the case's default start) and its prototype."""
    text = LINDAHL_T350.read_text()
    assert "settle" not in text  # the default: settled
    path = tmp_path / "short.toml"
    path.write_text(text.replace("ramp_duration = 7.0", "ramp_duration = 3.5")
                    .replace("duration = 28.0", "duration = 10.5"))
    diff = _differences(tmp_path, path, [("prototype", PROTOTYPE, False),
                                         ("model_coefficients", PROTOTYPE, True)])
    assert diff["prototype"] <= EXACT_SIMILITUDE
    assert diff["model_coefficients"] > GROUP_EFFECT


@pytest.mark.slow
@pytest.mark.parametrize("settle", ["true", "false"], ids=["settled", "unsettled"])
@pytest.mark.parametrize("source", [LINDAHL_T125, LINDAHL_T350], ids=["T1.25", "T3.50"])
def test_full_runs_differ_only_through_the_groups_not_kept(tmp_path: Path, source: Path,
                                                           settle: str, capsys) -> None:
    path = tmp_path / source.name
    path.write_text(source.read_text().replace("slack_filter = true",
                                               f"slack_filter = true\nsettle = {settle}"))
    sea = ScaleLaw(PROTOTYPE.length, PROTOTYPE.diameter, PROTOTYPE.volume_coefficient, 1.024)
    diff = _differences(tmp_path, path, [("prototype", PROTOTYPE, False),
                                         ("model_coefficients", PROTOTYPE, True),
                                         ("sea_water", sea, False)])
    with capsys.disabled():
        print(f"\n{source.name}, settle = {settle}: T/(wL) over the last cycle, prototype - "
              "model, relative to "
              "the model's peak: " + ", ".join(f"{k} {v:.3g}" for k, v in diff.items()))
    assert diff["prototype"] <= EXACT_SIMILITUDE
    assert diff["model_coefficients"] > GROUP_EFFECT
    assert diff["sea_water"] > GROUP_EFFECT
    assert math.isfinite(sum(diff.values()))


def test_the_relaxation_scales_with_the_line(tmp_path: Path) -> None:
    """The settled start of a line and of its scaled copy: the same dimensionless state,
    reached in the same dimensionless time (the relaxation's rate and chunks follow the
    line's time scale sqrt(L / g), which scales sqrt(lambda))."""
    dg_line._SETTLED.clear()
    model = load_case(LINDAHL_T350)
    prototype = scale_case_file(LINDAHL_T350, PROTOTYPE, output=tmp_path / "p.toml").case
    lines = [DynamicLine.from_case(c.lines[0], c.environment, c.seabed)
             for c in (model, prototype)]
    a, b = (ln.settle_report for ln in lines)
    assert a is not None and b is not None and a.converged and b.converged
    assert lines[1].settle_time_scale() == pytest.approx(
        math.sqrt(PROTOTYPE.length) * lines[0].settle_time_scale(), rel=EXACT_SIMILITUDE)
    assert b.time == pytest.approx(math.sqrt(PROTOTYPE.length) * a.time, rel=EXACT_SIMILITUDE)
    np.testing.assert_allclose(lines[1].r, PROTOTYPE.length * lines[0].r, rtol=0.0,
                               atol=EXACT_SIMILITUDE * prototype.lines[0].length)
