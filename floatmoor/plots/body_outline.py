"""The body's outline in a view: the union of its panels projected on the view's plane, drawn
as one filled translucent patch.

Each projected panel is turned counter-clockwise and all are joined into one compound path;
matplotlib fills a path by the non-zero winding rule, so the patch covers the union of the
panels once (one shade however many panels overlap): the body's silhouette, with the holes
between columns left open. A body given by points only (a forced-motion run) is their convex
hull in the view: the polygon through the fairleads.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from floatmoor.plots.body_pose import PlacedBody

__all__ = ["VIEW_AXES", "view_polygons", "body_path", "body_patch", "update_body_patch",
           "BODY_COLOUR", "BODY_ALPHA"]

#: (horizontal, vertical) coordinate indices of each view.
VIEW_AXES = {"side": (0, 2), "plan": (0, 1)}
#: Colour and opacity of the body's patch (the lines behind it stay visible).
BODY_COLOUR, BODY_ALPHA = "0.35", 0.35
#: Projected panels smaller than this fraction of the squared size of the body are seen
#: edge-on and left out (they add nothing to the union).
_EDGE_ON = 1e-12


def _signed_areas(polygons: NDArray[np.float64]) -> NDArray[np.float64]:
    """Shoelace areas of (m, k, 2) polygons, positive counter-clockwise."""
    x, y = polygons[..., 0], polygons[..., 1]
    return 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)


def _turn(a, b, c) -> float:
    """z of (b - a) x (c - a): positive for a left turn."""
    return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def _hull(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """Counter-clockwise convex hull of 2-D points (Andrew's monotone chain); two extreme
    points when they lie on one line, the point itself when there is one."""
    pts = np.unique(points, axis=0)
    if len(pts) < 3:
        return pts

    def chain(seq):
        out: list = []
        for p in seq:
            while len(out) >= 2 and _turn(out[-2], out[-1], p) <= 0.0:
                out.pop()
            out.append(p)
        return out[:-1]

    hull = chain(pts) + chain(pts[::-1])
    return np.array(hull) if len(hull) >= 2 else pts[[0, -1]]


def view_polygons(body: PlacedBody, view: str) -> list[NDArray[np.float64]]:
    """The closed polygons (k, 2) whose union is ``body`` seen in ``view`` ("side": x-z,
    "plan": x-y), counter-clockwise [m]."""
    axes = list(VIEW_AXES[view])
    flat = body.vertices[:, axes]
    if body.faces is None:
        return [_hull(flat)]
    polygons = flat[body.faces]
    area = _signed_areas(polygons)
    size = float(np.ptp(flat, axis=0).max()) if len(flat) else 0.0
    keep = np.abs(area) > _EDGE_ON * size * size
    polygons = np.where((area < 0.0)[:, None, None], polygons[:, ::-1], polygons)[keep]
    return list(polygons)


def body_path(body: PlacedBody, view: str):
    """:func:`view_polygons` as one matplotlib compound path."""
    from matplotlib.path import Path

    polygons = view_polygons(body, view)
    vertices = np.concatenate([np.vstack([p, p[:1]]) for p in polygons])
    codes = np.concatenate([[Path.MOVETO] + [Path.LINETO] * (len(p) - 1) + [Path.CLOSEPOLY]
                            for p in polygons]).astype(Path.code_type)
    return Path(vertices, codes)


def body_patch(ax, body: PlacedBody, view: str, *, colour: str = BODY_COLOUR,
               label: str | None = None):
    """Add the body's patch in ``view`` to ``ax`` and return it: filled in ``colour`` at
    :data:`BODY_ALPHA`, without an edge for panels (their inner edges would show), with a
    solid edge for a polygon through points (seen edge-on it is a segment)."""
    from matplotlib.colors import to_rgba
    from matplotlib.patches import PathPatch

    points = body.faces is None
    patch = PathPatch(body_path(body, view), facecolor=to_rgba(colour, BODY_ALPHA),
                      edgecolor=to_rgba(colour, 1.0) if points else "none",
                      linewidth=1.5 if points else 0.0, zorder=1.5, label=label)
    return ax.add_patch(patch)


def update_body_patch(patch, body: PlacedBody, view: str) -> None:
    """Move an animation's body patch to ``body``."""
    patch.set_path(body_path(body, view))
