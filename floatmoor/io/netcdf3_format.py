"""The netCDF classic file format (CDF-1, and CDF-2: 64-bit offsets): its header, parsed and
written, and where each variable's data lies in the file.

From the public *NetCDF Classic Format Specification* (Unidata): a file is a header, the data
of the fixed-size variables, then the records. The header is the magic ``CDF`` and version
byte, ``numrecs`` (the number of records, a 4-byte big-endian integer at offset 4), then the
dimensions (a length of 0 marks the one record, i.e. unlimited, dimension), the global
attributes and the variables (name, dimension ids, attributes, type, ``vsize``, ``begin``).
All numbers are big-endian; names and attribute values are padded with zero bytes to a
multiple of 4. A record variable has the record dimension first; record ``i`` holds one slice
of every record variable, in header order, at ``begin + i * recsize``.

Only what floatmoor's own files use is supported: CDF-1 and CDF-2 (not CDF-5, nor the
"streaming" ``numrecs``), types byte to double. The module reads and writes headers only;
:mod:`floatmoor.io.netcdf_stream` writes data and :mod:`floatmoor.io.netcdf3_reader` reads it.
"""

from __future__ import annotations

import copy
import struct
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

__all__ = ["Attribute", "Variable", "Header", "parse_header", "read_header", "NetCDF3Error",
           "NUMRECS_OFFSET", "NC_CHAR", "NC_INT", "NC_DOUBLE", "DTYPES"]

_MAGIC = b"CDF"
_ABSENT = b"\x00" * 8
NC_DIMENSION, NC_VARIABLE, NC_ATTRIBUTE = 0x0A, 0x0B, 0x0C
NC_BYTE, NC_CHAR, NC_SHORT, NC_INT, NC_FLOAT, NC_DOUBLE = 1, 2, 3, 4, 5, 6
#: The on-disk (big-endian) dtype of each nc_type.
DTYPES: dict[int, np.dtype] = {NC_BYTE: np.dtype(">i1"), NC_CHAR: np.dtype("S1"),
                               NC_SHORT: np.dtype(">i2"), NC_INT: np.dtype(">i4"),
                               NC_FLOAT: np.dtype(">f4"), NC_DOUBLE: np.dtype(">f8")}
#: File offset of ``numrecs``: after the magic and the version byte.
NUMRECS_OFFSET = 4
#: Largest header read [bytes]: floatmoor's headers hold the case text (tens of kB); a
#: damaged length field may not make a reader allocate gigabytes.
MAX_HEADER_BYTES = 64 << 20


class NetCDF3Error(ValueError):
    """A file that is not a netCDF classic file floatmoor can read, or a header that cannot be
    written: the message says what is wrong."""


def _pad4(n: int) -> int:
    return -n % 4


@dataclass
class Attribute:
    """An attribute: its type and value bytes as stored (without the padding)."""

    name: str
    nc_type: int
    raw: bytes
    #: file offset of the value bytes (set when the header is parsed or written)
    offset: int = -1

    @property
    def nelems(self) -> int:
        """Number of values (characters for text)."""
        return len(self.raw) // DTYPES[self.nc_type].itemsize

    def value(self) -> bytes | np.generic | np.ndarray:
        """The value as scipy's netCDF reader gives it: text without trailing zero bytes,
        one number as a scalar, several as an array."""
        if self.nc_type == NC_CHAR:
            return self.raw.rstrip(b"\x00")
        values = np.frombuffer(self.raw, dtype=DTYPES[self.nc_type])
        values = values.astype(values.dtype.newbyteorder("="))
        return values[0] if values.shape == (1,) else values

    @classmethod
    def of(cls, name: str, value: str | bytes | float | int | np.ndarray,
           nc_type: int | None = None) -> "Attribute":
        """An attribute holding ``value`` (text as UTF-8; ``nc_type`` picks a number's type,
        default double for floats and int for integers)."""
        if isinstance(value, str):
            value = value.encode("utf-8")
        if isinstance(value, bytes):
            return cls(name, NC_CHAR, value)
        array = np.asarray(value).reshape(-1)
        if nc_type is None:
            nc_type = NC_DOUBLE if array.dtype.kind == "f" else NC_INT
        return cls(name, nc_type, array.astype(DTYPES[nc_type]).tobytes())


@dataclass
class Variable:
    """A variable's header entry."""

    name: str
    dim_ids: tuple[int, ...]
    attributes: list[Attribute]
    nc_type: int
    vsize: int
    begin: int

    def attribute(self, name: str) -> Attribute | None:
        return next((a for a in self.attributes if a.name == name), None)


