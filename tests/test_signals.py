"""floatmoor.signals outside a command: an interrupt during an atomic write or an append is
delivered after it, so the file is whole; SIGTERM inside a command is an interrupt with status 143."""

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

#: The tests count on Python's SIGINT handler (tests/conftest.py).
pytestmark = pytest.mark.usefixtures("python_sigint")


def test_interrupt_during_a_library_write_comes_after_it(tmp_path, monkeypatch):
    case = load_case(LINDAHL_CASE, ['lines.chain.model="quasi-static"',
                                    "simulation.duration=3.0"])
    out = tmp_path / "run.nc"
    rec = Recorder(case, output_times(case.simulation), out)
    rec.reserve(6)
    rec.advance(3)  # three (zero) samples
    stream = recorder_module.NetCDF3Stream
    real_create, real_append = stream.create.__func__, stream.append

    def create(cls, *args, **kwargs):
        os.kill(os.getpid(), signal.SIGINT)  # Python's own handler: KeyboardInterrupt
        return real_create(cls, *args, **kwargs)

    def append(self, records):
        os.kill(os.getpid(), signal.SIGINT)
        real_append(self, records)

    monkeypatch.setattr(stream, "create", classmethod(create))
    monkeypatch.setattr(stream, "append", append)
    with pytest.raises(KeyboardInterrupt):  # the file is created whole
        rec.write(status="running")
    written = read_dataset(out)
    assert written.attrs["status"] == "running" and written.sizes["time"] == 3
    rec.advance(5)
    with pytest.raises(KeyboardInterrupt):  # two samples are appended, the status updated
        rec.write(status="running on")
    written = read_dataset(out)
    assert written.attrs["status"] == "running on" and written.sizes["time"] == 5
    rec.close()
    assert not list(tmp_path.glob(".*.tmp"))


def test_sigterm_in_a_command_is_an_interrupt_with_status_143():
    with pytest.raises(KeyboardInterrupt) as caught, interrupt_handling():
        os.kill(os.getpid(), signal.SIGTERM)
        for _ in range(1000):  # the handler runs between bytecodes
            np.zeros(1)
    assert isinstance(caught.value, Terminated) and exit_status(caught.value) == 143
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL
