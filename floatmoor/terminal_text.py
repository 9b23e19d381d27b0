"""Text from files shown safely on a terminal: control characters escaped, length bounded.

A case title, a MoorDyn deck's title, a database's recorded attributes or a file name come from
files someone else may have written. Printed raw, a terminal escape sequence (``ESC ] 0; ...
BEL`` retitles the window, ``ESC [ 2 J`` clears it, a carriage return hides what came before it,
a right-to-left override reorders what follows) makes the terminal show what the file's author
chose rather than what floatmoor says. :func:`shown` turns every such character into a visible
escape (``\\x1b``, ``\\u202e``) and bounds the length, so a message quoting untrusted text is one
readable line of bounded size.
"""

from __future__ import annotations

import unicodedata

__all__ = ["shown", "SHOWN_LIMIT", "MESSAGE_LIMIT"]

#: Longest quoted text kept whole [characters]: a title or a recorded command line fits in a few
#: hundred; beyond this the text is cut and the number of characters left out is said, so a
#: megabyte attribute cannot flood a terminal or a log.
SHOWN_LIMIT = 400
#: Longest error message printed whole [characters]: a message names a file, a key, what was
#: expected (a list of choices may take a few hundred characters) and quotes what was found.
MESSAGE_LIMIT = 2000


def _escaped(char: str) -> str:
    """A character as it may appear on a terminal: itself, or a visible escape."""
    if char == "\\":
        return char
    category = unicodedata.category(char)
    # Cc: C0 and C1 controls, DEL (newline, tab and carriage return included: a message is one
    # line); Cf: format characters (bidi overrides and isolates, zero-width joiners);
    # Zl/Zp: line and paragraph separators; Cs/Co/Cn: surrogates, private use, unassigned.
    if category in ("Cc", "Cf", "Zl", "Zp", "Cs", "Co", "Cn"):
        code = ord(char)
        if code <= 0xFF:
            return f"\\x{code:02x}"
        if code <= 0xFFFF:
            return f"\\u{code:04x}"
        return f"\\U{code:08x}"
    return char


def shown(text: object, limit: int = SHOWN_LIMIT) -> str:
    """``text`` as one terminal-safe line of at most about ``limit`` characters.

    Parameters
    ----------
    text
        Any text read from a file (converted with ``str``).
    limit
        Characters of the text kept; longer text is cut and ends with how many were left out.

    Returns
    -------
    str
        The text with control, format and unassigned characters written as visible escapes.
    """
    text = str(text)
    cut = len(text) - limit
    body = "".join(_escaped(c) for c in text[:limit])
    return body if cut <= 0 else f"{body}... ({cut} more characters)"
