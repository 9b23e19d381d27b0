"""Writing and reading result datasets as netCDF.

Files are netCDF-3 (64-bit offset) written with xarray's ``scipy`` engine, the one engine that
floatmoor's own dependencies provide, so every installation can read every file. Writes are
atomic: the dataset goes to a temporary file beside the target, which then replaces it, so a
reader (or an interrupted run) never sees a half-written file; the file is on disk before it
replaces the old one, which keeps its permissions, and a failed write (disk full, read-only
folder) leaves the old file and no temporary file behind.
"""

from __future__ import annotations

import os

import xarray as xr

from floatmoor.io.output_files import atomic_target

__all__ = ["write_dataset", "read_dataset", "read_attributes", "NETCDF_ENGINE", "NETCDF_FORMAT"]

NETCDF_ENGINE = "scipy"
NETCDF_FORMAT = "NETCDF3_64BIT"


def write_dataset(dataset: xr.Dataset, path: str | os.PathLike[str]) -> None:
    """Write ``dataset`` to ``path`` atomically.

    Parameters
    ----------
    dataset
        Real-valued dataset (netCDF-3 stores no complex numbers and no 64-bit integers).
    path
        Target file; its folder must exist. An existing file must be a regular file.

    Raises
    ------
    OutputWriteError
        When the write fails or ``path`` is not a regular file (the old file is kept).
    """
    with atomic_target(path) as tmp:
        dataset.to_netcdf(tmp, engine=NETCDF_ENGINE, format=NETCDF_FORMAT)


def read_attributes(path: str | os.PathLike[str]) -> dict | None:
    """The global attributes of a netCDF file (only they are read), or None when it is
    missing, unreadable or truncated."""
    if not os.path.isfile(path):
        return None
    try:
        with xr.open_dataset(path, engine=NETCDF_ENGINE) as ds:
            return dict(ds.attrs)
    except Exception:  # noqa: BLE001 - unreadable or truncated: the callers say so
        return None


def read_dataset(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read a result dataset fully into memory (the file is closed on return)."""
    with xr.open_dataset(path, engine=NETCDF_ENGINE) as ds:
        return ds.load()
