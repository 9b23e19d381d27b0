"""Lazy reading of netCDF classic files in bounded memory, as xarray datasets.

xarray's ``scipy`` engine either maps the whole file into memory (every page a read touches
then counts in the process's resident memory, and reading one series of a record variable
touches every record) or reads every variable whole when the file is opened. This reader
reads only what is asked for, with positioned reads, the records in blocks of
:data:`BLOCK_BYTES`: one line's tension from an hour-long run's file costs the series itself
and one block. Decoding (text, fill values, coordinates) is xarray's own, as for the
``scipy`` engine, so the datasets are the same.
"""

from __future__ import annotations

import os
import stat
import weakref
from pathlib import Path

import numpy as np
import xarray as xr
from xarray.backends import (
    AbstractDataStore, BackendArray, BackendEntrypoint, StoreBackendEntrypoint,
)
from xarray.core import indexing

from floatmoor.io.netcdf3_format import DTYPES, NC_CHAR, Header, NetCDF3Error, Variable, read_header

__all__ = ["open_netcdf3", "read_attributes_netcdf3", "BLOCK_BYTES"]

#: Bytes of records read at a time.
BLOCK_BYTES = 4 << 20


class _File:
    """A file descriptor for reading, closed with :meth:`close` or when collected."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.fd = os.open(path, os.O_RDONLY | os.O_CLOEXEC)
        self._finalizer = weakref.finalize(self, os.close, self.fd)
        if not stat.S_ISREG(os.fstat(self.fd).st_mode):
            self.close()
            raise NetCDF3Error(f"{path} is not a regular file")

    def read(self, offset: int, size: int) -> bytes:
        parts, total = [], 0
        while total < size:
            chunk = os.pread(self.fd, size - total, offset + total)
            if not chunk:
                break
            parts.append(chunk)
            total += len(chunk)
        return b"".join(parts)

    def read_exactly(self, offset: int, size: int) -> bytes:
        data = self.read(offset, size)
        if len(data) != size:
            raise NetCDF3Error(f"{self.path} ends before its data (truncated)")
        return data

    def close(self) -> None:
        self._finalizer()


def _decode_attribute(value: bytes | np.generic | np.ndarray) -> object:
    """An attribute value as xarray's scipy store gives it (text decoded)."""
    return value.decode("utf-8", "replace") if isinstance(value, bytes) else value


