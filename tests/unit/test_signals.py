"""floatmoor.signals outside a command: an interrupt during an atomic write is delivered after
it, so the file is whole; SIGTERM inside a command is an interrupt with status 143."""

from __future__ import annotations

import os
import signal

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.io.netcdf import read_dataset
from floatmoor.signals import Terminated, exit_status, interrupt_handling
from floatmoor.simulation import recorder as recorder_module
from floatmoor.simulation.forced import output_times
from floatmoor.simulation.recorder import Recorder
from tests.conftest import LINDAHL_CASE


def test_interrupt_during_a_library_write_comes_after_it(tmp_path, monkeypatch):
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"',
                                    "simulation.duration=3.0"])
    out = tmp_path / "run.nc"
    rec = Recorder(case, output_times(case.simulation), out)
    rec.advance(3)  # three (zero) samples
    real_write = recorder_module.write_dataset

    def write(dataset, path):
        os.kill(os.getpid(), signal.SIGINT)  # Python's own handler: KeyboardInterrupt
        real_write(dataset, path)

    monkeypatch.setattr(recorder_module, "write_dataset", write)
    with pytest.raises(KeyboardInterrupt):
        rec.write(status="running")
    written = read_dataset(out)
    assert written.attrs["status"] == "running" and written.sizes["time"] == 3
    assert not list(tmp_path.glob(".*.tmp"))


def test_sigterm_in_a_command_is_an_interrupt_with_status_143():
    with pytest.raises(KeyboardInterrupt) as caught, interrupt_handling():
        os.kill(os.getpid(), signal.SIGTERM)
        for _ in range(1000):  # the handler runs between bytecodes
            np.zeros(1)
    assert isinstance(caught.value, Terminated) and exit_status(caught.value) == 143
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL
