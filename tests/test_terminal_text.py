"""Untrusted text is shown as one terminal-safe line of bounded length."""

from __future__ import annotations

from floatmoor.terminal_text import SHOWN_LIMIT, shown


def test_escape_sequences_become_visible():
    text = "run\x1b]0;owned\x07 done\r\nnext\u202eevil\x9b2J"
    out = shown(text)
    assert out == "run\\x1b]0;owned\\x07 done\\x0d\\x0anext\\u202eevil\\x9b2J"
    assert all(c.isprintable() for c in out)


def test_plain_text_and_unicode_are_kept():
    text = "Lindahl chain, r = 0.20 m, T = 1.25 s, \u03b1 = 0.3, Øresund \\ backslash"
    assert shown(text) == text


def test_length_is_bounded_and_the_cut_is_said():
    out = shown("a" * (SHOWN_LIMIT + 1000))
    assert out == "a" * SHOWN_LIMIT + "... (1000 more characters)"
    assert shown("abcdef", limit=3) == "abc... (3 more characters)"
