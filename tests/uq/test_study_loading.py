"""Strict reading of study files: each rule gives one message naming the study file, the key
path, what was expected and what was found; ``floatmoor uq`` prints it, exits with 2 and
writes nothing."""

from __future__ import annotations

from pathlib import Path

import pytest

from floatmoor.cli import main
from floatmoor.errors import CaseError
from floatmoor.uq.study import load_study
from tests.conftest import CASES, LINDAHL_CASE

BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"

#: A valid case study; the bad studies below edit one thing of it.
GOOD = f"""
title = "quick"
case = "{LINDAHL_CASE}"
base_overrides = ["simulation.duration=3.75"]

[[inputs]]
key = "line_types.chain.normal_drag_coefficient"
distribution = "uniform"
lower = 1.25
upper = 3.75

[method]
kind = "quadrature"
order = 2

[[quantities]]
name = "cycle_max"
line = "chain"
statistic = "mean_cycle_max"

[[quantities]]
name = "cycle"
line = "chain"
statistic = "history"
window = [2.5, 3.75]
"""

#: (test id, (old, new) edit of GOOD, key path, fragment of expected, fragment of found)
BAD = [
    ("unknown_top_key", ('title = "quick"', 'title = "quick"\ncolour = 3'), "colour",
     "one of the known keys", "the unknown key 'colour'"),
    ("missing_title", ('title = "quick"', ""), "title", "a non-empty string",
     "nothing (the key is missing)"),
    ("case_and_model", ('title = "quick"', 'title = "quick"\nmodel = "taut_string"'), "case",
     "either case", "both case and model"),
    ("case_missing_file", (str(LINDAHL_CASE), "no_such_case.toml"), "case",
     "a case file (path relative to the study file)", "no such file"),
    ("bad_base_override", ("simulation.duration=3.75", "simulation.duration=-1.0"),
     "base_overrides", "a case that loads with these overrides", "simulation.duration"),
    ("unknown_distribution", ('distribution = "uniform"', 'distribution = "weibull"'),
     "inputs[0].distribution", '"uniform"', 'the string "weibull"'),
    ("missing_parameter", ("upper = 3.75\n", ""), "inputs[0].upper", "a finite number",
     "nothing (the key is missing)"),
    ("wrong_type_parameter", ("lower = 1.25", 'lower = "1.25"'), "inputs[0].lower",
     "a finite number", 'the string "1.25"'),
    ("upper_below_lower", ("upper = 3.75", "upper = 1.0"), "inputs[0]",
     "valid uniform parameters", "lower = 1.25, upper = 1"),
    ("key_not_in_case", ("line_types.chain.normal_drag_coefficient",
                         "line_types.chain.drag_coefficient_normal"), "inputs[0].key",
     "a --set key path of the case", '"line_types.chain.drag_coefficient_normal", which the '
     "case refuses"),
    ("key_of_wrong_type", ("line_types.chain.normal_drag_coefficient", "lines.chain.model"),
     "inputs[0].key", "takes the input's mean 2.5", "lines.chain.model"),
    ("unknown_method", ('kind = "quadrature"', 'kind = "monte-carlo"'), "method.kind",
     '"quadrature"', 'the string "monte-carlo"'),
    ("order_zero", ("order = 2", "order = 0"), "method.order", "an integer >= 1", "0"),
    ("regression_missing_samples", ('kind = "quadrature"', 'kind = "regression"\nq_norm = 1.0'
                                    '\nseed = 1'), "method.samples", "an integer >= 2",
     "nothing (the key is missing)"),
    ("q_norm_above_one", ('kind = "quadrature"', 'kind = "regression"\nq_norm = 1.5\n'
                          'samples = 10\nseed = 1'), "method.q_norm", "<= 1", "1.5"),
    ("q_norm_tiny", ('kind = "quadrature"', 'kind = "regression"\nq_norm = 1e-300\n'
                     'samples = 10\nseed = 1'), "method.q_norm", ">= 0.1", "1e-300"),
    ("seed_beyond_32_bits", ('kind = "quadrature"', 'kind = "regression"\nq_norm = 1.0\n'
                             'samples = 10\nseed = 99999999999999999999'), "method.seed",
     "<= 4294967295", "99999999999999999999"),
    ("uniform_bounds_overflow", ("lower = 1.25\nupper = 3.75", "lower = -1e308\nupper = 1e308"),
     "inputs[0]", "finite in double precision", "OpenTURNS refuses them"),
    ("gamma_shape_huge", ('distribution = "uniform"\nlower = 1.25\nupper = 3.75',
                          'distribution = "gamma"\nshape = 1e300\nrate = 1e-10\nlocation = 1.0'),
     "inputs[0]", "finite in double precision", "shape = 1e+300"),
    ("beta_exponents_tiny", ('distribution = "uniform"', 'distribution = "beta"\n'
                             'alpha = 1e-300\nbeta = 1e-300'), "inputs[0]",
     "finite in double precision", "alpha = 1e-300"),
    ("unknown_line", ('line = "chain"\nstatistic = "mean_cycle_max"',
                      'line = "rope"\nstatistic = "mean_cycle_max"'), "quantities[0].line",
     '"chain"', 'the string "rope"'),
    ("unknown_statistic", ('statistic = "mean_cycle_max"', 'statistic = "median"'),
     "quantities[0].statistic", '"mean_cycle_max"', 'the string "median"'),
    ("window_past_duration", ("window = [2.5, 3.75]", "window = [2.5, 20.0]"),
     "quantities[1].window", "end <= 3.75 s", "[2.5, 20.0]"),
    ("window_on_scalar", ('statistic = "mean_cycle_max"', 'statistic = "mean_cycle_max"\n'
                          'window = [0.0, 1.0]'), "quantities[0].window", "no window",
     "[0.0, 1.0]"),
    ("duplicate_quantity", ('name = "cycle"', 'name = "cycle_max"'), "quantities[1].name",
     "a name given once", "cycle_max"),
    ("dof_without_floater", ('line = "chain"\nstatistic = "mean_cycle_max"',
                             'dof = "Surge"\nstatistic = "max"'), "quantities[0].dof",
     "the case has no [floater]", 'the string "Surge"'),
]


