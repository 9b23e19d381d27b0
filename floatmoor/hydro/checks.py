"""The checks every hydrodynamic database must pass (``floatmoor hydro check`` and the tests).

Each check returns a :class:`CheckResult` with its worst measured value and its tolerance:

* ``symmetry``: A(omega) and B(omega) symmetric (reciprocity), each asymmetry measured against
  the matrix's scale for the pair's kinds of DOF (see :func:`check_symmetry`);
* ``damping_psd``: B(omega) positive semidefinite (a body in waves radiates energy, never
  absorbs it);
* ``kramers_kronig``: A(omega) rebuilt from K(t) and A_inf (floatmoor.hydro.radiation) within
  3 % of the BEM values over the band, for each DOF with added mass;
* ``kernel_decay``: |K_ii(t)| below 1e-3 of its peak from some time before the truncation time
  on (a failure says which frequencies to add: :func:`finer_frequencies`);
* ``haskind``: radiation damping against the one obtained from the excitation forces (Haskind
  relation, energy flux) within 5 % of the peak damping in surge and heave;
* ``hydrostatics``: displaced volume and hydrostatic stiffness C33, C44, C55 against the
  analytic values of the geometry (:func:`floatmoor.hydro.geometry.geometry_properties`)
  within 1 %; for a hull read from a mesh file, against the independent integration of the
  same hull recorded at build time (:func:`mesh_reference_properties`).

A check that cannot apply says so instead of passing silently (``CheckResult.applicable``
False, the reason in its detail; ``hydro check`` shows "n/a"): ``haskind`` on a database
without excitation forces or whose wave directions do not give the integral over the circle
(:func:`haskind_requirement`: built or imported alike; ``floatmoor check`` states it before a
build), ``hydrostatics`` on one without a geometry (imported from another program's files,
whose hydrostatics are the files' own).
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass

import numpy as np
import xarray as xr

from floatmoor.case.schema import Column, CylinderGeometry, FloaterGeometry, Member, \
    MeshGeometry, SemisubmersibleGeometry
from floatmoor.hydro.complex_values import merge_complex
from floatmoor.hydro.geometry import geometry_properties
from floatmoor.hydro.radiation import added_mass_from_kernel, radiation_kernel
from floatmoor.hydro.values import value_problems
from floatmoor.terminal_text import shown

__all__ = [
    "CheckResult", "run_checks", "check_values", "describe_failures", "haskind_damping",
    "geometry_from_dataset", "mesh_reference_properties", "haskind_requirement",
    "finer_frequencies",
    "RECIPROCITY_TOLERANCE", "PSD_TOLERANCE", "KRAMERS_KRONIG_TOLERANCE",
    "KERNEL_DECAY_THRESHOLD", "HASKIND_TOLERANCE", "HYDROSTATICS_TOLERANCE",
    "HASKIND_POINTWISE_REPORT", "NEGLIGIBLE_DOF", ]

#: |A_ij - A_ji| and |B_ij - B_ji| relative to the matrix's scale for the pair (see
#: check_symmetry). Panel methods satisfy reciprocity only to discretisation error; 1 % of the
#: matrix's scale is far below any physically relevant asymmetry.
RECIPROCITY_TOLERANCE = 0.01
#: Most negative eigenvalue of B relative to its largest one (discretisation error, as above).
PSD_TOLERANCE = 0.01
#: Kramers-Kronig: A rebuilt from K(t) within 3 % of the BEM A
#: (docs/theory/hydrodynamics.md#database-integrity).
KRAMERS_KRONIG_TOLERANCE = 0.03
#: K(t) must fall below this fraction of its peak before the truncation time
#: (docs/theory/hydrodynamics.md#database-integrity).
KERNEL_DECAY_THRESHOLD = 1e-3
#: Haskind relation: damping from the excitation within 5 % of the BEM damping
#: (docs/theory/hydrodynamics.md#database-integrity).
HASKIND_TOLERANCE = 0.05
#: The Haskind check also reports (does not test) the pointwise relative error where B_ii is
#: at least this fraction of its peak.
HASKIND_POINTWISE_REPORT = 0.5
#: Displacement and hydrostatic stiffness against the analytic geometry within 1 %
#: (docs/theory/hydrodynamics.md#database-integrity).
HYDROSTATICS_TOLERANCE = 0.01
#: A DOF whose largest added mass is below this fraction of the largest diagonal added mass
#: of its kind (translation, rotation) has no hydrodynamics to check (yaw of a cylinder).
NEGLIGIBLE_DOF = 1e-6

_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")


@dataclass(frozen=True)
class CheckResult:
    """Outcome of one check: ``worst`` is compared with ``tolerance`` (smaller is better).

    A check that cannot apply to the database (``applicable`` False: the Haskind relation
    without excitation forces, the hydrostatics without a geometry) says why in ``detail``;
    it does not fail (``passed`` True, ``worst`` NaN).
    """

    name: str
    passed: bool
    worst: float
    tolerance: float
    detail: str
    applicable: bool = True

    def as_dict(self) -> dict:
        """JSON-ready."""
        out = asdict(self)
        out.update(passed=bool(self.passed), worst=float(self.worst),
                   tolerance=float(self.tolerance), applicable=bool(self.applicable))
        return out

    @classmethod
    def not_applicable(cls, name: str, tolerance: float, reason: str) -> "CheckResult":
        """A check that cannot apply, and why."""
        return cls(name, True, math.nan, tolerance, reason, applicable=False)


def geometry_from_dataset(ds: xr.Dataset) -> FloaterGeometry:
    """The floater geometry recorded in a database."""
    g = json.loads(ds.attrs["geometry_json"])
    if g["kind"] == "mesh":  # no resolved path: the file is not needed to check a database
        return MeshGeometry(file=g["file"], sha256=g["sha256"], format=g["format"],
                            length_unit=g["length_unit"], position=tuple(g["position"]),
                            symmetry=tuple(g["symmetry"]))
    if g["kind"] == "cylinder":
        return CylinderGeometry(diameter=g["diameter"], draft=g["draft"], height=g["height"],
                                draft_from_mass=False)
    return SemisubmersibleGeometry(
        columns=tuple(Column(**c) for c in g["columns"]),
        members=tuple(Member(start=tuple(m["start"]), end=tuple(m["end"]),
                             diameter=m["diameter"]) for m in g["members"]))


def _matrices(ds: xr.Dataset, name: str) -> np.ndarray:
    return ds[name].transpose("omega", "radiating_dof", "influenced_dof").values


def _active_dofs(ds: xr.Dataset) -> list[int]:
    a = np.abs(np.diagonal(_matrices(ds, "added_mass"), axis1=1, axis2=2)).max(axis=0)
    out = []
    for i in range(6):
        group = a[:3] if i < 3 else a[3:]
        if a[i] > NEGLIGIBLE_DOF * group.max():
            out.append(i)
    return out


def check_symmetry(ds: xr.Dataset) -> CheckResult:
    """|M_ij - M_ji| relative to the matrix's scale for the pair, sqrt(D_i D_j) (units of
    M_ij), D_i the largest diagonal term of i's kind (translations, rotations): at each
    frequency for the added mass, the band maxima for the damping (which vanishes at low
    frequency, where its relative noise says nothing).

    Not the pair's own sqrt(M_ii M_jj): a DOF with hardly any radiation (the yaw of an
    axisymmetric hull, B_66 ~ 0) made a coupling's round-off noise look large (B_36 = -446
    N s against B_11 = 6.6e5 N s/m read as a failure); against the matrix's scale it is the
    0.07 % it is. A real asymmetry of a term that matters is as large against either."""
    active = _active_dofs(ds)
    worst, where = 0.0, ""
    for name in ("added_mass", "radiation_damping"):
        m = _matrices(ds, name)
        diag = np.abs(np.diagonal(m, axis1=1, axis2=2))
        if name == "radiation_damping":
            diag = np.broadcast_to(diag.max(axis=0), diag.shape)
        kinds = np.concatenate([np.repeat(diag[:, :3].max(axis=1, keepdims=True), 3, axis=1),
                                np.repeat(diag[:, 3:].max(axis=1, keepdims=True), 3, axis=1)],
                               axis=1)
        for a in active:
            for b in active:
                if b <= a:
                    continue
                asym = np.abs(m[:, a, b] - m[:, b, a]) / np.sqrt(kinds[:, a] * kinds[:, b])
                i = int(np.argmax(asym))
                if asym[i] > worst:
                    worst = float(asym[i])
                    where = (f"{name} {_DOFS[a]}-{_DOFS[b]} at omega = "
                             f"{ds['omega'].values[i]:.4g} rad/s")
    return CheckResult("symmetry", worst <= RECIPROCITY_TOLERANCE, worst, RECIPROCITY_TOLERANCE,
                       f"largest |M_ij - M_ji| / sqrt(D_i D_j) (D: the largest diagonal term of "
                       f"the DOF's kind): {worst:.2e} ({where})")


def check_damping_psd(ds: xr.Dataset) -> CheckResult:
    b = _matrices(ds, "radiation_damping")
    worst, where = 0.0, 0.0
    for i, m in enumerate(b):
        ev = np.linalg.eigvalsh(0.5 * (m + m.T))
        ratio = max(0.0, -ev.min() / ev.max()) if ev.max() > 0 else 0.0
        if ratio > worst:
            worst, where = ratio, ds["omega"].values[i]
    return CheckResult("damping_psd", worst <= PSD_TOLERANCE, worst, PSD_TOLERANCE,
                       f"most negative eigenvalue of B / largest: {worst:.2e}"
                       + (f" at omega = {where:.4g} rad/s" if worst > 0 else ""))


def kramers_kronig(ds: xr.Dataset, kernel=None) -> dict[int, np.ndarray]:
    """Relative difference (A_rebuilt - A_BEM) / |A_BEM| per active diagonal DOF."""
    kernel = kernel or radiation_kernel(ds)
    omega = ds["omega"].values
    a = _matrices(ds, "added_mass")
    out = {}
    for i in _active_dofs(ds):
        rebuilt = added_mass_from_kernel(kernel.time, kernel.kernel[:, i, i],
                                         kernel.added_mass_infinite[i, i], omega)
        out[i] = (rebuilt - a[:, i, i]) / np.abs(a[:, i, i])
    return out


def check_kramers_kronig(ds: xr.Dataset, kernel=None) -> CheckResult:
    errors = kramers_kronig(ds, kernel)
    omega = ds["omega"].values
    worst, where = 0.0, ""
    for i, err in errors.items():
        j = int(np.argmax(np.abs(err)))
        if abs(err[j]) >= worst:
            worst, where = float(abs(err[j])), f"{_DOFS[i]} at omega = {omega[j]:.4g} rad/s"
    return CheckResult("kramers_kronig", worst <= KRAMERS_KRONIG_TOLERANCE, worst,
                       KRAMERS_KRONIG_TOLERANCE,
                       f"largest |A_KK - A_BEM| / |A_BEM| over {omega[0]:.3g}-{omega[-1]:.3g} "
                       f"rad/s: {worst:.2%} ({where})")


def kernel_decay_times(ds: xr.Dataset, kernel=None) -> dict[int, float]:
    """Per active DOF: the time from which |K_ii| stays below the threshold (inf if never)."""
    kernel = kernel or radiation_kernel(ds)
    out = {}
    for i in _active_dofs(ds):
        k = np.abs(kernel.kernel[:, i, i])
        above = np.nonzero(k >= KERNEL_DECAY_THRESHOLD * k.max())[0]
        last = above[-1] if len(above) else 0
        out[i] = float(kernel.time[last + 1]) if last + 1 < len(kernel.time) else math.inf
    return out


def finer_frequencies(omega: np.ndarray) -> np.ndarray:
    """The frequencies to add for a kernel that does not decay before its truncation time
    pi / (median step) (:func:`floatmoor.hydro.radiation.truncation_time`): the midpoints of
    the present steps, which halve the step and double the truncation time [rad/s]."""
    omega = np.asarray(omega, dtype=float)
    return 0.5 * (omega[1:] + omega[:-1])


def _frequency_list(values: np.ndarray) -> str:
    """Frequencies for a message: all of them when few, else the first and last and a count."""
    if len(values) <= 8:
        return ", ".join(f"{w:.4g}" for w in values)
    return f"{len(values)} from {values[0]:.4g} to {values[-1]:.4g}"


def check_kernel_decay(ds: xr.Dataset, kernel=None) -> CheckResult:
    kernel = kernel or radiation_kernel(ds)
    times = kernel_decay_times(ds, kernel)
    t_max = kernel.truncation_time
    worst_dof = max(times, key=lambda i: times[i])
    worst = times[worst_dof] / t_max
    text = ", ".join(f"{_DOFS[i]} {t:.3g} s" for i, t in times.items())
    detail = (f"|K_ii| < {KERNEL_DECAY_THRESHOLD:g} x peak from: {text}; truncation time "
              f"{t_max:.4g} s (pi / the median frequency step)")
    if not worst < 1.0:
        omega = ds["omega"].values
        added = finer_frequencies(omega)
        detail += (f"; to double it, halve the frequency step: add the midpoints "
                   f"{_frequency_list(added)} rad/s ({len(omega) + len(added)} frequencies "
                   "in all) to [hydro] frequencies, and again while it fails")
    return CheckResult("kernel_decay", worst < 1.0, worst, 1.0, detail)


def haskind_damping(ds: xr.Dataset, dof: int) -> np.ndarray:
    """B_jj from the excitation forces: k / (8 pi rho g c_g) int_0^2pi |X_j(beta)|^2 d beta.

    The directions must be either the single direction of an axisymmetric body (cylinder;
    |X_1(beta)| = |X_1(0)| |cos beta|, |X_3| constant), or span [0, pi] (or [-pi, 0]) evenly
    on a body symmetric about y = 0 (|X_j(-beta)| = |X_j(beta)| for j = surge, heave,
    pitch), in which case the periodic trapezoidal rule is used on the mirrored directions,
    or cover the full circle evenly (any body: the periodic trapezoidal rule on them).
    """
    x = merge_complex(ds, "excitation_force").transpose("omega", "wave_direction",
                                                        "influenced_dof").values[:, :, dof]
    omega = ds["omega"].values
    k = ds["wavenumber"].values
    rho, g = float(ds.attrs["water_density"]), float(ds.attrs["gravity"])
    depth = math.inf if ds.attrs["bem_water_depth"] == "infinite" \
        else float(ds.attrs["bem_water_depth"])
    kh = k * depth if math.isfinite(depth) else np.full_like(k, np.inf)
    factor = np.where(np.isfinite(kh), 2 * kh / np.sinh(np.minimum(2 * kh, 700.0)), 0.0)
    cg = 0.5 * omega / k * (1.0 + factor)
    beta = ds["wave_direction"].values
    x2 = np.abs(x) ** 2
    kind = str(ds.attrs.get("geometry_kind", ""))
    need = haskind_requirement(kind, _mirror_symmetric(ds), beta)
    if need is not None:
        raise ValueError(need)
    if kind == "cylinder":
        if dof in (0, 1, 3, 4):
            integral = x2[:, 0] * math.pi  # int cos^2 = pi
        else:
            integral = x2[:, 0] * 2.0 * math.pi
    else:
        step = np.diff(beta)
        even, half, _ = _direction_span(beta)
        if even and half:
            # periodic trapezoid over [0, 2 pi) with the mirrored half: 2 * (sum of
            # interior) + end points once each
            integral = step[0] * (x2[:, 0] + x2[:, -1] + 2.0 * x2[:, 1:-1].sum(axis=1))
        else:
            integral = step[0] * x2.sum(axis=1)
    return k / (8.0 * math.pi * rho * g * cg) * integral


def _direction_span(beta: np.ndarray) -> tuple[bool, bool, bool]:
    """(evenly spaced, spanning [0, pi] or [-pi, 0], evenly covering the full circle)."""
    beta = np.asarray(beta, dtype=float)
    step = np.diff(beta)
    even = len(beta) > 1 and bool(np.allclose(step, step[0]))
    # [0, pi] or [-pi, 0] (a 180 deg yaw of the former): each mirrors to the full circle
    half = len(beta) > 1 and ((abs(beta[0]) < 1e-9 and abs(beta[-1] - math.pi) < 1e-9) or
                              (abs(beta[0] + math.pi) < 1e-9 and abs(beta[-1]) < 1e-9))
    full = even and abs(beta[-1] + step[0] - beta[0] - 2.0 * math.pi) < 1e-9
    return even, half, full


def haskind_requirement(kind: str, mirror_symmetric: bool, directions) -> str | None:
    """Why the Haskind check cannot integrate over the circle of wave directions, with what to
    change; None when it can (:func:`haskind_damping`).

    Parameters
    ----------
    kind
        The geometry's kind ("cylinder", "semisubmersible", "mesh", or "" for files imported
        from another program).
    mirror_symmetric
        Whether the hull is taken as symmetric about y = 0 (a mesh declaring "xz"; the
        parametric kinds and imported files are).
    directions
        The wave directions [rad].
    """
    if kind == "cylinder":
        return None  # axisymmetric: one direction gives every other
    even, half, full = _direction_span(np.asarray(directions, dtype=float))
    if even and half and mirror_symmetric:
        return None
    if full:
        return None
    if even and half:
        return ("the Haskind check on directions spanning 0 to 180 deg needs a hull "
                "symmetric about y = 0: declare the mesh's \"xz\" symmetry (the file holding "
                "the half y >= 0), or give directions evenly covering the full circle (e.g. "
                "0, 30, ..., 330)")
    symmetric = "" if mirror_symmetric or kind != "mesh" else \
        " with the mesh's \"xz\" symmetry declared (the file holding the half y >= 0)"
    return ("the Haskind check integrates the excitation over the circle of wave directions: "
            f"give directions evenly spanning 0 to 180 deg (e.g. 0, 30, ..., 180){symmetric}, "
            "or directions evenly covering the full circle (e.g. 0, 30, ..., 330)")


def _mirror_symmetric(ds: xr.Dataset) -> bool:
    """Whether the hull is taken as symmetric about y = 0 (the parametric kinds, whose
    Haskind check has always mirrored a 0-180 deg span, imported files, whose symmetry is
    unknown to us and which the check may only approximate, and mesh hulls that declare
    the "xz" plane)."""
    if ds.attrs.get("geometry_kind") != "mesh":
        return True
    try:
        symmetry = json.loads(ds.attrs.get("geometry_json", "{}")).get("symmetry", [])
    except json.JSONDecodeError:
        return False
    return "xz" in symmetry


def check_haskind(ds: xr.Dataset) -> CheckResult:
    """|B_Haskind - B| relative to the DOF's peak damping, at every frequency (surge, heave).

    The BEM damping is the small imaginary part of the radiation impedance: its absolute
    error scales with the impedance, not with B, so where B nearly cancels (the semisub's
    heave damping passes through zero near 0.42 rad/s) its pointwise relative error grows
    without bound while the excitation force stays accurate (there, |X3| agrees with WAMIT
    within 2 % while B33 differs from WAMIT's by 39 %). The peak is the scale at which
    "within 5 %" means something at every frequency; the pointwise error where B is at least
    half its peak is reported too.
    """
    if "excitation_force" not in ds.variables:
        return CheckResult.not_applicable(
            "haskind", HASKIND_TOLERANCE, "no excitation forces in the database"
            + (f" (imported from {ds.attrs['source']} files without them)"
               if ds.attrs.get("source", "capytaine") != "capytaine" else ""))
    omega = ds["omega"].values
    b = _matrices(ds, "radiation_damping")
    worst, where, pointwise = 0.0, "", 0.0
    for i in (0, 2):
        bem = b[:, i, i]
        if not bem.max() > 0.0:  # no radiation at all (or negative damping): nothing to scale by
            return CheckResult("haskind", False, math.inf, HASKIND_TOLERANCE,
                               f"{_DOFS[i]} radiation damping is nowhere positive (largest "
                               f"{bem.max():.3g})")
        need = haskind_requirement(str(ds.attrs.get("geometry_kind", "")),
                                   _mirror_symmetric(ds), ds["wave_direction"].values)
        if need is not None:  # n/a, built or imported alike (floatmoor check says so first)
            source = ds.attrs.get("source", "capytaine")
            whose = "the database's" if source == "capytaine" else f"the {source} files'"
            return CheckResult.not_applicable(
                "haskind", HASKIND_TOLERANCE, f"{need}; {whose} directions are " + ", ".join(
                    f"{d:g}" for d in np.degrees(ds["wave_direction"].values)) + " deg")
        haskind = haskind_damping(ds, i)
        diff = np.abs(haskind - bem)
        err = diff / bem.max()
        j = int(np.argmax(err))
        if err[j] >= worst:
            worst, where = float(err[j]), f"{_DOFS[i]} at omega = {omega[j]:.4g} rad/s"
        strong = bem >= HASKIND_POINTWISE_REPORT * bem.max()
        if np.any(strong):
            pointwise = max(pointwise, float((diff[strong] / bem[strong]).max()))
    return CheckResult("haskind", worst <= HASKIND_TOLERANCE, worst, HASKIND_TOLERANCE,
                       f"largest |B_Haskind - B| / peak B (surge, heave): {worst:.2%} ({where}); "
                       f"pointwise |B_Haskind - B| / B where B >= half its peak: "
                       f"{pointwise:.2%}")


def mesh_reference_properties(ds: xr.Dataset) -> dict[str, float]:
    """The reference hydrostatics of a hull read from a mesh file, recorded at build time
    (attribute ``mesh_reference_json``, :func:`floatmoor.hydro.mesh_checks.
    reference_hydrostatics`).

    A mesh has no analytic geometry. The database's hydrostatics are integrals of f n_z over
    the hull panels (floatmoor.hydro.hydrostatics); the reference integrates the same hull
    along paths that share no formula with them: the volume from int x n_x dS and
    int y n_y dS, the centre of buoyancy's height from int x z n_x dS and int y z n_y dS,
    the waterplane area and second moments from line integrals around the waterline
    (Green's theorem). Both are exact for the polyhedral hull, so they agree to round-off on a
    closed, outward-oriented hull and part where the hull is open or the database's values
    were changed. capytaine's own hydrostatics were not chosen: their one-point panel
    quadrature is not exact for the waterplane's second moments (-0.75 % in C44 of the
    buoy's buoyancy part; hydrostatics module docstring), too near the 1 % tolerance.

    Raises
    ------
    ValueError
        When the database records no reference.
    """
    try:
        return json.loads(ds.attrs["mesh_reference_json"])
    except (KeyError, json.JSONDecodeError, TypeError):
        raise ValueError("the database records no reference hydrostatics of its mesh "
                         "(mesh_reference_json)") from None


def hydrostatics_errors(ds: xr.Dataset) -> dict[str, float]:
    """Relative differences of the database hydrostatics from the analytic geometry (from
    the recorded reference integration for a mesh hull: :func:`mesh_reference_properties`)."""
    geometry = geometry_from_dataset(ds)
    rc = ds["rotation_center"].values
    rho, g = float(ds.attrs["water_density"]), float(ds.attrs["gravity"])
    c = ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values
    if isinstance(geometry, MeshGeometry):
        ref = mesh_reference_properties(ds)
        vz = ref["disp_volume"] * (ref["center_of_buoyancy_z"] - rc[2])
        analytic = {
            "disp_volume": ref["disp_volume"],
            "C33": rho * g * ref["waterplane_area"],
            "C44": rho * g * (ref["waterplane_yy"] + vz),
            "C55": rho * g * (ref["waterplane_xx"] + vz),
        }
    else:
        props = geometry_properties(geometry, reference_xy=(float(rc[0]), float(rc[1])))
        vz = props.volume * (props.centre_of_buoyancy[2] - rc[2])
        analytic = {
            "disp_volume": props.volume,
            "C33": rho * g * props.waterplane_area,
            "C44": rho * g * (props.waterplane_inertia[0] + vz),
            "C55": rho * g * (props.waterplane_inertia[1] + vz),
        }
    values = {"disp_volume": float(ds["disp_volume"]), "C33": c[2, 2], "C44": c[3, 3],
              "C55": c[4, 4]}
    return {k: (values[k] - analytic[k]) / abs(analytic[k]) for k in analytic}


def check_hydrostatics(ds: xr.Dataset) -> CheckResult:
    errors = hydrostatics_errors(ds)
    name = max(errors, key=lambda k: abs(errors[k]))
    worst = abs(errors[name])
    text = ", ".join(f"{k} {v:+.3%}" for k, v in errors.items())
    against = "the recorded independent integration of the mesh" \
        if ds.attrs.get("geometry_kind") == "mesh" else "the analytic geometry"
    return CheckResult("hydrostatics", worst <= HYDROSTATICS_TOLERANCE, worst,
                       HYDROSTATICS_TOLERANCE, f"against {against}: {text}")


def run_checks(ds: xr.Dataset) -> list[CheckResult]:
    """All checks on one database, in the order of the module docstring (their names are
    :data:`floatmoor.case.schema.HYDRO_CHECKS`).

    Parameters
    ----------
    ds
        The database (:func:`floatmoor.hydro.database.read_database`).

    Returns
    -------
    list of CheckResult
        One result per check, passed or not (:func:`describe_failures`)."""
    try:
        kernel = radiation_kernel(ds)
    except (ValueError, ArithmeticError, np.linalg.LinAlgError) as err:
        kernel = err
    checks = [("symmetry", RECIPROCITY_TOLERANCE, lambda: check_symmetry(ds)),
              ("damping_psd", PSD_TOLERANCE, lambda: check_damping_psd(ds)),
              ("kramers_kronig", KRAMERS_KRONIG_TOLERANCE,
               lambda: check_kramers_kronig(ds, _kernel(kernel))),
              ("kernel_decay", 1.0, lambda: check_kernel_decay(ds, _kernel(kernel))),
              ("haskind", HASKIND_TOLERANCE, lambda: check_haskind(ds)),
              ("hydrostatics", HYDROSTATICS_TOLERANCE, lambda: check_hydrostatics(ds))]
    results = []
    for name, tolerance, check in checks:
        if name == "hydrostatics" and "geometry_json" not in ds.attrs:
            results.append(CheckResult.not_applicable(
                name, tolerance, "no geometry to compare with: the hydrostatics are "
                f"the {ds.attrs.get('source', 'source')} files' own"))
            continue
        # values no BEM solver writes (an edited file) can break a check's arithmetic: that
        # is a failed check, reported in its row, not a traceback
        try:
            with np.errstate(all="raise", under="ignore"):
                results.append(check())
        except (ValueError, ArithmeticError, np.linalg.LinAlgError, KeyError, TypeError,
                AttributeError) as err:
            # KeyError, TypeError, AttributeError: recorded attributes (geometry_json, mesh
            # records) missing an entry or of another shape; their text is the file's: shown
            what = shown(f"missing {err}" if isinstance(err, KeyError) else str(err), 200)
            results.append(CheckResult(name, False, math.inf, tolerance,
                                       f"cannot be evaluated on these values ({what})"))
    return results


def _kernel(kernel):
    if isinstance(kernel, Exception):
        raise ValueError(f"no radiation kernel: {kernel}")
    return kernel


def check_values(ds: xr.Dataset) -> CheckResult:
    """The physical-value checks of :mod:`floatmoor.hydro.values` as a row of ``hydro check``
    (never accepted: a run refuses a database failing them)."""
    problems = value_problems(ds)
    return CheckResult("values", not problems, float(len(problems)), 0.0,
                       "; ".join(problems) if problems else "finite, moderate, physically "
                       "possible (volume, C33 > 0; A_inf PSD; B_ii >= 0)")


def describe_failures(results: list[CheckResult]) -> str:
    """``kernel_decay (worst inf, tolerance 1), ...``: the checks named with their values."""
    return ", ".join(f"{r.name} (worst {r.worst:.3g}, tolerance {r.tolerance:.3g})"
                     for r in results)
