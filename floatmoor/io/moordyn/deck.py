"""The contents of a MoorDyn v2 input file, as read (MoorDyn's units: SI, z up, angles in deg).

Every row keeps the line number it came from, so that the importer's messages can point at it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

__all__ = ["DeckLineType", "DeckPoint", "DeckLine", "DeckOption", "DeckSection", "Deck",
           "POINT_FIXED", "POINT_COUPLED", "POINT_FREE", "POINT_BODY"]

#: Point attachments, normalised from MoorDyn's spellings (parser.ATTACHMENTS).
POINT_FIXED, POINT_COUPLED, POINT_FREE, POINT_BODY = "fixed", "coupled", "free", "body"


@dataclass(frozen=True)
class DeckLineType:
    """A row of LINE TYPES: MoorDyn's one diameter serves buoyancy, added mass and drag."""

    name: str
    diameter: float  #: Diam [m]
    mass_per_length: float  #: Mass/m [kg/m]
    axial_stiffness: float  #: EA [N]
    internal_damping: float  #: BA [N s], or -zeta (a ratio of a segment's critical damping)
    bending_stiffness: float  #: EI [N m^2]
    normal_drag_coefficient: float  #: Cd, on Diam [-]
    added_mass_coefficient: float  #: Ca [-]
    tangential_drag_coefficient: float  #: CdAx, on pi Diam [-]
    tangential_added_mass_coefficient: float  #: CaAx [-]
    line_number: int = 0


@dataclass(frozen=True)
class DeckPoint:
    """A row of POINTS. ``body`` is the body number of a ``BodyN`` attachment (position
    relative to the body), else 0."""

    number: int
    attachment: str  #: one of POINT_FIXED, POINT_COUPLED, POINT_FREE, POINT_BODY
    position: tuple[float, float, float]  #: [m]
    mass: float  #: [kg]
    volume: float  #: [m^3]
    drag_area: float  #: CdA [m^2]
    added_mass_coefficient: float  #: Ca [-]
    body: int = 0
    attachment_text: str = ""  #: as written
    line_number: int = 0


@dataclass(frozen=True)
class DeckLine:
    """A row of LINES. ``length`` < 0 means a multiple of the end points' distance."""

    number: int
    line_type: str
    start: int  #: AttachA point number
    end: int  #: AttachB point number
    length: float  #: UnstrLen [m]
    segments: int  #: NumSegs
    outputs: str  #: output flags ("-" for none)
    line_number: int = 0


@dataclass(frozen=True)
class DeckOption:
    """A row of OPTIONS: ``value key [description]``."""

    key: str
    value: str
    line_number: int = 0


@dataclass(frozen=True)
class DeckSection:
    """A section kept as text: one floatmoor cannot model (RODS, BODIES, ...) or OUTPUTS."""

    name: str  #: normalised heading ("RODS")
    heading: str  #: as written
    rows: tuple[str, ...]
    line_number: int = 0


@dataclass(frozen=True)
class Deck:
    """A parsed MoorDyn input file.

    Attributes
    ----------
    source
        Its path, for messages.
    title
        The title line(s) before the first section.
    line_types, points, lines, options, outputs
        The rows of the ``LINE TYPES``, ``POINTS``, ``LINES``, ``OPTIONS`` and ``OUTPUTS``
        sections, in file order.
    other_sections
        Sections read as text only, in file order (bodies, rods, failures, ...).
    bodies
        The body rows (kept as their split fields) by body number, for body-attached points.
    """

    source: str  #: path, for messages
    title: str = ""
    line_types: tuple[DeckLineType, ...] = ()
    points: tuple[DeckPoint, ...] = ()
    lines: tuple[DeckLine, ...] = ()
    options: tuple[DeckOption, ...] = ()
    outputs: tuple[str, ...] = ()
    #: sections read as text only, in file order (bodies, rods, failures, ...)
    other_sections: tuple[DeckSection, ...] = ()
    #: the body rows (kept as their split fields) by body number, for body-attached points
    bodies: dict[int, tuple[str, ...]] = field(default_factory=dict)

    def option(self, *keys: str) -> DeckOption | None:
        """The last option whose key is one of ``keys`` (case-insensitive), or None: MoorDyn
        reads the options in order, so a later one wins."""
        wanted = {k.lower() for k in keys}
        found = None
        for opt in self.options:
            if opt.key.lower() in wanted:
                found = opt
        return found