def _write(tmp_path: Path, text: str, name: str = "study.toml") -> Path:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_good_study_loads(tmp_path):
    """The base of the bad studies is valid: each failure below is its one edit's."""
    study = load_study(_write(tmp_path, GOOD))
    assert study.keys == ("line_types.chain.normal_drag_coefficient",)
    assert [q.name for q in study.quantities] == ["cycle_max", "cycle"]
    assert study.quantities[1].window == (2.5, 3.75)


@pytest.mark.parametrize("edit, key, expected, found", [b[1:] for b in BAD],
                         ids=[b[0] for b in BAD])
def test_bad_study_names_file_key_expected_found(tmp_path, edit, key, expected, found):
    old, new = edit
    assert old in GOOD
    path = _write(tmp_path, GOOD.replace(old, new, 1))
    with pytest.raises(CaseError) as info:
        load_study(path)
    err = info.value
    assert err.source == str(path)
    assert err.key == key
    assert expected in err.expected
    assert found in err.found
    assert str(err).startswith(f"{path}: {key}: expected ")


@pytest.mark.parametrize("edit", [BAD[0][1], BAD[9][1], BAD[17][1]],
                         ids=["unknown_key", "key_not_in_case", "window"])
def test_cli_bad_study_exits_2_and_writes_nothing(tmp_path, capsys, edit):
    path = _write(tmp_path, GOOD.replace(*edit, 1))
    out = tmp_path / "out"
    status = main(["uq", str(path), "-o", str(out), "--quiet"])
    captured = capsys.readouterr()
    assert status == 2
    assert captured.out == ""
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"floatmoor: error: {path}: ")
    assert not out.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.toml"]


