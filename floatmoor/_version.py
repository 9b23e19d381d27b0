"""The installed floatmoor version."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("floatmoor")
except PackageNotFoundError:  # pragma: no cover - running from a source tree that is not installed
    __version__ = "0+unknown"
