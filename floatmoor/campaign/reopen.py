"""Reopening an existing campaign file to resume it: validated before any run is skipped or
its results taken over, and, to start over, moved aside rather than deleted
(docs/guide/safeguards.md#output-files).

A campaign file is resumed only when it is a regular file, a readable netCDF dataset that
floatmoor wrote as a campaign, of the same campaign (case text, base overrides, design), with
the variables, dimensions and shapes :class:`~floatmoor.campaign.store.CampaignStore` writes.
Anything else -- an empty, truncated or non-netCDF file, a run's output, another campaign, a
file whose variables do not fit the design -- is a :class:`CampaignFileError` naming the file
and what is wrong, and saying how to start over: ``floatmoor sweep --restart`` moves the file
aside to ``NAME.bak-N`` (:func:`move_aside`), never deleting it.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from floatmoor.campaign.design import CampaignDesign
from floatmoor.campaign.worker import BODY_STATISTICS, STRENGTH_STATISTICS, SUMMARY_STATISTICS
from floatmoor.errors import CaseError
from floatmoor.input_files import file_kind
from floatmoor.io.netcdf import NETCDF_ENGINE

__all__ = ["CampaignFileError", "read_campaign_file", "move_aside", "CAMPAIGN_TITLE",
           "START_OVER"]

#: The ``title`` attribute of every campaign file.
CAMPAIGN_TITLE = "floatmoor campaign"
#: How to start over, in every message about a campaign file that cannot be resumed.
START_OVER = ("to start over, re-run with --restart (floatmoor sweep), which moves the file "
              "aside to NAME.bak-N, or choose another output file")
#: The first bytes of a netCDF-3 file (classic or 64-bit offset), as campaign files are.
_NETCDF3_MAGIC = b"CDF"
#: Largest N tried by :func:`move_aside` (a folder with more backups wants tidying first).
_MAX_BACKUPS = 1000


class CampaignFileError(CaseError):
    """An existing campaign output file that cannot be resumed: bad input (exit 2)."""

    def __init__(self, path: str | os.PathLike[str], found: str) -> None:
        super().__init__(str(path), "", "the file of the same campaign, to resume it",
                         f"{found}; {START_OVER}")


def _dataset(path: Path) -> xr.Dataset:
    """The file read fully, after checking it is a non-empty regular file."""
    try:
        mode = os.stat(path).st_mode
    except OSError as err:
        raise CampaignFileError(path, f"a file that cannot be examined ({err.strerror or err})")
    if not stat.S_ISREG(mode):
        kind = file_kind(mode)
        raise CampaignFileError(path, kind)
    try:
        with open(path, "rb") as fh:
            head = fh.read(4)
    except OSError as err:
        raise CampaignFileError(path, f"a file that cannot be read ({err.strerror or err})")
    if not head:
        raise CampaignFileError(path, "an empty file")
    if not head.startswith(_NETCDF3_MAGIC):
        raise CampaignFileError(path, "a file that is not a readable netCDF dataset (no "
                                "netCDF-3 signature, which every campaign file has)")
    try:
        with xr.open_dataset(path, engine=NETCDF_ENGINE) as ds:
            return ds.load()
    except Exception as err:  # whatever a damaged file makes the reader raise
        detail = (str(err).strip().splitlines() or [""])[0].replace(str(path), "the file")
        raise CampaignFileError(path, "a file that is not a readable netCDF dataset (damaged "
                                f"or truncated: {type(err).__name__}: {detail})") from None


def _expect(ds: xr.Dataset, path: Path, name: str, dims: tuple[str, ...],
            shape: tuple[int, ...], kind: str = "f") -> None:
    """Variable ``name`` with ``dims`` and ``shape`` and dtype kind ``kind``."""
    if name not in ds.variables:
        raise CampaignFileError(path, f"a campaign file without the variable '{name}'")
    var = ds[name]
    text = kind == "U"  # netCDF-3 text reads back as str objects
    fits = var.dims == dims and var.shape == shape and (
        all(isinstance(v, str) for v in var.values.flat) if text else var.dtype.kind in kind)
    if not fits:
        raise CampaignFileError(path, f"a variable '{name}' of dimensions {var.dims}, shape "
                                f"{var.shape} and type {var.dtype} where this campaign has "
                                f"{dims}, {shape} and {'text' if text else 'numbers'}")


def read_campaign_file(path: str | os.PathLike[str], design: CampaignDesign,
                       identity: Mapping[str, str], lines: Sequence[str],
                       dofs: Sequence[str] = ()) -> xr.Dataset:
    """The campaign file ``path`` read fully, checked to be this campaign's.

    Parameters
    ----------
    path
        The existing output file.
    design, lines, dofs
        The campaign's axes, the case's line names and the floater's DOF names (empty for a
        case without a floater).
    identity
        The attributes that identify the campaign (case text, base overrides, design) and
        their values for this campaign.

    Raises
    ------
    CampaignFileError
        Naming the file, what is wrong with it and how to start over.
    """
    path = Path(path)
    ds = _dataset(path)
    title = ds.attrs.get("title")
    if title != CAMPAIGN_TITLE:
        raise CampaignFileError(path, "a netCDF file that is not a floatmoor campaign file "
                                f"(title {title!r}; a run's output?)")
    for key, wanted in identity.items():
        if ds.attrs.get(key) != wanted:
            what = key.replace("_", " ").replace("case toml", "case file text")
            raise CampaignFileError(path, f"another campaign: its {what} differs")
    dims = tuple(axis.name for axis in design.axes)
    shape = design.shape
    for axis in design.axes:
        for key in axis.keys:
            if key not in ds.coords or ds[key].dims != (axis.name,) or \
                    ds[key].size != len(axis):
                raise CampaignFileError(path, f"a campaign file whose coordinate '{key}' does "
                                        "not fit the design")
    if "line" not in ds.coords or [str(v) for v in ds["line"].values] != list(lines):
        raise CampaignFileError(path, "a campaign file whose lines are not the case's")
    _expect(ds, path, "status", dims, shape, kind="U")
    for name in ("compute_time_s", "wall_time_s"):
        _expect(ds, path, name, dims, shape)
    per_line = (dims + ("line",), shape + (len(lines),))
    for key in SUMMARY_STATISTICS:
        _expect(ds, path, f"fairlead_tension_{key}", *per_line)
    for key in STRENGTH_STATISTICS:  # absent from files written before they existed
        if key in ds.variables:
            _expect(ds, path, key, *per_line)
    if "run_file" in ds.variables:
        _expect(ds, path, "run_file", dims, shape, kind="U")
    body = bool(dofs) and "dof" in ds.coords and [str(d) for d in ds["dof"].values] == \
        list(dofs)
    if body:
        for key in BODY_STATISTICS:
            _expect(ds, path, f"body_displacement_{key}", dims + ("dof",),
                    shape + (len(dofs),))
    if "fairlead_tension" in ds.variables or ("body_displacement" in ds.variables and body):
        if "time" not in ds.coords or ds["time"].ndim != 1:
            raise CampaignFileError(path, "time series without a 'time' coordinate")
        n_time = ds.sizes["time"]
        if "fairlead_tension" in ds.variables:
            _expect(ds, path, "fairlead_tension", dims + ("line", "time"),
                    shape + (len(lines), n_time))
        if body and "body_displacement" in ds.variables:
            _expect(ds, path, "body_displacement", dims + ("time", "dof"),
                    shape + (n_time, len(dofs)))
    status = ds["status"].values.astype(str)
    unknown = sorted({s for s in status.flat if s not in ("complete", "pending")
                      and not s.startswith("failed")})
    if unknown:
        raise CampaignFileError(path, f"a run status {unknown[0]!r} (expected complete, "
                                "pending or failed: ...)")
    done = status == "complete"
    for name in ("compute_time_s", "wall_time_s"):
        if not np.all(np.isfinite(ds[name].values[done])):
            raise CampaignFileError(path, f"a complete run without its '{name}'")
    return ds


def move_aside(path: str | os.PathLike[str]) -> Path:
    """Rename ``path`` to the first free ``PATH.bak-N`` (N = 1, 2, ...) and return it; an
    existing backup is never replaced.

    Raises
    ------
    CaseError
        When no name is free or the file cannot be renamed (nothing moved).
    """
    path = Path(path)
    for n in range(1, _MAX_BACKUPS + 1):
        backup = path.with_name(f"{path.name}.bak-{n}")
        if os.path.lexists(backup):
            continue
        try:
            os.link(path, backup, follow_symlinks=False)  # fails if backup appeared meanwhile
        except FileExistsError:
            continue
        except OSError:  # a file system without hard links: rename (backup was free above)
            try:
                os.rename(path, backup)
            except OSError as err:
                raise CaseError("--restart", "", f"a file that can be moved aside to "
                                f"{backup}", f"{path}: {err.strerror or err}") from None
            return backup
        os.unlink(path)
        return backup
    raise CaseError("--restart", "", f"a free backup name {path.name}.bak-N up to "
                    f"N = {_MAX_BACKUPS}", "all taken")
