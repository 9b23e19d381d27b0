"""Seeded mutants of a text file for the readers' mutation corpora (tests/io/*corpus*.py): a
token set to an extreme or wrong value, a line dropped or repeated, two tokens swapped."""

from __future__ import annotations

import random
import re


def text_mutants(text: str, seed: str, samples: int, values: tuple[str, ...]
                 ) -> list[tuple[str, str]]:
    """(description, text) of ``samples`` mutants of ``text``, reproducible from ``seed``."""
    tokens = [m.span() for m in re.finditer(r"\S+", text)]
    lines = text.splitlines(keepends=True)
    rng = random.Random(seed)
    out = []
    for _ in range(samples):
        kind = rng.random()
        if kind < 0.7:
            a, b = rng.choice(tokens)
            value = rng.choice(values)
            out.append((f"token {text[a:b][:20]!r} at {a} -> {value[:20]!r}",
                        text[:a] + value + text[b:]))
        elif kind < 0.8:
            k = rng.randrange(len(lines))
            out.append((f"line {k + 1} dropped", "".join(lines[:k] + lines[k + 1:])))
        elif kind < 0.9:
            k = rng.randrange(len(lines))
            out.append((f"line {k + 1} repeated", "".join(lines[:k + 1] + lines[k:])))
        else:
            (a, b), (c, d) = sorted(rng.sample(tokens, 2))
            out.append((f"tokens at {a} and {c} swapped",
                        text[:a] + text[c:d] + text[b:c] + text[a:b] + text[d:]))
    return out
