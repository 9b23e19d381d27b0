"""Warnings raised during ``floatmoor run``: model-validity warnings are kept for the summary,
any other is shown once, as it is raised (a database's accepted failed checks, before the run).

The run's context (:func:`floatmoor.cli.run_case._validity_in_summary`) once re-showed the
other warnings while still recording them, so that each re-show was recorded again: the loop
never ended and the process ran out of memory. The check runs in a child process with a
bounded address space, so that such a loop fails the test instead of the machine.
"""

from __future__ import annotations

import os
import subprocess
import sys

from tests.conftest import REPO

#: Address space of the child [bytes]: the CLI's imports need about 0.3 GB; a runaway loop of
#: recorded warnings reaches this within seconds.
CHILD_MEMORY_LIMIT = 2 * 1024**3

_CHILD = f"""
import resource, warnings
resource.setrlimit(resource.RLIMIT_AS, ({CHILD_MEMORY_LIMIT}, {CHILD_MEMORY_LIMIT}))
from floatmoor.cli.run_case import _validity_in_summary
from floatmoor.errors import ModelValidityWarning
shown = []
with warnings.catch_warnings(record=True) as shown:
    warnings.simplefilter("always")
    with _validity_in_summary():
        warnings.warn(ModelValidityWarning("beyond linear hydrostatics"))
        warnings.warn(UserWarning("another warning"))
        during = [str(w.message) for w in shown]
print(during, [str(w.message) for w in shown])
"""


def test_a_run_shows_other_warnings_once_as_raised_and_keeps_validity_ones():
    result = subprocess.run([sys.executable, "-c", _CHILD], capture_output=True, text=True,
                            timeout=120, env={**os.environ, "PYTHONPATH": str(REPO)})
    assert result.returncode == 0, result.stderr[-2000:]
    assert result.stdout.strip() == "['another warning'] ['another warning']"
