"""What an existing output file is, so that a command replaces only files of its own kind.

A netCDF file is told apart by its global attributes, read from its header alone (a run's
results, a hydrodynamic database, a campaign file, a study's results); a case file by its
text (:func:`case_file_content`). The commands name the kind they write with
:data:`RUN_RESULT_FILE`, :data:`HYDRO_DATABASE_FILE` or :data:`CASE_FILE`, passed as the
``kind`` of :func:`floatmoor.io.output_files.check_output_file`; the rule is on the
safeguards page (docs/guide/safeguards.md#output-files).
"""

from __future__ import annotations

import os
import tomllib
from collections.abc import Callable
from pathlib import Path

__all__ = ["netcdf_content", "case_file_content", "RUN_RESULT", "HYDRO_DATABASE",
           "RUN_RESULT_FILE", "HYDRO_DATABASE_FILE", "CASE_FILE", "CASE_TABLES",
           "CASE_REQUIRED", "MOORDYN_DECK", "moordyn_deck_content", "CHECKPOINT"]

#: What :func:`netcdf_content` calls a run's results and a hydrodynamic database.
RUN_RESULT = "a floatmoor run result"
HYDRO_DATABASE = "a floatmoor hydrodynamic database"

_NETCDF_MAGICS = (b"CDF\x01", b"CDF\x02", b"CDF\x05", b"\x89HDF\r\n\x1a\n")
_HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"


def _attributes(path: Path) -> dict | None:
    """Global attributes of a netCDF file (netCDF-3 header, or the root of a netCDF-4/HDF5
    file), or None when they cannot be read."""
    with open(path, "rb") as fh:
        head = fh.read(len(_HDF5_MAGIC))
    if head == _HDF5_MAGIC:
        try:
            import h5py
        except ImportError:  # pragma: no cover - h5py comes with the BEMIO importer
            return None
        try:
            with h5py.File(path, "r") as f:
                return {k: (v.decode("utf-8", "replace") if isinstance(v, bytes) else v)
                        for k, v in f.attrs.items()}
        except (OSError, ValueError):
            return None
    from floatmoor.io.netcdf3_format import NetCDF3Error
    from floatmoor.io.netcdf3_reader import read_attributes_netcdf3

    try:
        return read_attributes_netcdf3(path)
    except (NetCDF3Error, OSError, ValueError):
        return None


def netcdf_content(path: str | os.PathLike[str]) -> str:
    """What the netCDF file at ``path`` holds, as a message names it: :data:`RUN_RESULT`,
    :data:`HYDRO_DATABASE`, a campaign file, a study's results, or a netCDF file floatmoor
    did not write or cannot read."""
    attrs = _attributes(Path(path))
    if attrs is None:
        return "a netCDF file floatmoor cannot read (damaged or truncated)"
    if "floatmoor_version" not in attrs:
        return "a netCDF file floatmoor did not write"
    title = str(attrs.get("title", ""))
    if "database" in attrs and "inputs_hash" in attrs:
        return HYDRO_DATABASE
    if title == "floatmoor campaign":
        return "a floatmoor campaign file"
    if "study_toml" in attrs:
        return "the results of a floatmoor uq study"
    if title == "floatmoor polynomial-chaos surrogate":
        return "a floatmoor surrogate"
    if "case_toml" in attrs and "status" in attrs:
        return RUN_RESULT
    return "a floatmoor file of another kind"


def _is(content: str) -> Callable[[Path], str | None]:
    """The check of a netCDF output kind: None for a file holding ``content``."""
    def check(path: Path) -> str | None:
        found = netcdf_content(path)
        return None if found == content else found
    return check


#: The top-level keys a case file may hold (those :func:`floatmoor.case.load.parse_case`
#: reads), and those every case file holds.
CASE_TABLES = frozenset({
    "title", "description", "environment", "seabed", "line_types", "lines", "points",
    "motion", "simulation", "floater", "hydro", "waves", "wind", "initial", "campaign"})
CASE_REQUIRED = frozenset({"title", "environment", "simulation"})


def case_file_content(path: str | os.PathLike[str]) -> str | None:
    """None when ``path`` holds a floatmoor case file (UTF-8 TOML whose top-level keys are
    all among :data:`CASE_TABLES` and include :data:`CASE_REQUIRED`), else what it is, for
    the message. Its values are not checked: a case that no longer loads (an older version's,
    one being edited) is still a case file."""
    from floatmoor.case.limits import MAX_CASE_FILE_BYTES

    with open(path, "rb") as fh:
        data = fh.read(MAX_CASE_FILE_BYTES + 1)
    if len(data) > MAX_CASE_FILE_BYTES:
        return "which is larger than any case file"
    try:
        table = tomllib.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError):
        return "which is not a TOML file"
    keys = set(table)
    if not CASE_REQUIRED <= keys or keys - CASE_TABLES:
        return "a TOML file that is not a floatmoor case"
    return None


#: Largest MoorDyn input file examined: decks are text of a few kB (a hundred lines).
_MAX_DECK_BYTES = 10_000_000


def moordyn_deck_content(path: str | os.PathLike[str]) -> str | None:
    """None when ``path`` holds a MoorDyn input file (text with a ``---`` heading of line
    types: ``LINE TYPES`` of version 2, ``LINE DICTIONARY`` of version 1), else what it is."""
    import re

    with open(path, "rb") as fh:
        data = fh.read(_MAX_DECK_BYTES + 1)
    if len(data) > _MAX_DECK_BYTES:
        return "which is larger than any MoorDyn input file"
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:
        return "which is not a text file"
    if not re.search(r"^\s*-{3,}.*\b(LINE TYPES|LINE DICTIONARY)\b", text, re.M | re.I):
        return "a file that is not a MoorDyn input file"
    return None


#: ``kind`` of :func:`~floatmoor.io.output_files.check_output_file` for each output.
RUN_RESULT_FILE = ("run result", _NETCDF_MAGICS, _is(RUN_RESULT))
HYDRO_DATABASE_FILE = ("hydrodynamic database", _NETCDF_MAGICS, _is(HYDRO_DATABASE))
CASE_FILE = ("case file", (b"",), case_file_content)
MOORDYN_DECK = ("MoorDyn input file", (b"",), moordyn_deck_content)
#: A run's checkpoint (``OUT.nc.checkpoint``): a numpy ``.npz``, which is a zip.
CHECKPOINT = ("checkpoint", (b"PK\x03\x04",))
