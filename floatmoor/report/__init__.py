"""Reports: ``floatmoor report`` and ``floatmoor compare``, figures, tables and Markdown of
one or more runs (docs/guide/reports.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "write_report": "floatmoor.report.build",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
