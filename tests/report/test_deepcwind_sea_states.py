"""DeepCwind LC34 and LC43 (docs/cases/deepcwind.md): 3-hour sea states with each line model, compared as the
quasi-dynamic paper's section 5 does (docs/validation/coupled.md#deepcwind-sea-states).

Each load case runs once per line model through ``floatmoor compare`` (a campaign over the
models, with the published values as labelled reference columns), which also renders the
report; the checks read the same analysis the report prints (floatmoor.report.tables).

Required: the three LC34 runs complete 3 hours without instability; the standard deviation of
the most loaded line's tension (line 2, the upwave line) is within 25 % of the published
dynamic model's. The mean tensions are not compared: the published means sit on a platform
offset the paper does not give, so that check was retired (the offset analysis stays as
documentation: tests/mooring/test_deepcwind_mean_offset.py).
And the published ordering: the quasi-static standard deviation of line 2 well below
the others' and its fatigue damage orders of magnitude lower; dynamic and quasi-dynamic
damage within a factor 2 of each other.

About 15 minutes on the development machine (the dynamic runs dominate).
"""

from __future__ import annotations

import numpy as np
import pytest

from floatmoor.report.compare import compare_models
from floatmoor.report.reference import load_reference
from floatmoor.report.runs import load_run
from tests.conftest import CASES

pytestmark = [pytest.mark.slow, pytest.mark.validation]

MODELS = ("quasi-static", "quasi-dynamic", "dynamic")
DEEPCWIND = CASES / "deepcwind"
#: Required: LC34 standard deviation of the most loaded line against the published dynamic
#: model (docs/cases/deepcwind.md, quasi-dynamic paper Table 8: 392.0 kN).
STD_RTOL = 0.25
#: "Well below": the quasi-static standard deviation of line 2 at most half of the
#: others' (published: 119.6 against 364.3 and 392.0 kN, 0.31 and 0.33).
QS_STD_RATIO = 0.5
#: "Orders of magnitude lower": the quasi-static damage of line 2 below a tenth of
#: the others' (published: 1.75e-7 against 1.40e-4 and 2.20e-4).
QS_DAMAGE_RATIO = 0.1
#: Required: dynamic and quasi-dynamic damage within a factor 2 (published 1.57).
DAMAGE_FACTOR = 2.0


def _compare(tmp_path_factory, name: str):
    out = tmp_path_factory.mktemp(name) / "report"
    reference = load_reference(DEEPCWIND / f"published_{name}.toml")
    files = compare_models(DEEPCWIND / f"deepcwind_{name}.toml", MODELS, out,
                           reference=reference)
    runs = [load_run(out / "runs" / f"{model}.nc", label=model) for model in MODELS]
    analyses = dict(zip(MODELS, files.analyses))  # what the report printed
    return files, runs, analyses, reference


@pytest.fixture(scope="module")
def lc34(tmp_path_factory):
    return _compare(tmp_path_factory, "lc34")


@pytest.fixture(scope="module")
def lc43(tmp_path_factory):
    return _compare(tmp_path_factory, "lc43")


def _published(reference, column: str, line: str, quantity: str) -> float:
    return next(c for c in reference.columns if c.key == column).lines[line][quantity]


@pytest.mark.parametrize("name", ["lc34", "lc43"])
def test_three_hour_runs_complete_with_every_line_model(name, request):
    files, runs, _, _ = request.getfixturevalue(name)
    for model, run in zip(MODELS, runs):
        ds = run.dataset
        assert ds.attrs["status"] == "complete", model
        assert float(ds["time"].values[-1]) == pytest.approx(10800.0)
        for var in ("fairlead_tension", "body_displacement"):
            assert np.all(np.isfinite(ds[var].values)), (model, var)
    assert files.summary.is_file()


def test_lc34_std_of_the_most_loaded_line(lc34):
    _, _, analyses, reference = lc34
    published = _published(reference, "dynamic", "line2", "std")
    std = analyses["dynamic"].tension["line2"]["std"]
    print(f"\nLC34 line 2 tension STD: dynamic {std / 1e3:.1f} kN, published dynamic model "
          f"{published / 1e3:.1f} kN ({std / published - 1:+.1%})")
    assert std == pytest.approx(published, rel=STD_RTOL)


def test_lc34_published_ordering_of_the_line_models(lc34):
    _, _, analyses, _ = lc34
    std = {m: analyses[m].tension["line2"]["std"] for m in MODELS}
    damage = {m: analyses[m].damage["line2"] for m in MODELS}
    print(f"\nLC34 line 2: STD {', '.join(f'{m} {v / 1e3:.1f} kN' for m, v in std.items())}; "
          f"damage {', '.join(f'{m} {v:.3g}' for m, v in damage.items())}")
    others = min(std["quasi-dynamic"], std["dynamic"])
    assert std["quasi-static"] <= QS_STD_RATIO * others
    assert damage["quasi-static"] <= QS_DAMAGE_RATIO * min(damage["quasi-dynamic"],
                                                           damage["dynamic"])
    ratio = damage["dynamic"] / damage["quasi-dynamic"]
    assert 1.0 / DAMAGE_FACTOR <= ratio <= DAMAGE_FACTOR
