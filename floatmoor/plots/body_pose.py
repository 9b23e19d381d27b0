"""Where the body is at a time of a run, for the views: the floater's panels placed by its
recorded 6-DOF motion, or, for a forced-motion run, the body-carried points the motion moves.

A floater run records ``body_displacement`` d from the static equilibrium x_eq on the lines
(the simulation's rest position), not from the case's rest pose; the pose drawn is
x = x_eq + d, with the kinematics of :func:`floatmoor.body.kinematics.points_state`,
p = c0 + x[:3] + R(x[3:]) (p0 - c0). Run files hold x_eq as ``body_equilibrium``. Files
written before they did are drawn with x_eq recovered from the body points' recorded
positions at the first output time: a least-squares fit of the six numbers (exact for three
or more body points not on one line; with fewer, the rotation about their line is left as the
record has it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.schema import Case
from floatmoor.plots.body_surface import BodySurface, body_surface
from floatmoor.rotations import rotation_matrix

__all__ = ["BodyModel", "PlacedBody", "body_model", "placed_body", "equilibrium_offset",
           "polygon_through", "OFFSET_TOLERANCE"]

#: Convergence of the x_eq fit (files without ``body_equilibrium``): positions are recorded
#: to float64 (about 1e-16 relative), so the fit stops at 1e-12 of the body's size [m].
OFFSET_TOLERANCE = 1e-12


@dataclass(frozen=True)
class BodyModel:
    """What the views draw of a run's body.

    Attributes
    ----------
    surface
        The floater's panels at rest, or None for a forced-motion run or a floater without
        [floater.geometry] (points only).
    centre
        The rotation centre at rest c0 [m].
    offset
        x_eq (6,): the equilibrium the recorded displacement is measured from (the file's
        ``body_equilibrium``, or fitted for a file without it).
    points
        Names of the body-carried points (the result's ``point`` coordinate).
    """

    surface: BodySurface | None
    centre: NDArray[np.float64]
    offset: NDArray[np.float64]
    points: tuple[str, ...]


@dataclass(frozen=True)
class PlacedBody:
    """The body at one time.

    Attributes
    ----------
    vertices
        (n, 3) [m].
    faces
        (m, 4) panels of ``vertices``, or None: the body is the convex hull of the points
        ``vertices`` in each view (a forced-motion run's body-carried points).
    displacement
        The full displacement from the rest pose x_eq + d (6,), or None (forced motion).
    """

    vertices: NDArray[np.float64]
    faces: NDArray[np.int64] | None
    displacement: NDArray[np.float64] | None


def _body_points(case: Case) -> tuple[tuple[str, ...], NDArray[np.float64]]:
    points = [p for p in case.points if p.kind == "body"]
    return (tuple(p.name for p in points),
            np.array([p.position for p in points], dtype=float).reshape(-1, 3))


def equilibrium_offset(dataset: xr.Dataset, names: tuple[str, ...],
                       rest: NDArray[np.float64], centre: NDArray[np.float64]
                       ) -> NDArray[np.float64]:
    """x_eq (6,) of a floater run: its ``body_equilibrium``, or for a file written before runs
    stored it, the pose at the first output time fitted to the recorded positions of the body
    points ``names`` at rest ``rest`` (n, 3), minus the recorded displacement then (module
    docstring); zero when such a file records no positions of them."""
    if "body_equilibrium" in dataset:
        return np.asarray(dataset["body_equilibrium"].sel(dof=dataset["body_displacement"]
                                                          ["dof"]).values, dtype=float)
    return _fitted_offset(dataset, names, rest, centre)


def _fitted_offset(dataset: xr.Dataset, names: tuple[str, ...], rest: NDArray[np.float64],
                   centre: NDArray[np.float64]) -> NDArray[np.float64]:
    """x_eq fitted to the body points' positions at the first output time (files without
    ``body_equilibrium``)."""
    from scipy.optimize import least_squares

    d0 = np.asarray(dataset["body_displacement"].isel(time=0).values, dtype=float)
    if not names or "point_position" not in dataset \
            or not set(names) <= set(map(str, dataset["point"].values)):
        return np.zeros(6)
    seen = np.asarray(dataset["point_position"].sel(point=list(names)).isel(time=0)
                      .transpose("point", "component").values, dtype=float)
    arms = rest - centre
    size = max(float(np.abs(arms).max()), 1.0)

    def residual(x: NDArray[np.float64]) -> NDArray[np.float64]:
        R = rotation_matrix(float(x[3]), float(x[4]), float(x[5]))
        return ((centre + x[:3] + arms @ R.T) - seen).ravel() / size

    fit = least_squares(residual, d0, method="trf", xtol=OFFSET_TOLERANCE,
                        ftol=OFFSET_TOLERANCE, gtol=OFFSET_TOLERANCE)
    return fit.x - d0


def body_model(case: Case, dataset: xr.Dataset) -> BodyModel | None:
    """The body of a run: the floater (with its panels) when the run has one, the
    body-carried points of a ``[motion] kind = "body"`` run, else None (a translational
    forced motion: nothing to draw beyond the fairleads).

    Raises
    ------
    BemFileError
        For a mesh hull whose file cannot be read or changed since the case was read.
    """
    names, rest = _body_points(case)
    if case.floater is not None and case.floater.geometry is None:
        # a floater of an imported database without a hull: its fairleads, when drawn
        if "body_displacement" in dataset and names and "point_position" in dataset:
            centre = np.asarray(case.floater.reference_point, dtype=float)
            return BodyModel(None, centre, np.zeros(6), names)
        return None
    if case.floater is not None and "body_displacement" in dataset:
        centre = np.asarray(case.floater.reference_point, dtype=float)
        return BodyModel(body_surface(case.floater), centre,
                         equilibrium_offset(dataset, names, rest, centre), names)
    motion = case.motion
    if motion is not None and motion.kind == "body" and len(names) >= 2 \
            and "point_position" in dataset:
        centre = np.asarray(motion.reference_point, dtype=float)  # type: ignore[union-attr]
        return BodyModel(None, centre, np.zeros(6), names)
    return None


def placed_body(model: BodyModel, dataset: xr.Dataset, time: float) -> PlacedBody:
    """The body of ``model`` at the output time nearest ``time`` [s]."""
    if model.surface is None:
        seen = dataset["point_position"].sel(point=list(model.points)).sel(
            time=time, method="nearest")
        return PlacedBody(np.asarray(seen.transpose("point", "component").values, dtype=float),
                          None, None)
    d = np.asarray(dataset["body_displacement"].sel(time=time, method="nearest").values,
                   dtype=float)
    x = model.offset + d
    return PlacedBody(model.surface.placed(x, model.centre), model.surface.faces, x)


def polygon_through(points: NDArray[np.float64]) -> NDArray[np.int64]:
    """The indices (1, n) of ``points`` (n, 3) in turn around their centroid, seen along the
    normal of their best-fit plane (the smallest principal direction): the polygon through a
    forced body's points, for the VTK series."""
    arms = points - points.mean(axis=0)
    _, _, axes = np.linalg.svd(arms)
    angle = np.arctan2(arms @ axes[1], arms @ axes[0])
    return np.argsort(angle, kind="stable")[None, :].astype(np.int64)
