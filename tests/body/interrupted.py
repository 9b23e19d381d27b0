"""Interrupting a coupled run part-way, for the resume tests."""

from __future__ import annotations

from pathlib import Path

import pytest

from floatmoor.case.schema import Case
from floatmoor.simulation.coupled_run import run_coupled


def interrupt_run(case: Case, output: Path, after_chunks: int = 3) -> None:
    """Run ``case`` to ``output`` with a checkpoint at every chunk and stop it with a
    KeyboardInterrupt from the progress callback of chunk ``after_chunks``."""
    calls = {"n": 0}

    def stop(t: float) -> None:
        calls["n"] += 1
        if calls["n"] == after_chunks:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_coupled(case, output=output, checkpoint_interval=0.0, progress=stop)
