"""The coupled runs whose results ``[waves] second_order = "none"`` must leave bit for bit as
they were before second-order wave loads existed, and their reference
(tests/data/references/second_order_none.json, made with this module from commit bc646cc,
the code before them).

Write the reference (on the code to compare against, e.g. ``git checkout bc646cc --
floatmoor``, then ``git checkout HEAD -- floatmoor`` after; a few seconds)::

    PYTHONPATH=. python -m tests.simulation.second_order_reference --write "floatmoor/ of bc646cc"

The values are compared exactly: rounding depends on numba's and BLAS's builds, so a
reference made on another machine or with other builds of them must be made again there (from
the code before the change) before it can judge.
"""

from __future__ import annotations

import argparse
import json

import numpy as np

from floatmoor.case.load import load_case
from floatmoor.simulation.coupled_run import run_coupled
from tests.conftest import CASES, REPO

REFERENCE = REPO / "tests" / "data" / "references" / "second_order_none.json"
BUOY_CASE = CASES / "cylinder_buoy" / "buoy_regular_T1.20.toml"
SHORT = ['lines.*.model="quasi-static"', "simulation.duration=0.5",
         "simulation.output_interval=0.02", "simulation.time_step=0.01"]
#: The seas, as --set overrides of the buoy case.
SEAS = {
    "regular": 'waves={kind = "regular", height = 0.04, period = 1.2, ramp_duration = 0.3}',
    "jonswap": 'waves={kind = "jonswap", hs = 0.04, tp = 1.2, seed = 3, ramp_duration = 0.3}',
}
#: The recorded variables compared.
VARIABLES = ("body_equilibrium", "body_displacement", "body_velocity", "fairlead_tension")


def results(extra: list[str] | None = None) -> dict[str, dict[str, list]]:
    """The compared variables of each sea's run, as nested lists (floats round-trip through
    JSON exactly)."""
    out = {}
    for name, sea in SEAS.items():
        ds = run_coupled(load_case(BUOY_CASE, SHORT + [sea] + list(extra or []))).dataset
        out[name] = {v: ds[v].values.tolist() for v in VARIABLES}
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--write", metavar="PROVENANCE",
                        help="write the reference, saying which code made it")
    args = parser.parse_args()
    data = results()
    if args.write:
        REFERENCE.write_text(json.dumps({"provenance": f"tests/simulation/second_order_reference.py "
                                         f"--write: {args.write}", "runs": data}) + "\n")
    else:
        print({k: {v: np.asarray(a).shape for v, a in d.items()} for k, d in data.items()})


if __name__ == "__main__":
    main()
