"""MoorDyn input files (decks): a strict reader, a writer, and the mapping between a deck and a
floatmoor case in both directions (``floatmoor import moordyn`` / ``floatmoor export moordyn``).

Modules: :mod:`.deck` (the parsed contents), :mod:`.parser` (text -> deck), :mod:`.writer`
(deck -> text), :mod:`.line_types` (floatmoor's line description <-> MoorDyn's),
:mod:`.importer` (deck -> case file text), :mod:`.exporter` (case and the solvers' numerics,
:mod:`floatmoor.mooring.deck_numerics` -> deck).
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "read_deck": "floatmoor.io.moordyn.parser",
    "parse_deck": "floatmoor.io.moordyn.parser",
    "Deck": "floatmoor.io.moordyn.deck",
    "deck_text": "floatmoor.io.moordyn.writer",
    "import_deck": "floatmoor.io.moordyn.importer",
    "export_case": "floatmoor.io.moordyn.exporter",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
