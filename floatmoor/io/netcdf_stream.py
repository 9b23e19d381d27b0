"""A netCDF classic (64-bit offset) file written as it grows: records appended, attributes
updated in place, every moment a valid file.

A run's results grow along the record (unlimited) dimension. :meth:`NetCDF3Stream.create`
writes the file once, atomically (:func:`floatmoor.io.output_files.atomic_target`: a reader
sees the old file or the new one, never a half-written one), from a *template*: netCDF bytes
written by xarray's own netCDF-3 writer, whose header (names, dimensions, types, attributes,
as xarray encodes them) and fixed-size data are kept, and whose records are the first ones.
Later writes go to the file in place, in an order that keeps it valid at every moment, so a
reader (``xarray.open_dataset(path, engine="scipy")``) may open it at any time, and a process
killed at any point (SIGKILL included) leaves a file holding every record appended before:

1. :meth:`~NetCDF3Stream.append` writes the new records *after* the last one, where no
   reader looks (readers read ``numrecs`` records), then flushes them to disk (``fsync``),
   and only then overwrites ``numrecs`` (4 bytes at offset 4, one write within a disk
   sector) with the new count. Killed before that write, the file has its old count and its
   old records; after it, the new ones. The fsync orders the two on disk too, so a power
   cut cannot leave a count that points past the data.
2. :meth:`~NetCDF3Stream.write_along` overwrites fixed-size data in place (a run's line
   shapes, whose whole extent is laid out at creation and filled with NaN, the fill value).
3. :meth:`~NetCDF3Stream.set_attributes` rewrites attribute values in place. A number keeps
   its size; a text attribute that changes (a run's ``status``) is created with room for
   ``reserve`` bytes, its value padded with zero bytes, which scipy's reader (and so
   xarray's ``scipy`` engine, floatmoor's) strips from text attributes and C readers take as
   the end of the string (a tool that prints every byte, ``ncdump``, shows them as ``\0``),
   so the header's lengths and every data offset stay as they are: a killed update leaves at
   worst a mix of the old and new text, never a broken header. A value longer than its room
   makes the stream rewrite the file with a larger header (through a temporary file that
   replaces it: the data are copied in pieces, so memory does not grow with the file).

Only record variables of plain numbers are appended (no packing, and for floats no fill
value other than NaN, so the values stored are the values given, as xarray would store
them); the stream refuses others when it is created or opened.
"""

from __future__ import annotations

import os
import stat
import struct
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from floatmoor.io.netcdf3_format import (
    DTYPES, NC_CHAR, NUMRECS_OFFSET, Attribute, Header, NetCDF3Error, Variable, parse_header,
    read_header,
)
from floatmoor.io.output_files import OutputWriteError, atomic_target, sync_folder

__all__ = ["NetCDF3Stream", "NetCDF3Error", "COPY_BLOCK_BYTES"]

#: Bytes copied or filled per write when laying out or rewriting a file: large enough for
#: few system calls, small enough to hold.
COPY_BLOCK_BYTES = 4 << 20

#: Attributes whose presence would make appended raw values differ from what xarray stores.
_PACKING = ("scale_factor", "add_offset", "valid_range", "valid_min", "valid_max")


def _write_all(fd: int, data: bytes | memoryview, offset: int) -> None:
    """``pwrite`` all of ``data`` at ``offset`` (a regular file may take it in pieces)."""
    view = memoryview(data).cast("B")
    while view.nbytes:
        n = os.pwrite(fd, view, offset)
        view, offset = view[n:], offset + n


def _read_at(fd: int, offset: int, size: int) -> bytes:
    """Up to ``size`` bytes at ``offset`` (fewer at the end of the file)."""
    parts, total = [], 0
    while total < size:
        chunk = os.pread(fd, size - total, offset + total)
        if not chunk:
            break
        parts.append(chunk)
        total += len(chunk)
    return b"".join(parts)


