"""Uncertain inputs of a study: a named parameter and its probability distribution.

Each distribution is given by the parameters an engineer states (bounds, mean and standard
deviation, ...), checked here, and built as an OpenTURNS distribution; the joint distribution
of several inputs is their independent product (the gpc paper's inputs are all independent).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Mapping, Sequence

import openturns as ot

__all__ = ["UncertainInput", "DISTRIBUTIONS", "check_input", "marginal", "joint_distribution"]


@dataclass(frozen=True)
class UncertainInput:
    """A model parameter that is a random variable.

    Parameters
    ----------
    key
        The case's ``--set`` key path, or a built-in model's parameter name.
    distribution
        A key of :data:`DISTRIBUTIONS`.
    parameters
        The distribution's parameters by name (:data:`DISTRIBUTIONS` lists them), in the
        units of ``key``.
    """

    key: str
    distribution: str
    parameters: dict[str, float]


#: Distribution name -> its parameter names, in the order a loader may list them.
#:
#: - ``uniform``: ``lower`` < ``upper``;
#: - ``normal``: ``mean``, ``std`` > 0;
#: - ``lognormal``: ``mean`` > 0 and ``std`` > 0 of the variable itself (not of its log);
#: - ``truncated_normal``: ``mean``, ``std`` > 0 of the parent normal, cut to
#:   [``lower``, ``upper``];
#: - ``beta``: shape exponents ``alpha``, ``beta`` > 0 on [``lower``, ``upper``], density
#:   proportional to (x - lower)^(alpha - 1) (upper - x)^(beta - 1);
#: - ``triangular``: ``lower`` <= ``mode`` <= ``upper``, ``lower`` < ``upper``;
#: - ``gamma``: ``shape`` > 0, ``rate`` > 0 [1/units of key], ``location`` (the lower bound),
#:   density proportional to (x - location)^(shape - 1) exp(-rate (x - location)).
DISTRIBUTIONS: dict[str, tuple[str, ...]] = {
    "uniform": ("lower", "upper"),
    "normal": ("mean", "std"),
    "lognormal": ("mean", "std"),
    "truncated_normal": ("mean", "std", "lower", "upper"),
    "beta": ("alpha", "beta", "lower", "upper"),
    "triangular": ("lower", "mode", "upper"),
    "gamma": ("shape", "rate", "location"),
}


def _positive(*names: str) -> Callable[[Mapping[str, float]], str | None]:
    def rule(p: Mapping[str, float]) -> str | None:
        bad = [f"{n} = {p[n]!r}" for n in names if not p[n] > 0.0]
        return f"{', '.join(bad)}: must be > 0" if bad else None
    return rule


def _ordered(low: str, high: str) -> Callable[[Mapping[str, float]], str | None]:
    def rule(p: Mapping[str, float]) -> str | None:
        if p[low] < p[high]:
            return None
        return f"{low} = {p[low]!r} >= {high} = {p[high]!r}: must be {low} < {high}"
    return rule


def _mode_inside(p: Mapping[str, float]) -> str | None:
    if p["lower"] <= p["mode"] <= p["upper"]:
        return None
    return f"mode = {p['mode']!r} outside [lower, upper] = [{p['lower']!r}, {p['upper']!r}]"


_RULES: dict[str, tuple[Callable[[Mapping[str, float]], str | None], ...]] = {
    "uniform": (_ordered("lower", "upper"),),
    "normal": (_positive("std"),),
    "lognormal": (_positive("mean", "std"),),
    "truncated_normal": (_positive("std"), _ordered("lower", "upper")),
    "beta": (_positive("alpha", "beta"), _ordered("lower", "upper")),
    "triangular": (_ordered("lower", "upper"), _mode_inside),
    "gamma": (_positive("shape", "rate"),),
}


def check_input(inp: UncertainInput) -> None:
    """Check that ``inp`` names a known distribution with exactly its parameters, finite and
    physical.

    Parameters
    ----------
    inp
        The input to check.

    Raises
    ------
    ValueError
        Naming the input's key and the problem (unknown distribution, missing or unknown
        parameter, non-finite value, lower >= upper, std <= 0, ...).
    """
    where = f"uncertain input {inp.key!r} ({inp.distribution})"
    if inp.distribution not in DISTRIBUTIONS:
        raise ValueError(f"uncertain input {inp.key!r}: unknown distribution "
                         f"{inp.distribution!r}, expected one of {', '.join(DISTRIBUTIONS)}")
    names = DISTRIBUTIONS[inp.distribution]
    missing = [n for n in names if n not in inp.parameters]
    unknown = [n for n in inp.parameters if n not in names]
    if missing or unknown:
        raise ValueError(f"{where}: expected parameters {', '.join(names)}; "
                         + "; ".join(([f"missing {', '.join(missing)}"] if missing else [])
                                     + ([f"unknown {', '.join(unknown)}"] if unknown else [])))
    for name in names:
        value = inp.parameters[name]
        if isinstance(value, bool) or not isinstance(value, (int, float)) \
                or not math.isfinite(value):
            raise ValueError(f"{where}: {name} must be a finite number, found {value!r}")
    for rule in _RULES[inp.distribution]:
        problem = rule(inp.parameters)
        if problem:
            raise ValueError(f"{where}: {problem}")


def marginal(inp: UncertainInput) -> ot.Distribution:
    """The OpenTURNS distribution of one input (checked first, :func:`check_input`)."""
    check_input(inp)
    p = {k: float(v) for k, v in inp.parameters.items()}
    kind = inp.distribution
    if kind == "uniform":
        return ot.Uniform(p["lower"], p["upper"])
    if kind == "normal":
        return ot.Normal(p["mean"], p["std"])
    if kind == "lognormal":
        return ot.LogNormalMuSigma(p["mean"], p["std"], 0.0).getDistribution()
    if kind == "truncated_normal":
        return ot.TruncatedNormal(p["mean"], p["std"], p["lower"], p["upper"])
    if kind == "beta":
        return ot.Beta(p["alpha"], p["beta"], p["lower"], p["upper"])
    if kind == "triangular":
        return ot.Triangular(p["lower"], p["mode"], p["upper"])
    return ot.Gamma(p["shape"], p["rate"], p["location"])


def joint_distribution(inputs: Sequence[UncertainInput]) -> ot.Distribution:
    """The joint distribution of independent ``inputs``, in their order.

    Parameters
    ----------
    inputs
        The uncertain inputs.

    Returns
    -------
    openturns.Distribution
        Their independent joint distribution (dimension ``len(inputs)``).

    Raises
    ------
    ValueError
        When there is no input, a key repeats, or an input is invalid (:func:`check_input`).
    """
    if not inputs:
        raise ValueError("no uncertain input: a study needs at least one")
    keys = [inp.key for inp in inputs]
    repeated = sorted({k for k in keys if keys.count(k) > 1})
    if repeated:
        raise ValueError(f"uncertain input {', '.join(map(repr, repeated))} given more than once")
    return ot.JointDistribution([marginal(inp) for inp in inputs])
