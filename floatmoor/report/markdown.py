"""Rendering a report's content as Markdown (``summary.md``) or a self-contained HTML page.

The content is a list of blocks: :class:`Heading`, :class:`Paragraph`, report tables
(:class:`floatmoor.report.tables.Table`) and :class:`Figure` links (relative file names).
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from typing import Sequence, Union

from floatmoor.report.tables import Table

__all__ = ["Heading", "Paragraph", "Figure", "Block", "render_markdown", "render_html"]


@dataclass(frozen=True)
class Heading:
    """A section heading (level 1 to 4)."""

    text: str
    level: int = 2


@dataclass(frozen=True)
class Paragraph:
    """A paragraph of text (Markdown emphasis allowed)."""

    text: str


@dataclass(frozen=True)
class Figure:
    """An image file beside the summary, with a caption."""

    path: str  #: relative to the summary
    caption: str


Block = Union[Heading, Paragraph, Table, Figure]


def _md_cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def render_markdown(blocks: Sequence[Block]) -> str:
    """The blocks as GitHub-flavoured Markdown."""
    out: list[str] = []
    for block in blocks:
        if isinstance(block, Heading):
            out += ["#" * block.level + " " + block.text, ""]
        elif isinstance(block, Paragraph):
            out += [block.text, ""]
        elif isinstance(block, Figure):
            out += [f"![{block.caption}]({block.path})", "", f"*{block.caption}*", ""]
        elif isinstance(block, Table):
            out += [f"**{block.title}**", ""]
            out.append("| " + " | ".join(_md_cell(h) for h in block.headers) + " |")
            out.append("|" + "|".join(" --- " for _ in block.headers) + "|")
            out += ["| " + " | ".join(_md_cell(c) for c in row) + " |" for row in block.rows]
            out.append("")
            out += [note + "\n" for note in block.notes]
    return "\n".join(out).rstrip() + "\n"


def _html_text(text: str) -> str:
    escaped = html.escape(text)
    parts = escaped.split("**")  # **bold** as in the Markdown
    return "".join(f"<strong>{p}</strong>" if i % 2 else p for i, p in enumerate(parts))


def render_html(blocks: Sequence[Block], title: str) -> str:
    """The blocks as one HTML page (figures linked, not embedded)."""
    out = ["<!DOCTYPE html>", "<html><head><meta charset=\"utf-8\">",
           f"<title>{html.escape(title)}</title>",
           "<style>body{font-family:sans-serif;max-width:1100px;margin:auto}"
           "table{border-collapse:collapse;margin:0.5em 0}"
           "td,th{border:1px solid #bbb;padding:2px 8px;text-align:right}"
           "td:first-child,th:first-child{text-align:left}img{max-width:100%}</style>",
           "</head><body>"]
    for block in blocks:
        if isinstance(block, Heading):
            out.append(f"<h{block.level}>{html.escape(block.text)}</h{block.level}>")
        elif isinstance(block, Paragraph):
            out.append(f"<p>{_html_text(block.text)}</p>")
        elif isinstance(block, Figure):
            out.append(f"<figure><img src=\"{html.escape(block.path)}\" alt=\""
                       f"{html.escape(block.caption)}\"><figcaption>"
                       f"{html.escape(block.caption)}</figcaption></figure>")
        elif isinstance(block, Table):
            out.append(f"<p><strong>{html.escape(block.title)}</strong></p><table>")
            out.append("<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in block.headers)
                       + "</tr>")
            for row in block.rows:
                out.append("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in row)
                           + "</tr>")
            out.append("</table>")
            out += [f"<p><small>{_html_text(note)}</small></p>" for note in block.notes]
    out.append("</body></html>")
    return "\n".join(out) + "\n"