class _Array(BackendArray):
    """One variable's data, read on demand (integers and slices; xarray does the rest)."""

    def __init__(self, file: _File, header: Header, var: Variable) -> None:
        self.file, self.header, self.var = file, header, var
        self.shape = header.shape(var)
        disk = DTYPES[var.nc_type]
        self.disk = disk
        self.dtype = disk if var.nc_type == NC_CHAR else disk.newbyteorder("=")

    def __getitem__(self, key: indexing.ExplicitIndexer) -> np.ndarray:
        return indexing.explicit_indexing_adapter(key, self.shape,
                                                  indexing.IndexingSupport.BASIC, self._get)

    def _get(self, key: tuple) -> np.ndarray:
        if not self.shape:
            data = self.file.read_exactly(self.var.begin, self.disk.itemsize)
            return np.frombuffer(data, dtype=self.disk).astype(self.dtype).reshape(())
        first, rest = key[0], key[1:]
        rows = np.arange(self.shape[0])[first]
        single = np.ndim(rows) == 0
        rows = np.atleast_1d(rows)
        if rows.size == 0:
            out = np.empty((0, *self.shape[1:]), dtype=self.dtype)
            return out[(slice(None), *rest)]
        if self.header.is_record(self.var):
            out = self._records(rows, rest)
        else:
            out = self._fixed(rows, rest)
        return out[0] if single else out

    def _fixed(self, rows: np.ndarray, rest: tuple) -> np.ndarray:
        """Rows of a fixed-size variable: the contiguous range that holds them."""
        row_items = int(np.prod(self.shape[1:], dtype=np.int64))
        lo, hi = int(rows.min()), int(rows.max()) + 1
        size = row_items * self.disk.itemsize
        data = self.file.read_exactly(self.var.begin + lo * size, (hi - lo) * size)
        block = np.frombuffer(data, dtype=self.disk).reshape((hi - lo, *self.shape[1:]))
        return block[rows - lo][(slice(None), *rest)].astype(self.dtype)

    def _records(self, rows: np.ndarray, rest: tuple) -> np.ndarray:
        """Rows of a record variable, read in blocks of whole records."""
        header = self.header
        recsize, start = header.recsize, header.record_begin
        field = np.dtype({"names": ["v"], "formats": [(self.disk, self.shape[1:])],
                          "offsets": [self.var.begin - start], "itemsize": recsize})
        per_block = max(1, BLOCK_BYTES // max(recsize, 1))
        order = np.argsort(rows, kind="stable")
        ascending = rows[order]
        parts = []
        for a in range(int(ascending[0]), int(ascending[-1]) + 1, per_block):
            b = a + per_block
            wanted = ascending[(ascending >= a) & (ascending < b)]
            if not wanted.size:
                continue
            b = int(wanted[-1]) + 1
            data = self.file.read_exactly(start + a * recsize, (b - a) * recsize)
            block = np.frombuffer(data, dtype=field)["v"]
            parts.append(block[wanted - a][(slice(None), *rest)].astype(self.dtype))
        out = np.concatenate(parts) if len(parts) > 1 else parts[0]
        result = np.empty_like(out)
        result[order] = out
        return result


class _Store(AbstractDataStore):
    """The variables and attributes of a netCDF classic file, for xarray's decoding."""

    def __init__(self, path: Path) -> None:
        self.file = _File(path)
        try:
            self.header = read_header(self.file.read)
            end = self.header.record_begin + self.header.numrecs * self.header.recsize
            if os.fstat(self.file.fd).st_size < end:
                raise NetCDF3Error(f"{path} is shorter than its {self.header.numrecs} "
                                   "records (truncated)")
        except BaseException:
            self.file.close()
            raise

    def get_variables(self) -> dict[str, xr.Variable]:
        header = self.header
        out = {}
        for var in header.variables:
            attrs = {a.name: (a.value() if a.name == "_FillValue"
                              else _decode_attribute(a.value())) for a in var.attributes}
            data = indexing.LazilyIndexedArray(_Array(self.file, header, var))
            out[var.name] = xr.Variable(header.dim_names(var), data, attrs)
        return out

    def get_attrs(self) -> dict[str, object]:
        return {a.name: _decode_attribute(a.value()) for a in self.header.attributes}

    def get_dimensions(self) -> dict[str, int]:
        return {name: (self.header.numrecs if length == 0 else length)
                for name, length in self.header.dims}

    def get_encoding(self) -> dict[str, object]:
        rec = self.header.record_dim
        return {"unlimited_dims": {self.header.dims[rec][0]} if rec is not None else set()}

    def close(self) -> None:
        self.file.close()


class _Entrypoint(BackendEntrypoint):
    """xarray's backend interface to :class:`_Store`, decoding as the ``scipy`` engine."""

    description = "floatmoor's lazy netCDF classic reader"
    open_dataset_parameters = ("filename_or_obj", "drop_variables", "mask_and_scale",
                               "decode_times", "concat_characters", "decode_coords",
                               "use_cftime", "decode_timedelta")

    def open_dataset(self, filename_or_obj, *, drop_variables=None, mask_and_scale=True,
                     decode_times=True, concat_characters=True, decode_coords=True,
                     use_cftime=None, decode_timedelta=None) -> xr.Dataset:
        store = _Store(Path(filename_or_obj))
        try:
            return StoreBackendEntrypoint().open_dataset(
                store, mask_and_scale=mask_and_scale, decode_times=decode_times,
                concat_characters=concat_characters, decode_coords=decode_coords,
                drop_variables=drop_variables, use_cftime=use_cftime,
                decode_timedelta=decode_timedelta)
        except BaseException:
            store.close()
            raise


def open_netcdf3(path: str | os.PathLike[str]) -> xr.Dataset:
    """Open a netCDF classic file lazily: values are read when asked for, in bounded memory.

    The dataset holds the file open until :meth:`xarray.Dataset.close` (or until it is
    collected); its variables, coordinates and attributes are those of
    ``xarray.open_dataset(path, engine="scipy")``.

    Raises
    ------
    NetCDF3Error
        When the file is not a netCDF classic file, or is truncated.
    OSError
        When it cannot be opened.
    """
    return xr.open_dataset(os.fspath(path), engine=_Entrypoint)


def read_attributes_netcdf3(path: str | os.PathLike[str]) -> dict[str, object]:
    """The global attributes of a netCDF classic file, from its header alone.

    Raises
    ------
    NetCDF3Error, OSError
        As :func:`open_netcdf3`.
    """
    store = _Store(Path(path))
    try:
        return store.get_attrs()
    finally:
        store.close()
