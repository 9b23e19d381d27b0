"""Complex database values, stored split along a ``complex`` dimension (``re``, ``im``).

netCDF-3 holds no complex numbers, so a database (:mod:`floatmoor.hydro.database`) keeps them
split as capytaine's ``separate_complex_values`` does; this merges them back for the modules
that read a database, including its checks (:mod:`floatmoor.hydro.checks`), which the
database's loading runs in turn.
"""

from __future__ import annotations

import xarray as xr

__all__ = ["merge_complex"]


def merge_complex(ds: xr.Dataset, name: str) -> xr.DataArray:
    """Variable ``name`` with its ``complex`` dimension merged back into complex values."""
    da = ds[name]
    if "complex" not in da.dims:
        return da
    return da.sel(complex="re", drop=True) + 1j * da.sel(complex="im", drop=True)
