"""OrcaFlex text data files (``.yml``, OrcaFlex 9.8 and later): a strict, safe YAML reader and
the mapping of the mooring part of a model to a floatmoor case (``floatmoor import orcaflex``).

Modules: :mod:`.reader` (file -> plain data, aliases, anchors and merge keys refused, sizes
bounded), :mod:`.values` (numbers, units and key paths for messages), :mod:`.importer` (model
-> case file text, checked by the case loader before anything is written); the command is
:mod:`floatmoor.cli.orcaflex`.
The mapping is documented in docs/guide/mooring_systems.md#orcaflex-models.
"""
