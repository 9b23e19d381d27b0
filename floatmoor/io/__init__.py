"""Files: the variable table, result datasets and netCDF, other programs' BEM results
(WAMIT, BEMIO), line shapes for ParaView.
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "read_dataset": "floatmoor.io.netcdf",
    "write_dataset": "floatmoor.io.netcdf",
    "open_result": "floatmoor.io.netcdf",
    "read_attributes": "floatmoor.io.netcdf",
    "read_wamit": "floatmoor.io.wamit",
    "read_bemio": "floatmoor.io.bemio",
    "write_vtk_series": "floatmoor.io.vtk",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
