"""The floater's static equilibrium in the run file (``body_equilibrium``, the origin of
``body_displacement``) and the views' use of it; files written before runs stored it are
drawn with the equilibrium fitted to the recorded fairleads (floatmoor.plots.body_pose)."""

from __future__ import annotations

import warnings

import numpy as np
from scipy.optimize import root

from floatmoor.body.kinematics import generalised_force, points_state
from floatmoor.body.model import static_force
from floatmoor.case.load import load_case
from floatmoor.hydro.database import load_for_case
from floatmoor.hydro.radiation import hydrostatic_stiffness_total
from floatmoor.io.dataset import DOFS
from floatmoor.plots import body_pose
from floatmoor.plots.body_pose import body_model
from floatmoor.plots.context import run_context
from floatmoor.plots.shapes import frame
from floatmoor.simulation.coupled import EQUILIBRIUM_RTOL, line_force_quasi_static
from tests.plots.conftest import BUOY, RUN

#: Placing the fairleads is a rotation and a translation of coordinates below 7 m: exact to
#: float64 rounding (about 1e-15 m); the brief's 1e-9 m [m].
POSITION_TOL = 1e-9
#: The run solves the equilibrium to a residual force of EQUILIBRIUM_RTOL (1e-9) of the
#: largest static force (the lines' 7.4 N pull on the buoy), so to 7.4e-9 N; over the
#: smallest restoring stiffness of the free DOFs (surge and pitch on the chains, about
#: 10 N/m and 37 N m/rad) that is 1e-9 m or rad. The test's own solve is as tight; twice
#: that plus a margin of 5 [m or rad].
EQUILIBRIUM_ATOL = 1e-8
#: The equilibrium fitted for files without ``body_equilibrium`` against the stored one: the
#: fit stops at body_pose.OFFSET_TOLERANCE (1e-12 of the body's size, 0.26 m here) on three
#: fairleads not on one line (all six DOFs resolved); 1e-9, as the positions [m or rad].
FIT_ATOL = 1e-9


def _case():
    return load_case(BUOY, [item for item in RUN if item.startswith(("simulation", "lines"))])


def _independent_equilibrium(case) -> tuple[np.ndarray, object]:
    """The buoy's static equilibrium solved here (scipy's hybrid Powell method on the static
    balance, not the run's Newton): F_0 - C x + sum of the catenaries' generalised forces
    = 0 with the database's hydrostatics; and the balance's residual function."""
    ds = load_for_case(case)
    env = case.environment
    f0 = static_force(case.floater, ds, env)
    stiffness = hydrostatic_stiffness_total(ds, case.floater)
    centre = np.asarray(case.floater.reference_point, dtype=float)
    arms = np.array([np.subtract(line.fairlead, centre) for line in case.lines])

    def balance(x: np.ndarray) -> np.ndarray:
        pos, _ = points_state(x, np.zeros(6), arms, centre)
        forces = np.array([line_force_quasi_static(line, env, case.seabed, p)
                           for line, p in zip(case.lines, pos)])
        return f0 - stiffness @ x + generalised_force(x, forces, arms)

    # sway, roll and yaw are free of stiffness by symmetry: solved in the other three
    free = np.array([0, 2, 4])

    def reduced(y: np.ndarray) -> np.ndarray:
        x = np.zeros(6)
        x[free] = y
        return balance(x)[free]

    # to the relative step 1e-10 (the catenaries' own tolerance stops a tighter one)
    solution = root(reduced, np.zeros(3), method="hybr", options={"xtol": 1e-10})
    assert solution.success, solution.message
    x = np.zeros(6)
    x[free] = solution.x
    return x, balance


def test_run_file_holds_the_equilibrium_its_displacement_is_measured_from(dataset):
    variable = dataset["body_equilibrium"]
    assert variable.dims == ("dof",) and tuple(map(str, variable["dof"].values)) == DOFS
    assert variable.attrs["units"] == "m or rad"
    assert "static equilibrium" in variable.attrs["long_name"]
    assert "body_equilibrium" in dataset["body_displacement"].attrs["long_name"]
    expected, balance = _independent_equilibrium(_case())
    stored = variable.values
    print(f"stored {stored}, independent {expected}, "
          f"difference {np.abs(stored - expected).max():.2e}")
    np.testing.assert_allclose(stored, expected, rtol=0.0, atol=EQUILIBRIUM_ATOL)
    assert stored[2] < -3e-3  # the chains' weight sinks the buoy (3.6 mm)
    # the stored pose balances the static forces as tightly as the run asks
    pull = np.abs(balance(np.zeros(6))).max()
    assert np.abs(balance(stored)).max() <= EQUILIBRIUM_RTOL * pull


def test_fairleads_placed_from_the_equilibrium_are_where_the_run_recorded_them(dataset):
    case = _case()
    centre = np.asarray(case.floater.reference_point, dtype=float)
    names = [p.name for p in case.points if p.kind == "body"]
    arms = np.array([np.subtract(case.point(name).position, centre) for name in names])
    x0 = dataset["body_equilibrium"].values + dataset["body_displacement"].isel(time=0).values
    placed, _ = points_state(x0, np.zeros(6), arms, centre)
    seen = dataset["point_position"].sel(point=names).isel(time=0) \
        .transpose("point", "component").values
    print(f"largest fairlead misplacement {np.abs(placed - seen).max():.2e} m")
    np.testing.assert_allclose(placed, seen, rtol=0.0, atol=POSITION_TOL)


def test_views_take_the_stored_equilibrium_without_fitting(dataset, monkeypatch):
    def no_fit(*args):
        raise AssertionError("fitted although the file holds body_equilibrium")

    monkeypatch.setattr(body_pose, "_fitted_offset", no_fit)
    model = body_model(_case(), dataset)
    assert np.array_equal(model.offset, dataset["body_equilibrium"].values)


def test_file_without_the_equilibrium_is_drawn_with_the_fitted_one(dataset):
    """A file written before runs stored ``body_equilibrium``: the fit to the fairleads at
    t = 0 gives the same pose, and no warning."""
    older = dataset.drop_vars("body_equilibrium")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model = body_model(_case(), older)
    print(f"fit - stored: {np.abs(model.offset - dataset['body_equilibrium'].values).max():.2e}")
    np.testing.assert_allclose(model.offset, dataset["body_equilibrium"].values, rtol=0.0,
                               atol=FIT_ATOL)


def test_without_a_body_model_the_marked_centre_is_at_the_equilibrium_plus_the_motion(
        dataset):
    """A run whose case does not re-read has no body model; the body's centre marked in the
    shape views is still the reference point moved by x_eq + d (d alone for older files)."""
    broken = dataset.copy()
    broken.attrs = dict(dataset.attrs, case_toml="[not a case")
    context = run_context(broken)
    assert context.body is None
    x = (dataset["body_equilibrium"] + dataset["body_displacement"].sel(
        time=float(dataset["shape_time"][5]), method="nearest")).values
    centre = frame(broken, 5, context).body
    np.testing.assert_allclose(centre, np.asarray(context.reference_point) + x[:3], rtol=0.0,
                               atol=POSITION_TOL)
    older = frame(broken.drop_vars("body_equilibrium"), 5, context).body
    np.testing.assert_allclose(older, centre - dataset["body_equilibrium"].values[:3],
                               rtol=0.0, atol=POSITION_TOL)