def test_mean_cycle_max_needs_periodic_motion(tmp_path):
    """The buoy moves in waves, not a prescribed periodic motion: the run summary gives no
    cycle maxima, so the study may not ask for them."""
    text = f"""
title = "buoy"
case = "{BUOY_CASE}"
[[inputs]]
key = "lines.line3.anchor.0"
distribution = "normal"
mean = 6.9175
std = 0.025
[method]
kind = "quadrature"
order = 1
[[quantities]]
name = "t3"
line = "line3"
statistic = "mean_cycle_max"
"""
    with pytest.raises(CaseError) as info:
        load_study(_write(tmp_path, text))
    assert info.value.key == "quantities[0].statistic"
    assert "periodic [motion]" in info.value.expected


def test_model_study_rules(tmp_path):
    """A built-in model study: inputs name model parameters, fixed ones sit in
    [parameters], and there are no [[quantities]]."""
    base = """
title = "string"
model = "taut_string"
[parameters]
t = 0.25
[[inputs]]
key = "T"
distribution = "uniform"
lower = 100.0
upper = 116.0
[method]
kind = "quadrature"
order = 2
"""
    assert load_study(_write(tmp_path, base)).quantities[0].kind == "model"
    cases = [
        (base.replace('key = "T"', 'key = "stiffness"'), "inputs[0].key",
         "a parameter of model taut_string"),
        (base.replace("t = 0.25", "t = 0.25\ncolour = 1.0"), "parameters.colour",
         "one of the known keys"),
        (base.replace("t = 0.25", "T = 108.0"), "parameters.T",
         "not also an uncertain input"),
        (base + '[[quantities]]\nname = "y"\nline = "a"\nstatistic = "max"\n', "quantities",
         "no [[quantities]] with a built-in model"),
    ]
    for text, key, expected in cases:
        with pytest.raises(CaseError) as info:
            load_study(_write(tmp_path, text))
        assert info.value.key == key, text
        assert expected in info.value.expected


def test_shipped_studies_load():
    """Every study file shipped in cases/uq is valid (their cases, keys and windows)."""
    paths = sorted((CASES / "uq").glob("*.toml"))
    assert len(paths) == 12
    for path in paths:
        study = load_study(path)
        assert study.quantities, path


def test_a_regression_basis_is_bounded_before_it_is_built(tmp_path):
    """Four inputs at order 20 ask for 10 626 candidate polynomials (more than
    MAX_BASIS_SIZE): refused at load, before any run, naming the order."""
    from floatmoor.uq.study import MAX_BASIS_SIZE

    keys = ["normal_drag_coefficient", "tangential_drag_coefficient", "added_mass_coefficient",
            "mass_per_length"]
    inputs = "".join(f'[[inputs]]\nkey = "line_types.chain.{k}"\ndistribution = "uniform"\n'
                     f"lower = 0.05\nupper = 0.1\n\n" for k in keys)
    text = GOOD.replace(GOOD[GOOD.index("[[inputs]]"):GOOD.index("[method]")], inputs)
    text = text.replace('kind = "quadrature"\norder = 2', 'kind = "regression"\norder = 20\n'
                        "q_norm = 1.0\nsamples = 100\nseed = 1")
    with pytest.raises(CaseError) as info:
        load_study(_write(tmp_path, text))
    assert info.value.key == "method.order"
    assert f"at most {MAX_BASIS_SIZE} basis polynomials" in info.value.expected
    study = load_study(_write(tmp_path, text.replace("q_norm = 1.0", "q_norm = 0.5")))
    assert study.method.q_norm == 0.5  # a hyperbolic basis keeps the same order within it


@pytest.mark.parametrize("dimension, order, q_norm", [(1, 5, 1.0), (2, 5, 1.0), (3, 7, 1.0),
                                                      (6, 20, 0.1), (4, 6, 0.4)])
def test_the_basis_count_matches_openturns(dimension, order, q_norm):
    import openturns as ot

    from floatmoor.uq.study import hyperbolic_basis_size

    size = ot.HyperbolicAnisotropicEnumerateFunction(dimension, q_norm)
    assert hyperbolic_basis_size(dimension, order, q_norm, 10_000) == \
        size.getBasisSizeFromTotalDegree(order)
    assert hyperbolic_basis_size(50, 20, 1.0, 100) == 101  # stops past the limit
