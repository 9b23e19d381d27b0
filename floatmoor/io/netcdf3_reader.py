"""Lazy reading of netCDF classic files in bounded memory, as xarray datasets.

xarray's ``scipy`` engine either maps the whole file into memory (every page a read touches
then counts in the process's resident memory, and reading one series of a record variable
touches every record) or reads every variable whole when the file is opened. This reader
reads only what is asked for, with positioned reads, the records in blocks of
:data:`BLOCK_BYTES` into one buffer: one line's tension from an hour-long run's file costs the
series itself and one block. Decoding (text, fill values, coordinates) is xarray's own, as for the
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

#: Bytes read at a time (records of a record variable, rows of another).
BLOCK_BYTES = 1 << 20


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

    def read_into(self, buffer: np.ndarray, offset: int) -> None:
        """Fill the byte array ``buffer`` from ``offset``."""
        view = memoryview(buffer).cast("B")
        while view.nbytes:
            n = os.preadv(self.fd, [view], offset)
            if n <= 0:
                raise NetCDF3Error(f"{self.path} ends before its data (truncated)")
            view, offset = view[n:], offset + n

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
    """One variable's data, read on demand (integers and slices; xarray does the rest).

    Rows (along the first dimension) are read in blocks of at most :data:`BLOCK_BYTES` into
    one reused buffer and copied into the result, so reading a series costs the series and
    a block, however long the file."""

    def __init__(self, file: _File, header: Header, var: Variable, swap: bool = False) -> None:
        self.file, self.header, self.var = file, header, var
        #: whether the first two dimensions are presented swapped (see :func:`open_netcdf3`)
        self.swap = swap
        self.file_shape = header.shape(var)
        shape = self.file_shape
        self.shape = (shape[1], shape[0], *shape[2:]) if swap else shape
        disk = DTYPES[var.nc_type]
        self.disk = disk
        self.dtype = disk if var.nc_type == NC_CHAR else disk.newbyteorder("=")
        if header.is_record(var):  # a row is a whole record, of which this is a field
            self.row_bytes = header.recsize
            self.row_dtype = np.dtype({"names": ["v"], "formats": [(disk, shape[1:])],
                                       "offsets": [var.begin - header.record_begin],
                                       "itemsize": header.recsize})
            self.start = header.record_begin
        else:
            self.row_bytes = int(np.prod(shape[1:], dtype=np.int64)) * disk.itemsize
            self.row_dtype = np.dtype({"names": ["v"], "formats": [(disk, shape[1:])]})
            self.start = var.begin

    def __getitem__(self, key: indexing.ExplicitIndexer) -> np.ndarray:
        return indexing.explicit_indexing_adapter(key, self.shape,
                                                  indexing.IndexingSupport.BASIC, self._get)

    def _get(self, key: tuple) -> np.ndarray:
        if not self.shape:
            data = self.file.read_exactly(self.var.begin, self.disk.itemsize)
            return np.frombuffer(data, dtype=self.disk).astype(self.dtype).reshape(())
        if self.swap:
            out = self._get_file((key[1], key[0], *key[2:]))
            both = isinstance(key[0], slice) and isinstance(key[1], slice)
            return out.swapaxes(0, 1) if both else out
        return self._get_file(key)

    def _get_file(self, key: tuple) -> np.ndarray:
        """``key`` in the file's order of dimensions."""
        first, rest = key[0], key[1:]
        n = self.file_shape[0]
        if isinstance(first, slice):
            return self._rows(range(*first.indices(n)), rest)
        index = int(first) + n if int(first) < 0 else int(first)
        if not 0 <= index < n:
            raise IndexError(f"index {int(first)} out of range for {n} rows")
        return self._rows(range(index, index + 1), rest)[0]

    def _rows(self, rows: range, rest: tuple) -> np.ndarray:
        """Rows ``rows`` of the variable, indexed by ``rest`` along its other dimensions."""
        probe = np.empty((1, *self.file_shape[1:]), dtype=self.dtype)[(slice(None), *rest)]
        out = np.empty((len(rows), *probe.shape[1:]), dtype=self.dtype)
        if not len(rows):
            return out
        if rows.step < 0:  # read them in increasing order
            out[::-1] = self._rows(rows[::-1], rest)
            return out
        step = rows.step
        per_block = max(1, BLOCK_BYTES // max(self.row_bytes, 1))
        per_read = min(len(rows), (per_block - 1) // step + 1)  # wanted rows per read
        buffer = np.empty(((per_read - 1) * step + 1) * self.row_bytes, dtype=np.uint8)
        done = 0
        while done < len(rows):
            k = min(per_read, len(rows) - done)
            span = (k - 1) * step + 1  # rows read, of which every step-th is wanted
            view = buffer[:span * self.row_bytes]
            self.file.read_into(view, self.start + rows[done] * self.row_bytes)
            block = view.view(self.row_dtype)["v"]
            out[done:done + k] = block[::step][(slice(None), *rest)]
            done += k
        return out


class _Store(AbstractDataStore):
    """The variables and attributes of a netCDF classic file, for xarray's decoding."""

    def __init__(self, path: Path, record_second: tuple[str, ...] = ()) -> None:
        self.record_second = record_second
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
            dims = header.dim_names(var)
            swap = (header.is_record(var) and len(dims) >= 2
                    and dims[1] in self.record_second)
            if swap:
                dims = (dims[1], dims[0], *dims[2:])
            data = indexing.LazilyIndexedArray(_Array(self.file, header, var, swap))
            out[var.name] = xr.Variable(dims, data, attrs)
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
                               "use_cftime", "decode_timedelta", "record_second")

    def open_dataset(self, filename_or_obj, *, drop_variables=None, mask_and_scale=True,
                     decode_times=True, concat_characters=True, decode_coords=True,
                     use_cftime=None, decode_timedelta=None,
                     record_second: tuple[str, ...] = ()) -> xr.Dataset:
        store = _Store(Path(filename_or_obj), tuple(record_second))
        try:
            return StoreBackendEntrypoint().open_dataset(
                store, mask_and_scale=mask_and_scale, decode_times=decode_times,
                concat_characters=concat_characters, decode_coords=decode_coords,
                drop_variables=drop_variables, use_cftime=use_cftime,
                decode_timedelta=decode_timedelta)
        except BaseException:
            store.close()
            raise


def open_netcdf3(path: str | os.PathLike[str], record_second: tuple[str, ...] = ()
                 ) -> xr.Dataset:
    """Open a netCDF classic file lazily: values are read when asked for, in bounded memory.

    The dataset holds the file open until :meth:`xarray.Dataset.close` (or until it is
    collected); its variables, coordinates and attributes are those of
    ``xarray.open_dataset(path, engine="scipy")``, but that a record variable whose second
    dimension is in ``record_second`` has its first two dimensions swapped (read lazily as
    such: transposing a lazily read variable in xarray makes later selections read all of
    it).

    Raises
    ------
    NetCDF3Error
        When the file is not a netCDF classic file, or is truncated.
    OSError
        When it cannot be opened.
    """
    return xr.open_dataset(os.fspath(path), engine=_Entrypoint,
                           backend_kwargs={"record_second": tuple(record_second)})


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
