"""Quick gPC study files of the Lindahl chain, shared by the uq tests and the cluster tests."""

from __future__ import annotations

__all__ = ["quick_study"]

#: Quadrature order 1 over two inputs (4 runs of 5 s on quasi-static lines); the chain
#: length range is the study's, so that studies side by side give different numbers.
_QUICK = """
title = "Lindahl chain on quasi-static lines, lengths {lower} to {upper} m"
case = "L.toml"
base_overrides = ['lines.chain.model="quasi-static"', "simulation.duration=5.0"]

[[inputs]]
key = "lines.chain.length"
distribution = "uniform"
lower = {lower}
upper = {upper}

[[inputs]]
key = "motion.radius"
distribution = "normal"
mean = 0.2
std = 0.01

[method]
kind = "quadrature"
order = 1

[[quantities]]
name = "tension_max"
line = "chain"
statistic = "max"

[[quantities]]
name = "tension"
line = "chain"
statistic = "history"
window = [2.5, 5.0]
"""


def quick_study(lower: float = 32.9, upper: float = 33.1) -> str:
    """The study file's text, the chain length uniform in [lower, upper] m."""
    return _QUICK.format(lower=lower, upper=upper)
