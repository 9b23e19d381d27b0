"""MoorDyn input files (decks): a strict reader, a writer, and the mapping between a deck and a
floatmoor case in both directions (``floatmoor import moordyn`` / ``floatmoor export moordyn``).

Modules: :mod:`.deck` (the parsed contents), :mod:`.parser` (text -> deck), :mod:`.writer`
(deck -> text), :mod:`.line_types` (floatmoor's line description <-> MoorDyn's),
:mod:`.importer` (deck -> case file text), :mod:`.exporter` (case and the solvers' numerics,
:mod:`floatmoor.mooring.deck_numerics` -> deck).
"""
