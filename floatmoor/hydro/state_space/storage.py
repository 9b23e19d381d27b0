"""A database's state-space realisation stored in its own netCDF file.

Variables ``state_space_*`` (the modal A as two diagonals, B, C, the pairs and their
errors) and attributes are added beside the BEM variables without touching them or the
recorded inputs, so adding a fit (``floatmoor hydro fit-state-space``) does not make the
database stale; :func:`read_state_space` refuses a damaged realisation loudly.
"""

from __future__ import annotations

import json
import math

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor._version import __version__
from floatmoor.hydro.database import HydroDatabaseError
from floatmoor.hydro.state_space.kernel_fit import METHOD
from floatmoor.hydro.state_space.realisation import DOFS, PairRealisation, StateSpaceRadiation
from floatmoor.terminal_text import shown

__all__ = ["has_state_space", "read_state_space", "add_to_dataset", "remove_from_dataset"]

#: Name prefix of every variable, dimension and attribute of the realisation.
_PREFIX = "state_space_"

_VARIABLES = {
    "order": {"long_name": "number of radiation states of the pair", "units": "1"},
    "radiating_dof": {"long_name": "degree of freedom of the motion driving the pair's states",
                      "units": "1"},
    "influenced_dof": {"long_name": "degree of freedom of the force of the pair's states",
                       "units": "1"},
    "A_diagonal": {"long_name": "diagonal of the state matrix A (real modal form, "
                                "z' = A z + B v_radiating: A = diag(A_diagonal) + "
                                "superdiag(A_superdiagonal) - subdiag(A_superdiagonal) within "
                                "each pair's block)", "units": "1/s"},
    "A_superdiagonal": {"long_name": "superdiagonal of A (the frequency of a complex pole "
                                     "pair on its first state, 0 elsewhere; the subdiagonal "
                                     "is its negative)", "units": "1/s"},
    "B": {"long_name": "input vector: z' = A z + B v_radiating (states in m or rad)",
          "units": "1"},
    "C": {"long_name": "output vector: radiation force mu_influenced = sum C z over the pair "
                       "(kg/s^2, kg m/s^2, kg m^2/s^2 by DOF pair, as K(t))", "units": "kg/s^2"},
    "kernel_error": {"long_name": "relative L2 error of the realisation's K(t) over the "
                                  "truncation time", "units": "1"},
    "damping_error": {"long_name": "largest |B_fit - B_BEM| over the BEM band relative to "
                                   "sqrt(max B_ii max B_jj)", "units": "1"},
    "added_mass_error": {"long_name": "largest |A_fit - A_BEM| over the BEM band relative to "
                                      "sqrt(max A_ii max A_jj) (A_inf: the band mean)",
                         "units": "1"},
    "min_damping": {"long_name": "diagonal pairs: smallest B_fit(omega) over all frequencies "
                                 "relative to its largest (>= 0: passive)", "units": "1"},
}


def _modal_matrix(diagonal: NDArray[np.float64], upper: NDArray[np.float64]
                  ) -> NDArray[np.float64]:
    """diag(diagonal) + superdiag(upper) - subdiag(upper)."""
    upper = np.asarray(upper, float)[:len(diagonal) - 1]
    return np.diag(np.asarray(diagonal, float)) + np.diag(upper, 1) - np.diag(upper, -1)


def has_state_space(ds: xr.Dataset) -> bool:
    """Whether the database holds a state-space realisation."""
    return f"{_PREFIX}A_diagonal" in ds.variables


