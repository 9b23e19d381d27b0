"""Connecting to a Dask distributed scheduler (``floatmoor sweep --scheduler ADDRESS``).

The address is checked before anything runs (a malformed one is bad input, status 2), and the
connection gives up after :data:`CONNECT_TIMEOUT` with a one-line error (a failure, status 1)
instead of Dask's 30 s wait and traceback.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

from floatmoor.errors import CaseError, FloatmoorError

if TYPE_CHECKING:
    from distributed import Client

__all__ = ["SchedulerError", "check_address", "connect", "CONNECT_TIMEOUT"]

#: Seconds to wait for the scheduler to answer. A scheduler on a cluster's network answers
#: in milliseconds; 5 s tolerates a busy one and still fails fast on a dead address.
CONNECT_TIMEOUT = 5.0
#: ``[protocol://]host:port``, as Dask accepts it (host a name, IPv4 or [IPv6]).
_ADDRESS = re.compile(r"(?:(?:tcp|tls|ucx|ws|wss)://)?(?:[A-Za-z0-9_.-]+|\[[0-9A-Fa-f:.]+\])"
                      r":\d{1,5}")


class SchedulerError(FloatmoorError):
    """The Dask scheduler cannot be reached."""


def check_address(address: str) -> None:
    """Raise :class:`CaseError` unless ``address`` reads as ``[tcp://]host:port``."""
    if not _ADDRESS.fullmatch(address) or not 0 < int(address.rsplit(":", 1)[1]) < 65536:
        raise CaseError("--scheduler", "", "a scheduler address such as tcp://host:8786",
                        f"'{address}'")


def connect(address: str) -> "Client":
    """A client of the scheduler at ``address``.

    Raises
    ------
    CaseError
        For a malformed address.
    SchedulerError
        When it does not answer within :data:`CONNECT_TIMEOUT`.
    """
    check_address(address)
    from distributed import Client

    try:
        return Client(address, timeout=CONNECT_TIMEOUT)
    except (OSError, TimeoutError, ValueError) as err:
        raise SchedulerError(f"cannot reach the Dask scheduler at {address} within "
                             f"{CONNECT_TIMEOUT:g} s ({err}); nothing was run") from None