@dataclass
class Header:
    """A netCDF classic header."""

    version: int  #: 1 (classic) or 2 (64-bit offset)
    numrecs: int
    dims: list[tuple[str, int]]  #: (name, length); length 0: the record dimension
    attributes: list[Attribute] = field(default_factory=list)
    variables: list[Variable] = field(default_factory=list)

    # -- structure ---------------------------------------------------------------------------
    @property
    def record_dim(self) -> int | None:
        """Index of the record dimension, None without one."""
        return next((i for i, (_, n) in enumerate(self.dims) if n == 0), None)

    def variable(self, name: str) -> Variable:
        for var in self.variables:
            if var.name == name:
                return var
        raise KeyError(name)

    def attribute(self, name: str) -> Attribute | None:
        return next((a for a in self.attributes if a.name == name), None)

    def is_record(self, var: Variable) -> bool:
        rec = self.record_dim
        return rec is not None and bool(var.dim_ids) and var.dim_ids[0] == rec

    def dim_names(self, var: Variable) -> tuple[str, ...]:
        return tuple(self.dims[i][0] for i in var.dim_ids)

    def fixed_shape(self, var: Variable) -> tuple[int, ...]:
        """Shape of the variable, or of one record of a record variable."""
        ids = var.dim_ids[1:] if self.is_record(var) else var.dim_ids
        return tuple(self.dims[i][1] for i in ids)

    def shape(self, var: Variable) -> tuple[int, ...]:
        """Shape of the variable, with ``numrecs`` records for a record variable."""
        fixed = self.fixed_shape(var)
        return (self.numrecs, *fixed) if self.is_record(var) else fixed

    def data_bytes(self, var: Variable) -> int:
        """Bytes of the variable's data (of one record for a record variable), unpadded."""
        return int(np.prod(self.fixed_shape(var), dtype=np.int64)) * DTYPES[var.nc_type].itemsize

    @property
    def record_variables(self) -> list[Variable]:
        return [v for v in self.variables if self.is_record(v)]

    @property
    def recsize(self) -> int:
        """Bytes per record: the record variables' vsizes (one record variable: unpadded)."""
        rec = self.record_variables
        if len(rec) == 1:
            return self.data_bytes(rec[0])
        return sum(v.vsize for v in rec)

    @property
    def record_begin(self) -> int:
        """File offset of the first record (the end of the data for a file without records)."""
        rec = self.record_variables
        if rec:
            return min(v.begin for v in rec)
        return max((v.begin + v.vsize for v in self.variables), default=self.size)

    @property
    def size(self) -> int:
        """Bytes of the header as :meth:`to_bytes` writes it."""
        return len(self.to_bytes())

    def lay_out(self) -> None:
        """Set every variable's ``vsize`` and ``begin``: the fixed-size variables right after
        the header, in header order, then the record variables (the header's size does not
        depend on these values, so one pass suffices)."""
        for var in self.variables:
            n = self.data_bytes(var)
            var.vsize = min(n + _pad4(n), 2**32 - 1)
        offset = self.size
        for var in self.variables:
            if not self.is_record(var):
                var.begin, offset = offset, offset + var.vsize
        for var in self.variables:
            if self.is_record(var):
                var.begin, offset = offset, offset + var.vsize

    def copy(self) -> "Header":
        return copy.deepcopy(self)

    # -- bytes -------------------------------------------------------------------------------
    def to_bytes(self) -> bytes:
        """The header as stored; sets every attribute's ``offset``."""
        out = bytearray()
        offset_fmt = ">i" if self.version == 1 else ">q"

        def put_int(n: int) -> None:
            out.extend(struct.pack(">i", n))

        def put_name(name: str) -> None:
            raw = name.encode("utf-8")
            put_int(len(raw))
            out.extend(raw + b"\x00" * _pad4(len(raw)))

        def put_attributes(attributes: list[Attribute]) -> None:
            if not attributes:
                out.extend(_ABSENT)
                return
            put_int(NC_ATTRIBUTE)
            put_int(len(attributes))
            for att in attributes:
                put_name(att.name)
                put_int(att.nc_type)
                put_int(att.nelems)
                att.offset = len(out)
                out.extend(att.raw + b"\x00" * _pad4(len(att.raw)))

        out.extend(_MAGIC + bytes([self.version]))
        put_int(self.numrecs)
        if self.dims:
            put_int(NC_DIMENSION)
            put_int(len(self.dims))
            for name, length in self.dims:
                put_name(name)
                put_int(length)
        else:
            out.extend(_ABSENT)
        put_attributes(self.attributes)
        if self.variables:
            put_int(NC_VARIABLE)
            put_int(len(self.variables))
            for var in self.variables:
                put_name(var.name)
                put_int(len(var.dim_ids))
                for i in var.dim_ids:
                    put_int(i)
                put_attributes(var.attributes)
                put_int(var.nc_type)
                put_int(var.vsize)
                out.extend(struct.pack(offset_fmt, var.begin))
        else:
            out.extend(_ABSENT)
        return bytes(out)


class _Truncated(Exception):
    """The header runs past the bytes read so far."""


