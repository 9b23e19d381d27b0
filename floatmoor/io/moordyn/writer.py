"""A :class:`~floatmoor.io.moordyn.deck.Deck` -> the text of a MoorDyn v2 input file.

Numbers are written at round-trip precision (Python's shortest repr), so that reading the file
back gives the same values. ``notes`` go into the title block (MoorDyn reads nothing before the
first section heading), one ``#`` line each.
"""

from __future__ import annotations

from collections.abc import Sequence

from floatmoor.io.moordyn.deck import POINT_COUPLED, POINT_FIXED, POINT_FREE, Deck

__all__ = ["deck_text"]

_ATTACHMENT = {POINT_FIXED: "Fixed", POINT_COUPLED: "Coupled", POINT_FREE: "Free"}


def _n(value: float) -> str:
    return repr(float(value))


def _table(rows: list[list[str]]) -> list[str]:
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    return ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]


def deck_text(deck: Deck, notes: Sequence[str] = ()) -> str:
    """The v2 input file text of ``deck``, with ``notes`` as comments in its title block.

    Parameters
    ----------
    deck
        The contents to write.
    notes
        Lines of comment (what MoorDyn cannot represent, where the deck came from).

    Returns
    -------
    str
        The file's text.

    Raises
    ------
    ValueError
        A note or the title would be read as a section heading (it holds ``---``), or a point
        is attached to a body (the writer writes fixed, coupled and free points only).
    """
    for text in (deck.title, *notes):
        if "---" in text or "\n" in text:
            raise ValueError(f"title and notes must be single lines without '---': {text!r}")
    out = ["--------------------- MoorDyn Input File ------------------------------------",
           deck.title]
    out.extend(f"# {note}" for note in notes)
    out.append("----------------------- LINE TYPES ------------------------------------------")
    rows = [["TypeName", "Diam", "Mass/m", "EA", "BA/-zeta", "EI", "Cd", "Ca", "CdAx", "CaAx"],
            ["(name)", "(m)", "(kg/m)", "(N)", "(N-s/-)", "(N-m^2)", "(-)", "(-)", "(-)", "(-)"]]
    rows += [[t.name, _n(t.diameter), _n(t.mass_per_length), _n(t.axial_stiffness),
              _n(t.internal_damping), _n(t.bending_stiffness), _n(t.normal_drag_coefficient),
              _n(t.added_mass_coefficient), _n(t.tangential_drag_coefficient),
              _n(t.tangential_added_mass_coefficient)] for t in deck.line_types]
    out += _table(rows)
    out.append("---------------------- POINTS ------------------------------------------------")
    rows = [["ID", "Attachment", "X", "Y", "Z", "Mass", "Volume", "CdA", "Ca"],
            ["(#)", "(-)", "(m)", "(m)", "(m)", "(kg)", "(m^3)", "(m^2)", "(-)"]]
    for p in deck.points:
        if p.attachment not in _ATTACHMENT:
            raise ValueError(f"point {p.number}: cannot write a {p.attachment} point")
        rows.append([str(p.number), _ATTACHMENT[p.attachment], *(_n(c) for c in p.position),
                     _n(p.mass), _n(p.volume), _n(p.drag_area), _n(p.added_mass_coefficient)])
    out += _table(rows)
    out.append("---------------------- LINES -------------------------------------------------")
    rows = [["ID", "LineType", "AttachA", "AttachB", "UnstrLen", "NumSegs", "Outputs"],
            ["(#)", "(name)", "(#)", "(#)", "(m)", "(-)", "(-)"]]
    rows += [[str(ln.number), ln.line_type, str(ln.start), str(ln.end), _n(ln.length),
              str(ln.segments), ln.outputs or "-"] for ln in deck.lines]
    out += _table(rows)
    out.append("---------------------- OPTIONS -----------------------------------------------")
    out += _table([[o.value, o.key] for o in deck.options])
    if deck.outputs:
        out.append("---------------------- OUTPUTS -----------------------------------------------")
        out.append(" ".join(deck.outputs))
    out.append("------------------------- END ------------------------------------------------")
    return "\n".join(out) + "\n"
