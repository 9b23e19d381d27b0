"""The case file: its schema, the strict reader, ``--set`` overrides, loading and the
cross-checks of what it describes (docs/reference/case_file.md).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "load_case": "floatmoor.case.load",
    "parse_case": "floatmoor.case.load",
    "Case": "floatmoor.case.schema",
    "apply_overrides": "floatmoor.case.overrides",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