class _Cursor:
    def __init__(self, data: bytes) -> None:
        self.data, self.pos = data, 0

    def take(self, n: int) -> bytes:
        if n < 0:
            raise NetCDF3Error(f"a negative length ({n}) in the header")
        end = self.pos + n
        if end > len(self.data):
            raise _Truncated
        out, self.pos = self.data[self.pos:end], end
        return out

    def int32(self) -> int:
        return struct.unpack(">i", self.take(4))[0]

    def count(self) -> int:
        n = self.int32()
        if n < 0:
            raise NetCDF3Error(f"a negative count ({n}) in the header")
        return n

    def name(self) -> str:
        n = self.count()
        raw = self.take(n)
        self.take(_pad4(n))
        try:
            return raw.decode("utf-8")
        except UnicodeDecodeError:
            raise NetCDF3Error(f"a name that is not UTF-8 ({raw[:40]!r})") from None

    def attributes(self) -> list[Attribute]:
        tag, n = self.int32(), self.count()
        if tag == 0 and n == 0:
            return []
        if tag != NC_ATTRIBUTE:
            raise NetCDF3Error(f"an attribute list tag {tag:#x}")
        out = []
        for _ in range(n):
            name = self.name()
            nc_type = self.int32()
            if nc_type not in DTYPES:
                raise NetCDF3Error(f"attribute '{name}' of unknown type {nc_type}")
            size = self.count() * DTYPES[nc_type].itemsize
            offset = self.pos
            raw = self.take(size)
            self.take(_pad4(size))
            out.append(Attribute(name, nc_type, raw, offset))
        return out


def parse_header(data: bytes) -> Header:
    """The header at the start of ``data``.

    Raises
    ------
    NetCDF3Error
        When ``data`` does not start with a netCDF classic header floatmoor reads (saying
        what is wrong), or ends inside it.
    """
    try:
        return _parse(data)
    except _Truncated:
        raise NetCDF3Error("a file that ends inside its header (truncated)") from None


def _parse(data: bytes) -> Header:
    cur = _Cursor(data)
    magic = cur.take(4)
    if magic[:3] != _MAGIC:
        raise NetCDF3Error("a file that does not start like a netCDF classic file")
    version = magic[3]
    if version not in (1, 2):
        raise NetCDF3Error(f"netCDF classic format version {version} (1 and 2 are read)")
    numrecs = cur.int32()
    if numrecs < 0:
        raise NetCDF3Error("a 'streaming' or negative record count")
    tag, n = cur.int32(), cur.count()
    dims: list[tuple[str, int]] = []
    if not (tag == 0 and n == 0):
        if tag != NC_DIMENSION:
            raise NetCDF3Error(f"a dimension list tag {tag:#x}")
        dims = [(cur.name(), cur.count()) for _ in range(n)]
    if sum(1 for _, length in dims if length == 0) > 1:
        raise NetCDF3Error("more than one record dimension")
    attributes = cur.attributes()
    tag, n = cur.int32(), cur.count()
    variables = []
    if not (tag == 0 and n == 0):
        if tag != NC_VARIABLE:
            raise NetCDF3Error(f"a variable list tag {tag:#x}")
        for _ in range(n):
            name = cur.name()
            ids = tuple(cur.count() for _ in range(cur.count()))
            if any(i >= len(dims) for i in ids):
                raise NetCDF3Error(f"variable '{name}' with an unknown dimension")
            atts = cur.attributes()
            nc_type = cur.int32()
            if nc_type not in DTYPES:
                raise NetCDF3Error(f"variable '{name}' of unknown type {nc_type}")
            vsize = struct.unpack(">I", cur.take(4))[0]
            begin = struct.unpack(">i" if version == 1 else ">q", cur.take(4 * version))[0]
            if begin < 0:
                raise NetCDF3Error(f"variable '{name}' at a negative offset")
            variables.append(Variable(name, ids, atts, nc_type, vsize, begin))
    header = Header(version, numrecs, dims, attributes, variables)
    for var in variables:
        if header.record_dim in var.dim_ids[1:]:
            raise NetCDF3Error(f"variable '{var.name}' with the record dimension not first")
    return header


def read_header(read: Callable[[int, int], bytes]) -> Header:
    """The header of a file, read with ``read(offset, size)`` (which returns fewer bytes at
    the end of the file) in growing pieces.

    Raises
    ------
    NetCDF3Error
        As :func:`parse_header`.
    """
    size = 1 << 16
    while True:
        data = read(0, size)
        try:
            return _parse(data)
        except _Truncated:
            if len(data) < size:
                raise NetCDF3Error("a file that ends inside its header (truncated or "
                                   "empty)") from None
            if size >= MAX_HEADER_BYTES:
                raise NetCDF3Error(f"a header larger than {MAX_HEADER_BYTES} bytes") from None
            size *= 4
