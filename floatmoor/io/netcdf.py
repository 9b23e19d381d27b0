"""Writing and reading result datasets as netCDF.

Files are netCDF-3 (64-bit offset) written with xarray's ``scipy`` engine, the one engine that
floatmoor's own dependencies provide, so every installation can read every file. Writes are
atomic: the dataset goes to a temporary file beside the target, which then replaces it, so a
reader (or an interrupted run) never sees a half-written file; the file is on disk before it
replaces the old one, which keeps its permissions, and a failed write (disk full, read-only
folder) leaves the old file and no temporary file behind. A run's results are not written
whole: they are appended as the run goes (:mod:`floatmoor.io.netcdf_stream`), ``time`` the
record dimension, and read back with :func:`open_result` (lazily) or :func:`read_dataset`,
which give their variables in the order of :func:`floatmoor.io.dataset.build_result_dataset`.
"""

from __future__ import annotations

import os

import xarray as xr

from floatmoor.io.dataset import BEFORE_TIME, result_order
from floatmoor.io.netcdf3_format import NetCDF3Error
from floatmoor.io.netcdf3_reader import open_netcdf3, read_attributes_netcdf3
from floatmoor.io.output_files import atomic_target

__all__ = ["write_dataset", "read_dataset", "open_result", "read_attributes", "NETCDF_ENGINE",
           "NETCDF_FORMAT"]

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
        # no record dimension, whatever the dataset's encoding says (a run's results read
        # from their file carry ``unlimited_dims={"time"}``, which netCDF-3 cannot store in
        # their in-memory order): a whole dataset is written whole
        dataset.to_netcdf(tmp, engine=NETCDF_ENGINE, format=NETCDF_FORMAT, unlimited_dims=())


def read_attributes(path: str | os.PathLike[str]) -> dict | None:
    """The global attributes of a netCDF file (only its header is read), or None when it is
    missing, unreadable or truncated.

    Parameters
    ----------
    path
        The netCDF file.

    Returns
    -------
    dict or None
        Attribute name -> value.
    """
    if not os.path.isfile(path):
        return None
    try:
        return read_attributes_netcdf3(path)
    except (NetCDF3Error, OSError):  # unreadable or truncated: the callers say so
        return None


def read_dataset(path: str | os.PathLike[str]) -> xr.Dataset:
    """Read a dataset fully into memory (the file is closed on return); a run's results
    with their variables in the order of
    :func:`~floatmoor.io.dataset.build_result_dataset` (:func:`~floatmoor.io.dataset.result_order`).

    Parameters
    ----------
    path
        The netCDF file.

    Returns
    -------
    xarray.Dataset
        The dataset, in memory.
    """
    with xr.open_dataset(path, engine=NETCDF_ENGINE) as ds:
        return result_order(ds.load())


def open_result(path: str | os.PathLike[str]) -> xr.Dataset:
    """A run's results read lazily: values are read from the file as they are asked for, in
    bounded memory (:mod:`floatmoor.io.netcdf3_reader`), so statistics of a long run's series
    need not hold the whole file; what is held is what is asked for, and the ``time``
    coordinate and its index (16 bytes per sample). The variables are in the order of
    :func:`~floatmoor.io.dataset.build_result_dataset`. The dataset holds the file open until
    it is closed or collected.

    Parameters
    ----------
    path
        A result file (netCDF classic, as :func:`write_dataset` writes it).

    Returns
    -------
    xarray.Dataset
        The lazily read dataset; close it (or use it in a ``with`` block) when done.

    Raises
    ------
    NetCDF3Error
        When the file is not a netCDF classic file, or is truncated.
    """
    return open_netcdf3(path, record_second=BEFORE_TIME)