def _check_appendable(header: Header) -> None:
    """Refuse record variables whose values xarray would transform when storing them."""
    if header.record_dim is None:
        raise NetCDF3Error("a file without a record (unlimited) dimension")
    for var in header.record_variables:
        if var.nc_type == NC_CHAR:
            raise NetCDF3Error(f"record variable '{var.name}' of text, which is not appended")
        packed = [a.name for a in var.attributes if a.name in _PACKING]
        fill = var.attribute("_FillValue")
        if fill is not None and var.nc_type in (5, 6) and not np.isnan(fill.value()):
            packed.append("_FillValue (not NaN)")
        if packed:
            raise NetCDF3Error(f"record variable '{var.name}' with {', '.join(packed)}, "
                               "whose stored values are not the values given")


class NetCDF3Stream:
    """A netCDF classic file open for appending records and updating attributes.

    Use :meth:`create` for a new file, :meth:`open` to continue an existing one; close it
    with :meth:`close` (or a ``with`` block). Every method leaves the file valid (see the
    module notes); a failed write raises :class:`~floatmoor.io.output_files.OutputWriteError`
    naming the file.
    """

    def __init__(self, path: Path, fd: int, header: Header) -> None:
        self.path, self._fd, self.header = path, fd, header

    # -- opening -----------------------------------------------------------------------------
    @classmethod
    def create(cls, path: str | os.PathLike[str], template: bytes, *,
               sizes: Mapping[str, int] | None = None,
               values: Mapping[str, np.ndarray] | None = None,
               reserve: Mapping[str, int] | None = None,
               records: Mapping[str, np.ndarray] | None = None) -> "NetCDF3Stream":
        """Write a new file at ``path`` (atomically replacing any file there) from the netCDF
        classic bytes ``template`` and open it.

        Parameters
        ----------
        path
            The file; its folder must exist.
        template
            A netCDF classic file with a record dimension (as ``xarray.Dataset.to_netcdf()``
            gives it): its header, fixed-size data and records are written.
        sizes
            New lengths of fixed dimensions; the fixed-size variables along them are laid out
            at their new size and filled from ``values``, else with NaN (their template data
            are dropped).
        values
            Data of resized variables (the whole variable, in any byte order).
        reserve
            Bytes of room of text attributes that :meth:`set_attributes` will change.
        records
            More records, after the template's (as :meth:`append` takes them), written with
            them: the new file has all or, when the write fails, none of them.

        Raises
        ------
        NetCDF3Error
            When the template is not such a file, or a record variable cannot be appended.
        OutputWriteError
            When the write fails (nothing is left behind; an old file stays as it was).
        """
        path = Path(path)
        source = parse_header(template)
        _check_appendable(source)
        header = source.copy()
        resized = set()
        for name, length in (sizes or {}).items():
            index = next((i for i, (d, _) in enumerate(header.dims) if d == name), None)
            if index is None or index == header.record_dim or length < 1:
                raise NetCDF3Error(f"cannot resize dimension '{name}' to {length}")
            header.dims[index] = (name, int(length))
            resized.add(index)
        for name, room in (reserve or {}).items():
            att = header.attribute(name)
            if att is None or att.nc_type != NC_CHAR:
                raise NetCDF3Error(f"no text attribute '{name}' to reserve room for")
            att.raw = att.raw.ljust(room, b"\x00")
        header.lay_out()
        changed = {v.name for v in header.variables if set(v.dim_ids) & resized}
        if any(header.is_record(header.variable(n)) for n in changed):
            raise NetCDF3Error("a resized dimension of a record variable")
        extra = _encode_records(header, records) if records is not None else None
        if extra is not None:
            header.numrecs += extra.shape[0]
        with atomic_target(path) as tmp:
            with open(tmp, "r+b") as fh:
                fh.write(header.to_bytes())
                for var in header.variables:
                    if header.is_record(var):
                        continue
                    fh.seek(var.begin)
                    if var.name in changed:
                        _write_values(fh, header, var, (values or {}).get(var.name))
                    else:
                        old = source.variable(var.name)
                        fh.write(template[old.begin:old.begin + var.vsize])
                fh.seek(header.record_begin)
                fh.write(template[source.record_begin:
                                  source.record_begin + source.numrecs * source.recsize])
                if extra is not None:
                    fh.write(extra.view(np.uint8))
                fh.truncate(header.record_begin + header.numrecs * header.recsize)
        return cls._open_fd(path, header)

    @classmethod
    def open(cls, path: str | os.PathLike[str]) -> "NetCDF3Stream":
        """Open the existing file ``path`` to append to it.

        Raises
        ------
        NetCDF3Error
            When it is not a netCDF classic file with appendable records, or is shorter than
            its records.
        OutputWriteError
            When it cannot be opened for writing, or is not a regular file.
        """
        path = Path(path)
        try:
            fd = os.open(path, os.O_RDWR | os.O_CLOEXEC | os.O_NOFOLLOW)
        except OSError as err:
            raise OutputWriteError(f"cannot open {path}: {err.strerror or err}") from None
        try:
            if not stat.S_ISREG(os.fstat(fd).st_mode):
                raise OutputWriteError(f"cannot append to {path}: not a regular file")
            header = read_header(lambda offset, size: _read_at(fd, offset, size))
            _check_appendable(header)
            end = header.record_begin + header.numrecs * header.recsize
            if os.fstat(fd).st_size < end:
                raise NetCDF3Error(f"a file shorter than its {header.numrecs} records "
                                   "(truncated)")
            return cls(path, fd, header)
        except BaseException:
            os.close(fd)
            raise

    @classmethod
    def _open_fd(cls, path: Path, header: Header) -> "NetCDF3Stream":
        try:
            fd = os.open(path, os.O_RDWR | os.O_CLOEXEC | os.O_NOFOLLOW)
        except OSError as err:
            raise OutputWriteError(f"cannot write {path}: {err.strerror or err}") from None
        return cls(path, fd, header)

    # -- writing -----------------------------------------------------------------------------
    @property
    def numrecs(self) -> int:
        """Records in the file."""
        return self.header.numrecs

    def _fail(self, err: OSError) -> OutputWriteError:
        return OutputWriteError(f"cannot write {self.path}: {err.strerror or err}")

    def append(self, records: Mapping[str, np.ndarray]) -> None:
        """Append records: every record variable's values, the record dimension first (the
        same number of records for all).

        Raises
        ------
        ValueError
            When a record variable is missing or misshapen, or its values do not fit its
            type without loss (the file is unchanged).
        OutputWriteError
            When the write fails (the file keeps its previous records).
        """
        header = self.header
        block = _encode_records(header, records)
        n = block.shape[0]
        if n == 0:
            return
        end = header.record_begin + header.numrecs * header.recsize
        try:
            _write_all(self._fd, block.view(np.uint8), end)
            os.fsync(self._fd)  # the records are on disk before the count that covers them
            _write_all(self._fd, struct.pack(">i", header.numrecs + n), NUMRECS_OFFSET)
        except OSError as err:
            raise self._fail(err) from err
        header.numrecs += n

    def truncate(self, numrecs: int) -> None:
        """Keep the first ``numrecs`` records only: the count first, then the file's end."""
        header = self.header
        if not 0 <= numrecs <= header.numrecs:
            raise ValueError(f"cannot keep {numrecs} of {header.numrecs} records")
        try:
            _write_all(self._fd, struct.pack(">i", numrecs), NUMRECS_OFFSET)
            os.fsync(self._fd)
            os.ftruncate(self._fd, header.record_begin + numrecs * header.recsize)
        except OSError as err:
            raise self._fail(err) from err
        header.numrecs = numrecs

    def sync(self) -> None:
        """Flush the file (its records, count and attributes) and its folder's entry to
        disk: after it, a power cut leaves the file as it is now (what a checkpoint that
        counts its records needs: ``floatmoor.simulation.checkpoint``).

        Raises
        ------
        OutputWriteError
            When the flush fails.
        """
        try:
            os.fsync(self._fd)
            sync_folder(self.path.parent)
        except OSError as err:
            raise self._fail(err) from err

    def write_along(self, name: str, dim: str, start: int, values: np.ndarray) -> None:
        """Overwrite fixed-size variable ``name`` at indices ``start ...`` of its dimension
        ``dim`` with ``values`` (shaped as the variable, with that many entries along
        ``dim``).

        Raises
        ------
        ValueError
            For a record variable, a dimension it does not have, or values of another shape.
        OutputWriteError
            When the write fails.
        """
        header = self.header
        var = header.variable(name)
        dims = header.dim_names(var)
        if header.is_record(var) or dim not in dims:
            raise ValueError(f"'{name}' is not a fixed-size variable along '{dim}'")
        axis = dims.index(dim)
        shape = header.shape(var)
        data = np.asarray(values).astype(DTYPES[var.nc_type], casting="safe")
        count = data.shape[axis] if data.ndim == len(shape) else -1
        want = shape[:axis] + (count,) + shape[axis + 1:]
        if data.shape != want or start < 0 or start + count > shape[axis]:
            raise ValueError(f"'{name}': values of shape {data.shape} at {dim} = {start} in a "
                             f"variable of shape {shape}")
        outer = int(np.prod(shape[:axis], dtype=np.int64))
        inner = int(np.prod(shape[axis + 1:], dtype=np.int64)) * data.itemsize
        rows = data.reshape(outer, count * inner // data.itemsize)
        try:
            for k in range(outer):
                offset = var.begin + (k * shape[axis] + start) * inner
                _write_all(self._fd, np.ascontiguousarray(rows[k]).tobytes(), offset)
        except OSError as err:
            raise self._fail(err) from err

    def set_attributes(self, attributes: Mapping[str, str | float | int]) -> None:
        """Change global attributes in place (numbers of the same count; text within its
        room, padded with zero bytes, or after rewriting the file with more room).

        Raises
        ------
        KeyError
            For an attribute the file does not have.
        ValueError
            For a number where the file has text or several values, or text for a number.
        OutputWriteError
            When the write fails.
        """
        header = self.header
        longer: dict[str, bytes] = {}
        updates: list[tuple[Attribute, bytes]] = []
        for name, value in attributes.items():
            att = header.attribute(name)
            if att is None:
                raise KeyError(f"no global attribute '{name}' in {self.path}")
            if att.nc_type == NC_CHAR:
                if not isinstance(value, str):
                    raise ValueError(f"attribute '{name}' holds text, not {value!r}")
                raw = value.encode("utf-8")
                if len(raw) > len(att.raw):
                    longer[name] = raw
                else:
                    updates.append((att, raw.ljust(len(att.raw), b"\x00")))
            else:
                if isinstance(value, str) or att.nelems != 1:
                    raise ValueError(f"attribute '{name}' holds {att.nelems} number(s), not "
                                     f"{value!r}")
                raw = np.asarray([value]).astype(DTYPES[att.nc_type]).tobytes()
                updates.append((att, raw))
        try:
            for att, raw in updates:
                _write_all(self._fd, raw, att.offset)
                att.raw = raw
        except OSError as err:
            raise self._fail(err) from err
        if longer:
            self._rewrite(longer)

    def _rewrite(self, text: Mapping[str, bytes]) -> None:
        """Rewrite the file with the text attributes ``text`` given twice their length of
        room: a new header, then the data copied in pieces, through a temporary file that
        replaces this one."""
        old = self.header
        header = old.copy()
        for name, raw in text.items():
            att = header.attribute(name)
            att.raw = raw.ljust(2 * len(raw), b"\x00")
        old_start = min((v.begin for v in old.variables), default=old.size)
        shift = header.size - old_start
        shift += -shift % 4
        for var in header.variables:
            var.begin += shift
        end = old.record_begin + old.numrecs * old.recsize
        with atomic_target(self.path) as tmp:
            with open(tmp, "r+b") as fh:
                fh.write(header.to_bytes())
                fh.seek(old_start + shift)
                offset = old_start
                while offset < end:
                    chunk = _read_at(self._fd, offset, min(COPY_BLOCK_BYTES, end - offset))
                    if not chunk:
                        raise OutputWriteError(f"cannot rewrite {self.path}: it ends early")
                    fh.write(chunk)
                    offset += len(chunk)
        os.close(self._fd)
        self._fd = -1
        reopened = self._open_fd(self.path, header)
        self._fd, self.header = reopened._fd, header
        reopened._fd = -1

    def close(self) -> None:
        """Flush the file to disk and close it (again: nothing)."""
        if self._fd < 0:
            return
        fd, self._fd = self._fd, -1
        try:
            os.fsync(fd)
        except OSError as err:
            raise self._fail(err) from err
        finally:
            os.close(fd)

    def __enter__(self) -> "NetCDF3Stream":
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __del__(self) -> None:
        if getattr(self, "_fd", -1) >= 0:
            os.close(self._fd)


def _records_dtype(header: Header) -> np.dtype:
    """One record as a structured dtype: every record variable at its offset."""
    start = header.record_begin
    names, formats, offsets = [], [], []
    for var in header.record_variables:
        names.append(var.name)
        formats.append((DTYPES[var.nc_type], header.fixed_shape(var)))
        offsets.append(var.begin - start)
    return np.dtype({"names": names, "formats": formats, "offsets": offsets,
                     "itemsize": header.recsize})


def _encode_records(header: Header, records: Mapping[str, np.ndarray]) -> np.ndarray:
    """Records as stored: a structured array of every record variable's values (the record
    dimension first), converted to the stored types without loss.

    Raises
    ------
    ValueError
        When a record variable is missing or misshapen, or the variables' lengths differ.
    TypeError
        When values do not fit a variable's type without loss.
    """
    missing = [v.name for v in header.record_variables if v.name not in records]
    if missing:
        raise ValueError(f"no values for the record variables {missing}")
    lengths = {np.shape(records[v.name])[0] for v in header.record_variables}
    if len(lengths) != 1:
        raise ValueError(f"record variables of different lengths {sorted(lengths)}")
    n = lengths.pop()
    block = np.zeros(n, dtype=_records_dtype(header))
    for var in header.record_variables:
        data = np.asarray(records[var.name])
        want = (n, *header.fixed_shape(var))
        if data.shape != want:
            raise ValueError(f"record variable '{var.name}': shape {data.shape}, "
                             f"expected {want}")
        block[var.name] = data.astype(DTYPES[var.nc_type], casting="safe")
    return block


def _write_values(fh, header: Header, var: Variable, values: np.ndarray | None) -> None:
    """Write a fixed-size variable's data at the file position: ``values``, or NaN (the
    fill value of floats) in pieces; then its padding."""
    size = header.data_bytes(var)
    dtype = DTYPES[var.nc_type]
    if values is not None:
        data = np.asarray(values).astype(dtype, casting="safe")
        if data.shape != header.shape(var):
            raise NetCDF3Error(f"values of '{var.name}' of shape {data.shape}, expected "
                               f"{header.shape(var)}")
        fh.write(data.tobytes())
    else:
        if dtype.kind != "f":
            raise NetCDF3Error(f"no values for the resized non-float variable '{var.name}'")
        block = np.full(max(1, COPY_BLOCK_BYTES // dtype.itemsize), np.nan, dtype=dtype)
        left = size // dtype.itemsize
        while left:
            n = min(left, block.size)
            fh.write(block[:n].tobytes())
            left -= n
    fh.write(b"\x00" * (var.vsize - size))
