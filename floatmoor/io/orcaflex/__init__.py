"""OrcaFlex text data files (``.yml``, OrcaFlex 9.8 and later): a strict, safe YAML reader and
the mapping of the mooring part of a model to a floatmoor case (``floatmoor import orcaflex``).

Modules: :mod:`.reader` (file -> plain data, aliases, anchors and merge keys refused, sizes
bounded), :mod:`.values` (numbers, units and key paths for messages), :mod:`.importer` (model
-> case file text, checked by the case loader before anything is written); the command is
:mod:`floatmoor.cli.orcaflex`.
The mapping is documented in docs/guide/mooring_systems.md#orcaflex-models.
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "read_model": "floatmoor.io.orcaflex.reader",
    "import_model": "floatmoor.io.orcaflex.importer",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
