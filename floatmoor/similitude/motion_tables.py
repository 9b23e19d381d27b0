"""The motion table of a scaled case (``[motion] file``), rewritten at the new scale.

Times scale by the law's time factor (sqrt(lambda), eq. 33), displacements by lambda and
rotations not at all; the table keeps its header (``time, x, y, z`` or a body table's
``time, surge, sway, heave, roll_deg|rad, ...``, the formats of
:mod:`floatmoor.case.motion_table`), its comment lines and row order, with a comment line
saying where it comes from. Values are written as in the scaled case file
(:func:`~floatmoor.similitude.decimals.rounded`), so a round trip gives the original numbers.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from floatmoor.case.motion_body import BODY_TABLE_HEADERS
from floatmoor.case.motion_table import HEADER
from floatmoor.similitude.decimals import rounded
from floatmoor.similitude.laws import ScaleLaw

__all__ = ["ScaledTable", "COLUMN_KINDS", "scaled_table_name", "scale_motion_table"]

#: Quantity kind (:meth:`ScaleLaw.factor`) of every column a motion table may have, from the
#: headers the case loader accepts: time, rotations (``*_deg``, ``*_rad``) unscaled, the rest
#: displacements.
COLUMN_KINDS: dict[str, str] = {
    c: "time" if c == "time" else "same" if c.endswith(("_deg", "_rad")) else "length"
    for header in (HEADER, *BODY_TABLE_HEADERS) for c in header
}


@dataclass(frozen=True)
class ScaledTable:
    """A scaled motion table to write beside the scaled case."""

    path: Path  #: where it goes: the scaled case's folder, :func:`scaled_table_name`
    source: Path  #: the original table
    text: str  #: its contents


def scaled_table_name(output: str | Path, original: str | Path) -> str:
    """File name of the scaled table: the scaled case's name, then the original table's
    (``prototype.toml`` and ``motion.csv`` give ``prototype_motion.csv``)."""
    return f"{Path(output).stem}_{Path(original).name}"


def scale_motion_table(text: str, law: ScaleLaw, note: str) -> str:
    """The text of a motion table (already read and checked by the case loader) at the new
    scale, ``note`` (one line) as its first comment line."""
    out = [f"# {note}"]
    kinds: list[str] | None = None
    for line in text.splitlines():
        if not line.strip() or line.lstrip().startswith("#"):
            out.append(line)
            continue
        cells = [c.strip() for c in line.split(",")]
        if kinds is None:  # the header row
            kinds = [COLUMN_KINDS[c] for c in cells]
            out.append(line)
            continue
        out.append(",".join(repr(rounded(float(c) * law.factor(k)))
                            for c, k in zip(cells, kinds, strict=True)))
    return "\n".join(out) + "\n"