def remove_from_dataset(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` without any state-space variables, dimensions and attributes."""
    names = [v for v in ds.variables if str(v).startswith(_PREFIX)]
    out = ds.drop_vars(names)
    for key in [k for k in out.attrs if k.startswith(_PREFIX)]:
        del out.attrs[key]
    return out


def add_to_dataset(ds: xr.Dataset, realisation: StateSpaceRadiation) -> xr.Dataset:
    """``ds`` with the realisation's variables and attributes (replacing any earlier fit);
    every other variable and attribute is left as it is."""
    out = remove_from_dataset(ds)
    out.attrs.pop("path", None)
    pairs = realisation.pairs
    diagonal = np.zeros(realisation.n_states)
    upper = np.zeros(realisation.n_states)
    b = np.zeros(realisation.n_states)
    c = np.zeros(realisation.n_states)
    k = 0
    for p in pairs:
        n = p.order
        if not np.array_equal(p.a, _modal_matrix(np.diagonal(p.a), np.diagonal(p.a, 1))):
            raise ValueError("the realisation is not in real modal form")
        diagonal[k:k + n] = np.diagonal(p.a)
        upper[k:k + n - 1] = np.diagonal(p.a, 1)
        b[k:k + n] = p.b
        c[k:k + n] = p.c
        k += n

    def var(name: str, values, dims) -> xr.DataArray:
        return xr.DataArray(values, dims=dims, attrs=dict(_VARIABLES[name]))

    out[f"{_PREFIX}order"] = var("order", np.array([p.order for p in pairs], np.int32),
                                 ("state_space_pair",))
    out[f"{_PREFIX}radiating_dof"] = var("radiating_dof",
                                         np.array([DOFS[p.radiating] for p in pairs]),
                                         ("state_space_pair",))
    out[f"{_PREFIX}influenced_dof"] = var("influenced_dof",
                                          np.array([DOFS[p.influenced] for p in pairs]),
                                          ("state_space_pair",))
    out[f"{_PREFIX}A_diagonal"] = var("A_diagonal", diagonal, ("state_space_state",))
    out[f"{_PREFIX}A_superdiagonal"] = var("A_superdiagonal", upper, ("state_space_state",))
    out[f"{_PREFIX}B"] = var("B", b, ("state_space_state",))
    out[f"{_PREFIX}C"] = var("C", c, ("state_space_state",))
    for name in ("kernel_error", "damping_error", "added_mass_error", "min_damping"):
        out[f"{_PREFIX}{name}"] = var(name, np.array([getattr(p, name) for p in pairs]),
                                      ("state_space_pair",))
    out.attrs.update({
        f"{_PREFIX}method": METHOD,
        f"{_PREFIX}settings_json": json.dumps(realisation.settings, sort_keys=True),
        f"{_PREFIX}kernel_json": json.dumps(realisation.kernel_settings, sort_keys=True),
        f"{_PREFIX}errors_json": json.dumps(realisation.summary(), sort_keys=True),
        f"{_PREFIX}created": realisation.created,
        f"{_PREFIX}fit_seconds": float(realisation.fit_seconds),
        f"{_PREFIX}floatmoor_version": __version__,
    })
    return out


def read_state_space(ds: xr.Dataset) -> StateSpaceRadiation | None:
    """The realisation stored in ``ds``, or None.

    Raises
    ------
    HydroDatabaseError
        The variables are there but inconsistent (a damaged file).
    """
    if not has_state_space(ds):
        return None
    where = shown(ds.attrs.get("path", ds.attrs.get("database", "database")), 200)
    try:
        orders = ds[f"{_PREFIX}order"].values.astype(int)
        rad = [DOFS.index(str(v)) for v in ds[f"{_PREFIX}radiating_dof"].values]
        inf = [DOFS.index(str(v)) for v in ds[f"{_PREFIX}influenced_dof"].values]
        diagonal = np.asarray(ds[f"{_PREFIX}A_diagonal"].values, float)
        upper = np.asarray(ds[f"{_PREFIX}A_superdiagonal"].values, float)
        b = np.asarray(ds[f"{_PREFIX}B"].values, float)
        c = np.asarray(ds[f"{_PREFIX}C"].values, float)
        errors = {n: np.asarray(ds[f"{_PREFIX}{n}"].values, float)
                  for n in ("kernel_error", "damping_error", "added_mass_error", "min_damping")}
        matrix = json.loads(ds.attrs[f"{_PREFIX}errors_json"]).get("matrix_min_damping")
        summary = json.loads(ds.attrs[f"{_PREFIX}errors_json"])["pairs"]
        settings = json.loads(ds.attrs[f"{_PREFIX}settings_json"])
        ksettings = json.loads(ds.attrs[f"{_PREFIX}kernel_json"])
        if not (isinstance(settings, dict) and isinstance(ksettings, dict)
                and isinstance(ksettings.get("fingerprint", {}), dict)
                and isinstance(settings.get("kernel_rtol", 0.0), (int, float))):
            raise ValueError("settings of another kind than recorded by a fit")
        if orders.sum() != b.size or diagonal.size != b.size or upper.size != b.size or \
                c.size != b.size or np.any(orders < 1):
            raise ValueError("state counts disagree")
        if not all(np.all(np.isfinite(x)) for x in (diagonal, upper, b, c)):
            raise ValueError("non-finite values")
        pairs = []
        k = 0
        for p, n in enumerate(orders):
            info = summary[p] if p < len(summary) else {}
            pairs.append(PairRealisation(
                rad[p], inf[p], _modal_matrix(diagonal[k:k + n], upper[k:k + n]),
                b[k:k + n].copy(), c[k:k + n].copy(),
                float(errors["kernel_error"][p]), float(errors["damping_error"][p]),
                float(errors["min_damping"][p]), float(errors["added_mass_error"][p]),
                int(info.get("dropped", 0)), int(info.get("reflected", 0)),
                bool(info.get("passivity_enforced", False)),
                bool(info.get("within_tolerance", True))))
            k += n
        return StateSpaceRadiation(tuple(pairs), settings, ksettings,
                                   shown(ds.attrs.get(f"{_PREFIX}created", ""), 40),
                                   float(ds.attrs.get(f"{_PREFIX}fit_seconds", math.nan)),
                                   math.nan if matrix is None else float(matrix))
    # the variables and attributes are the file's: any of another kind or shape (also JSON
    # Python cannot read, or nested past its recursion limit) is a damaged realisation
    except (KeyError, ValueError, TypeError, AttributeError, IndexError, RecursionError) as err:
        raise HydroDatabaseError(f"{where}: damaged state-space realisation "
                                 f"({shown(err, 200)}); refit with 'floatmoor hydro "
                                 "fit-state-space'") from None
