"""The moving-start generalisation of the DG kernels leaves a fixed-anchor line bit-identical.

``tests/data/dg_system/lindahl_baseline.npz`` was written by :func:`run` with the kernels as
they were before the start end could move (commit efa0522, the head of main before
mooring systems): regenerate it only from such a commit (``python -m tests.mooring.dg.test_dg_system_bits
FILE``). The Lindahl chain (docs/cases/lindahl.md) runs 0.5 s of harmonic fairlead motion with the
Kelvin-Voigt damping implicit and explicit.

Bit-identity holds on the processor that wrote the baseline: numba compiles for the host CPU,
and LLVM fuses multiply-adds where the CPU has FMA instructions, so another processor rounds
differently (on this project's 2026-11-26 machine: 1e-11 relative after the 0.5 s, 60 % of the
values differing in their last bits, at main's head before the implicit DG as after). Elsewhere the
comparison is to :data:`CPU_RTOL`.
"""

from __future__ import annotations

import sys

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from tests.conftest import CASES, REPO

BASELINE = REPO / "tests" / "data" / "dg_system" / "lindahl_baseline.npz"
#: Another CPU's rounding (FMA or not) grown over 0.5 s of steps: observed 1e-11 relative on
#: the largest value of each array; a change of the arithmetic (a term, a coefficient) moves
#: these arrays by far more than 1e-9.
CPU_RTOL = 1e-9
#: The relaxation of the baseline's code [1/s, s, s] (DynamicLine.settle before it ran on the
#: line's own time scale).
BASELINE_SETTLE_RATE, BASELINE_SETTLE_CHUNK, BASELINE_SETTLE_MAX_TIME = 20.0, 0.1, 20.0


def run(damping: str) -> dict[str, np.ndarray]:
    """End forces, laid length and final state of the Lindahl line over 0.5 s."""
    case = load_case(CASES / "lindahl" / "lindahl_r0.20_T1.25.toml",
                     ["lines.chain.dynamic.elements=12", "lines.chain.dynamic.order=5",
                      'lines.chain.dynamic.time_integration="explicit"',
                      f'lines.chain.dynamic.internal_damping="{damping}"',
                      "line_types.chain.internal_damping_ratio=0.05",
                      "lines.chain.dynamic.settle=false"])
    ln = case.lines[0]
    line = DynamicLine.from_case(ln, case.environment, case.seabed)
    # settled as the baseline's code did, on fixed times (20 1/s, 0.1 s chunks, 20 s at most),
    # not on the line's own time scale: what is compared is the kernels' arithmetic
    line.settle(rate=BASELINE_SETTLE_RATE, chunk=BASELINE_SETTLE_CHUNK,
                max_time=BASELINE_SETTLE_MAX_TIME)
    t = np.linspace(0.0, 0.5, 51)
    f0 = np.asarray(ln.fairlead)
    w = 2 * np.pi / 1.25
    path = f0 + 0.2 * np.outer(np.sin(w * t), [1.0, 0.0, 0.3])
    vel = 0.2 * w * np.outer(np.cos(w * t), [1.0, 0.0, 0.3])
    n = t.size
    ff, af, lb, st = np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n), np.zeros(n)
    line.solve_path(t, path, vel, ff, af, lb, st)
    return dict(fairlead_force=ff, anchor_force=af, laid=lb, r=line.r, v=line.v)


#: The explicit variant (6-12 s) is slow, for the default-run budget; the implicit one stays.
@pytest.mark.parametrize("damping", ["implicit", pytest.param("explicit", marks=pytest.mark.slow)])
def test_fixed_anchor_line_is_bit_identical_to_the_old_kernels(damping: str) -> None:
    base = np.load(BASELINE)
    out = run(damping)
    same_bits = all(value.tobytes() == base[f"{damping}_{key}"].tobytes()
                    for key, value in out.items())
    for key, value in out.items():
        ref = base[f"{damping}_{key}"]
        assert value.shape == ref.shape
        if not same_bits:  # another processor (see the module docstring)
            err = np.max(np.abs(value - ref)) / max(float(np.max(np.abs(ref))), 1e-300)
            assert err <= CPU_RTOL, (key, err)


if __name__ == "__main__":
    np.savez(sys.argv[1], **{f"{d}_{k}": a for d in ("implicit", "explicit")
                            for k, a in run(d).items()})
