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


def stop_mid_step(case: Case, output: Path, monkeypatch: pytest.MonkeyPatch, calls: int,
                  error: BaseException) -> None:
    """Run ``case`` to ``output`` with the default (wall-clock) checkpoint interval and raise
    ``error`` from the ``calls``-th advance of a quasi-dynamic line: inside a body step, after
    some lines have advanced and before the others, the state the run must not checkpoint."""
    from floatmoor.mooring.quasidynamic import QuasiDynamicLine

    original = QuasiDynamicLine.solve_path
    count = {"n": 0}

    def advance(self, *args, **kwargs):
        count["n"] += 1
        if count["n"] == calls:
            raise error
        return original(self, *args, **kwargs)

    with monkeypatch.context() as patch:
        patch.setattr(QuasiDynamicLine, "solve_path", advance)
        with pytest.raises(type(error)):
            run_coupled(case, output=output)
    assert count["n"] == calls


def interrupt_at_body_step(patch: pytest.MonkeyPatch, step: int) -> None:
    """Make the ``step``-th body step of the coupled runs that follow raise a
    KeyboardInterrupt (Ctrl-C inside a run, as the CLI sees it)."""
    from floatmoor.simulation.coupled import MooredBody

    original, calls = MooredBody.step, []

    def stepped(self) -> None:
        calls.append(1)
        if len(calls) == step:
            raise KeyboardInterrupt
        original(self)

    patch.setattr(MooredBody, "step", stepped)
