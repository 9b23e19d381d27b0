"""Mean wave drift coefficients from the first-order BEM solution
(docs/theory/hydrodynamics.md#mean-wave-drift).

The mean second-order force and moment on the floater in a regular wave of unit amplitude,
with the floater moving by its RAOs (:mod:`floatmoor.hydro.rao`: with the mooring's linearised
stiffness and any linear damping), in capytaine's e^{-i omega t} convention (the mean of
Re(a e^{-i omega t}) Re(b e^{-i omega t}) is Re(a conj(b)) / 2). Two independent routes:

* **far field** (Maruo, Newman: momentum conservation), surge, sway and yaw, by capytaine's
  :func:`capytaine.post_pro.mean_drift_force.far_field_mean_drift_force` from the Kochin
  functions of the diffracted and radiated waves (:func:`capytaine.post_pro.kochin.compute_kochin`,
  :data:`KOCHIN_ANGLES` angles), finite or infinite depth;
* **near field** (Pinkster: pressure integration over the mean wetted hull), all six DOFs, by
  :func:`near_field_drift` (vectorised NumPy: no time loop), the sum of

  I    relative wave elevation at the waterline: -rho g / 4 oint |zeta_r|^2 n dl;
  II   quadratic velocity (Bernoulli): rho / 4 int |grad phi|^2 n dS;
  III  first-order pressure gradient over the first-order displacement X of the panel:
       -1/2 Re int (X . conj(grad p1)) n dS, p1 = i omega rho phi;
  IV   rotation of the first-order pressure force F1 (moments: and the moment of F1 about the
       displaced centre): 1/2 Re(alpha x conj F1), 1/2 Re(xi x conj F1 + alpha x conj M1),
       with F1, M1 integrated from p1 - rho g X_z on the mean hull;
  V    hydrostatic pressure on the second-order part of the rigid motion (rotation vector
       convention: X2 = alpha x (alpha x r) / 2).

  Moments are about the rotation centre; the normal n points into the fluid. The waterline
  term takes the hull vertical at the waterline (wall-sided), as Pinkster's formula does.

The velocity on the hull comes from the source distribution of capytaine's indirect method:
its tangential part is the principal-value integral of the sources (the jump of the single
layer is normal), its normal part is the body's normal velocity (the boundary condition). The
drift solves are therefore separate from the database's (direct method) solves, with the
sources kept, on the same hull meshed finer towards the still water line
(:func:`floatmoor.hydro.drift_build.drift_waterline_panel_size`): the waterline and velocity
terms, which cancel each other in large part, and the Kochin functions' e^{kz} vary fastest
there.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
from numpy.typing import NDArray

__all__ = ["KOCHIN_ANGLES", "DRIFT_TERMS", "Hull", "hull_panels", "near_field_drift",
           "DriftResult", "solve_drift", "far_field_from_kochin", "POINTS_PER_BLOCK"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
#: Angles of the Kochin functions over [0, 2 pi] (plus one step beyond each end, as
#: capytaine's far-field function needs the wave directions strictly inside): a 1 degree step,
#: over which the Kochin functions of the tested bodies (kR up to 7) vary smoothly; with it the
#: far field met the MacCamy-Fuchs drift and the fixed body's energy identity to the mesh's
#: accuracy (tests/hydro/test_drift.py). Not refined further: untested.
KOCHIN_ANGLES = 361
#: The near-field terms, in the order of the ``near_field_terms`` attribute.
DRIFT_TERMS = ("waterline", "velocity", "pressure_gradient", "rotation", "hydrostatic")
#: Points per block of the velocity influence matrices (memory: points x panels x 3 complex).
POINTS_PER_BLOCK = 600
#: A vertex on the still water line within this fraction of the hull's size [-] (meshes are
#: written with z = 0 exactly; 1e-9 allows for the translation to the reference point).
_WATERLINE_TOLERANCE = 1e-9


@dataclass
class Hull:
    """The mean wetted hull's panels (centres, unit normals into the fluid, areas) and its
    waterline segments (midpoints at z = 0, lengths, horizontal unit normals)."""

    centres: NDArray[np.float64]
    normals: NDArray[np.float64]
    areas: NDArray[np.float64]
    waterline_points: NDArray[np.float64]
    waterline_lengths: NDArray[np.float64]
    waterline_normals: NDArray[np.float64]
    #: (3, n, n) sparse operators giving the tangential gradient at each panel centre from
    #: values at the panel centres (:func:`surface_gradient`)
    gradient: tuple = ()


def hull_panels(mesh, hull_mask: NDArray[np.bool_] | None = None) -> Hull:
    """The :class:`Hull` of a capytaine mesh (``hull_mask``: the hull panels of a mesh
    including a lid); waterline segments are the panel edges with both ends at z = 0."""
    merged = mesh.merged() if hasattr(mesh, "merged") else mesh
    centres = np.asarray(merged.faces_centers, float)
    normals = np.asarray(merged.faces_normals, float)
    areas = np.asarray(merged.faces_areas, float)
    vertices = np.asarray(merged.vertices, float)
    faces = np.asarray(merged.faces, int)
    mask = np.ones(len(faces), bool) if hull_mask is None else np.asarray(hull_mask, bool)
    size = float(np.ptp(vertices, axis=0).max()) if len(vertices) else 1.0
    on_surface = np.abs(vertices[:, 2]) <= _WATERLINE_TOLERANCE * size
    points, lengths, wl_normals, owners = [], [], [], []
    for f in np.nonzero(mask)[0]:
        face = faces[f]
        for a, b in zip(face, np.roll(face, -1)):
            if a == b or not (on_surface[a] and on_surface[b]):
                continue
            length = float(np.linalg.norm(vertices[b] - vertices[a]))
            horizontal = normals[f, :2]
            norm = float(np.linalg.norm(horizontal))
            if length <= 0.0 or norm <= 0.0:
                continue
            mid = 0.5 * (vertices[a] + vertices[b])
            points.append([mid[0], mid[1], 0.0])
            lengths.append(length)
            wl_normals.append([horizontal[0] / norm, horizontal[1] / norm, 0.0])
            owners.append(int(np.count_nonzero(mask[:f])))
    hull_faces = faces[mask]
    wl_points = np.array(points).reshape(-1, 3)
    return Hull(centres[mask], normals[mask], areas[mask], wl_points,
                np.array(lengths), np.array(wl_normals).reshape(-1, 3),
                surface_gradient(vertices, hull_faces, centres[mask], normals[mask], size,
                                 wl_points, np.array(owners, int)))


def surface_gradient(vertices: NDArray, faces: NDArray, centres: NDArray, normals: NDArray,
                     size: float, extra_points: NDArray | None = None,
                     extra_owners: NDArray | None = None) -> tuple:
    """Sparse operators (Gx, Gy, Gz) giving the tangential gradient of a field known at the
    panel centres (and at ``extra_points``, each on the edge of panel ``extra_owners``: the
    waterline points), columns in that order: on each panel, the least-squares plane through
    its neighbours' values (panels sharing a vertex, vertices identified by position to 1e-9
    of the hull size, and its own extra points) in the panel's tangent plane. Exact for a
    linear field; second-order accurate on the symmetric stencils of a structured mesh."""
    from scipy.sparse import csr_matrix

    key = np.round(vertices / (1e-9 * size)).astype(np.int64)
    _, ident = np.unique(key, axis=0, return_inverse=True)
    ident = ident.ravel()
    panels_of: dict[int, set[int]] = {}
    for f, face in enumerate(faces):
        for v in set(ident[face].tolist()):
            panels_of.setdefault(v, set()).add(f)
    rows, cols, vals = [[], [], []], [[], [], []], [[], [], []]
    n_faces = len(faces)
    extra = np.zeros((0, 3)) if extra_points is None else np.asarray(extra_points, float)
    extra_of: dict[int, list[int]] = {}
    for e, owner in enumerate([] if extra_owners is None else extra_owners):
        extra_of.setdefault(int(owner), []).append(e)
    every = np.concatenate([centres, extra])
    for f, face in enumerate(faces):
        nb = sorted(set().union(*(panels_of[v] for v in set(ident[face].tolist()))) - {f})
        nb += [n_faces + e for e in extra_of.get(f, [])]
        if len(nb) < 2:
            continue
        n = normals[f]
        d = every[nb] - centres[f]
        d = d - np.outer(d @ n, n)  # in the tangent plane
        # least squares g = (D^T D)^+ D^T (phi_nb - phi_f), D restricted to the plane
        weights = np.linalg.pinv(d.T @ d, rcond=1e-10) @ d.T  # (3, k)
        for a in range(3):
            rows[a].extend([f] * (len(nb) + 1))
            cols[a].extend(nb + [f])
            vals[a].extend(list(weights[a]) + [-float(weights[a].sum())])
    shape = (n_faces, n_faces + len(extra))
    return tuple(csr_matrix((vals[a], (rows[a], cols[a])), shape=shape) for a in range(3))


def _cross(a: NDArray, b: NDArray) -> NDArray:
    """Cross product over the last axis (complex allowed)."""
    return np.stack([a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1],
                     a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2],
                     a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]], axis=-1)


def _mean(a: NDArray, b: NDArray) -> NDArray:
    """Mean of the product of two harmonic amplitudes, elementwise: Re(a conj b) / 2."""
    return 0.5 * np.real(a * np.conj(b))


def near_field_drift(hull: Hull, *, omega: float, rho: float, g: float,
                     rotation_center: NDArray[np.float64], motion: NDArray[np.complex128],
                     potential: NDArray[np.complex128], velocity: NDArray[np.complex128],
                     waterline_potential: NDArray[np.complex128]
                     ) -> NDArray[np.float64]:
    """Mean drift force and moment (Pinkster's pressure integration), per unit wave
    amplitude squared, term by term.

    Parameters
    ----------
    hull
        Panels and waterline of the mean wetted hull.
    omega, rho, g
        Wave frequency [rad/s], water density [kg/m^3], gravity [m/s^2].
    rotation_center
        Point the moments are about and the rotations turn about [m].
    motion
        Complex RAO (6,) [m/m, rad/m] (zeros: a fixed body).
    potential, velocity
        Total first-order potential (incident + diffracted + radiated by ``motion``) at the
        panel centres (n,) [m^2/s] and its gradient (n, 3) [m/s] per unit wave amplitude.
    waterline_potential
        The total potential at the waterline points (w,).

    Returns
    -------
    ndarray (5, 6)
        Terms I-V (:data:`DRIFT_TERMS`) of (Fx, Fy, Fz, Mx, My, Mz) [N/m^2, N m/m^2]; their
        sum over the first axis is the mean drift.
    """
    c = np.asarray(rotation_center, float)
    xi, alpha = np.asarray(motion[:3]), np.asarray(motion[3:])
    n, ds = hull.normals, hull.areas[:, None]
    r = hull.centres - c
    rxn = _cross(r, n)
    disp = xi[None, :] + _cross(np.broadcast_to(alpha, r.shape), r)  # X1 at the panels
    out = np.zeros((5, 6))
    # I: relative wave elevation at the waterline (zeta = i omega phi / g)
    if len(hull.waterline_lengths):
        rw = hull.waterline_points - c
        disp_w = xi[None, :] + _cross(np.broadcast_to(alpha, rw.shape), rw)
        zeta_r = 1j * omega / g * waterline_potential - disp_w[:, 2]
        weight = (-0.25 * rho * g * np.abs(zeta_r) ** 2 * hull.waterline_lengths)[:, None]
        out[0, :3] = np.sum(weight * hull.waterline_normals, axis=0)
        out[0, 3:] = np.sum(weight * _cross(rw, hull.waterline_normals), axis=0)
    # II: quadratic velocity term of Bernoulli's pressure
    q = (0.25 * rho * np.sum(np.abs(velocity) ** 2, axis=1))[:, None] * ds
    out[1, :3] = np.sum(q * n, axis=0)
    out[1, 3:] = np.sum(q * rxn, axis=0)
    # III: first-order dynamic pressure gradient over the first-order displacement
    grad_p1 = 1j * omega * rho * velocity
    s = -np.sum(_mean(disp, grad_p1), axis=1)[:, None] * ds
    out[2, :3] = np.sum(s * n, axis=0)
    out[2, 3:] = np.sum(s * rxn, axis=0)
    # IV: rotation of the first-order force (dynamic + hydrostatic pressure on the mean hull)
    p1 = 1j * omega * rho * potential - rho * g * disp[:, 2]
    f1 = -np.sum(p1[:, None] * n * ds, axis=0)
    m1 = -np.sum(p1[:, None] * rxn * ds, axis=0)
    out[3, :3] = np.real(0.5 * _cross(alpha, np.conj(f1)))
    out[3, 3:] = np.real(0.5 * (_cross(xi, np.conj(f1)) + _cross(alpha, np.conj(m1))))
    # V: hydrostatic pressure p0 = -rho g z on the second-order rigid motion: the mean
    # second-order displacement X2 = alpha x (alpha x r) / 2, the mean second-order normal,
    # and the first-order displacement with the first-order turn of the normal
    ab = np.broadcast_to(alpha, r.shape)
    x2 = 0.25 * np.real(_cross(ab, _cross(np.conj(ab), r)))
    n2 = 0.25 * np.real(_cross(ab, _cross(np.conj(ab), n)))
    n1 = _cross(ab, n)
    p0 = (-rho * g * hull.centres[:, 2])[:, None] * ds
    hz = (rho * g * x2[:, 2])[:, None] * ds  # -(-rho g X2_z)
    out[4, :3] = np.sum(hz * n - p0 * n2, axis=0)
    x1n1 = 0.5 * np.real(_cross(disp, np.conj(n1)))
    out[4, 3:] = np.sum(hz * rxn - p0 * (_cross(x2, n) + x1n1 + _cross(r, n2)), axis=0)
    return out


@dataclass
class DriftResult:
    """Mean drift coefficients at the database's frequencies and directions."""

    far_field: NDArray[np.float64]  #: (omega, direction, 6): NaN for Heave, Roll, Pitch
    near_field: NDArray[np.float64]  #: (omega, direction, 6)
    near_field_terms: NDArray[np.float64]  #: (omega, direction, term, 6)
    kochin_diffraction: NDArray[np.complex128]  #: (omega, direction, theta)
    kochin_radiation: NDArray[np.complex128]  #: (omega, dof, theta)
    theta: NDArray[np.float64]
    seconds: float
    #: drift with the further RAOs of :func:`solve_drift`'s ``other_motions``
    others: list = dataclasses.field(default_factory=list)
    #: what the caller records of the mesh solved on (floatmoor.hydro.drift_build)
    mesh: dict = dataclasses.field(default_factory=dict)


def kochin_angles(count: int = KOCHIN_ANGLES) -> NDArray[np.float64]:
    """[0, 2 pi] in ``count - 1`` steps, extended by one step at each end."""
    step = 2.0 * math.pi / (count - 1)
    return np.linspace(-step, 2.0 * math.pi + step, count + 2)


def far_field_from_kochin(omega: NDArray, wavenumber: NDArray, directions: NDArray,
                          theta: NDArray, kochin_diffraction: NDArray, kochin_radiation: NDArray,
                          motion: NDArray, *, depth: float, rho: float, g: float
                          ) -> NDArray[np.float64]:
    """Far-field mean drift (omega, direction, 6) through capytaine's function (Surge, Sway,
    Yaw filled; the other DOFs NaN).

    In finite depth the Kochin functions are divided by tanh(kh) first
    (:func:`finite_depth_kochin_factor`): with capytaine 3.0.0's normalisation its far-field
    formula breaks the energy identity of a fixed body (scattered energy flux against the
    interference term) by exactly tanh(kh), and falls short of the MacCamy-Fuchs drift of a
    bottom-mounted cylinder by 29 % at kh = 1; with the factor both hold (to the mesh's
    accuracy), and the deep-water limit is unchanged.
    """
    import xarray as xr
    from capytaine.post_pro.mean_drift_force import far_field_mean_drift_force

    factor = finite_depth_kochin_factor(np.asarray(wavenumber, float), depth)[:, None, None]
    kochin_diffraction = kochin_diffraction * factor
    kochin_radiation = kochin_radiation * factor

    out = np.full((len(omega), len(directions), 6), np.nan)
    for b, beta in enumerate(directions):
        # one direction at a time: capytaine's function forms every pair of directions (the
        # cross terms of a bichromatic sea); the mean drift is the diagonal of that matrix
        ds = xr.Dataset({
            "kochin_diffraction": (("omega", "wave_direction", "theta"),
                                   kochin_diffraction[:, b:b + 1]),
            "kochin_radiation": (("omega", "radiating_dof", "theta"), kochin_radiation),
            "wavenumber": (("omega",), np.asarray(wavenumber, float)),
            "water_depth": depth, "rho": rho, "g": g,
        }, coords={"omega": omega, "wave_direction": [beta], "theta": theta,
                   "radiating_dof": list(DOFS)})
        x = xr.DataArray(motion[:, b:b + 1], dims=("omega", "wave_direction", "radiating_dof"),
                         coords={"omega": omega, "wave_direction": [beta],
                                 "radiating_dof": list(DOFS)})
        res = far_field_mean_drift_force(x, ds)
        for name, dof in (("drift_force_surge", 0), ("drift_force_sway", 1),
                          ("drift_force_yaw", 5)):
            out[:, b, dof] = np.real(res[name].values[:, 0, 0])
    return out


def finite_depth_kochin_factor(wavenumber: NDArray, depth: float) -> NDArray:
    """1 / tanh(kh) in finite depth, 1 in deep water (:func:`far_field_from_kochin`)."""
    k = np.asarray(wavenumber, float)
    if not math.isfinite(depth):
        return np.ones_like(k)
    return 1.0 / np.tanh(k * depth)


Progress = Callable[[int, int, float, float], None]


def solve_drift(body, *, omegas: NDArray, directions: NDArray, motion: NDArray,
                depth: float, rho: float, g: float, rotation_center: NDArray,
                progress: Progress | None = None, theta_count: int = KOCHIN_ANGLES,
                other_motions: tuple = ()) -> DriftResult:
    """Solve the radiation and diffraction problems with capytaine's indirect method (sources
    kept) and compute both drift routes.

    Parameters
    ----------
    body
        capytaine FloatingBody (hull, optional lid, rigid-body DOFs about ``rotation_center``).
    omegas, directions
        Frequencies [rad/s] and wave directions [rad].
    motion
        Complex RAO (omega, direction, 6) the body moves by.
    depth, rho, g
        Water depth (inf: deep), density, gravity.
    rotation_center
        The point (3,) [m] the rotational DOFs and the drift moments are about.
    progress
        Called after each frequency with (done, total, omega, seconds).
    theta_count
        Number of angles of the Kochin functions over the full circle (far-field route).
    other_motions
        Further RAOs (omega, direction, 6) to compute the drift with from the same solves
        (the result's ``others``: a DriftResult each, without Kochin functions).
    """
    import capytaine as cpt
    from capytaine.bem.airy_waves import airy_waves_potential
    from capytaine.post_pro.kochin import compute_kochin

    from floatmoor.hydro.build import _clear_capytaine_caches

    start = time.perf_counter()
    solver = cpt.BEMSolver(green_function=cpt.Delhommeau(
        finite_depth_prony_decomposition_method="python"), method="indirect")
    gf = solver.engine.green_function
    mesh_all = body.mesh_including_lid.merged() if hasattr(body.mesh_including_lid, "merged") \
        else body.mesh_including_lid
    hull_mask = np.asarray(body.hull_mask, bool)
    hull = hull_panels(body.mesh_including_lid, hull_mask)
    points = np.concatenate([hull.centres, hull.waterline_points])
    n_h = len(hull.centres)
    n_w, n_b = len(omegas), len(directions)
    theta = kochin_angles(theta_count)
    h_diff = np.zeros((n_w, n_b, len(theta)), complex)
    h_rad = np.zeros((n_w, 6, len(theta)), complex)
    motions = [motion, *other_motions]
    terms = np.zeros((len(motions), n_w, n_b, 5, 6))
    wavenumbers = np.zeros(n_w)
    common = dict(water_depth=depth, rho=rho, g=g)
    dof_motion = _dof_motion(hull, rotation_center)
    for i, omega in enumerate(omegas):
        t0 = time.perf_counter()
        results = []
        for dof in DOFS:
            results.append(solver.solve(cpt.RadiationProblem(
                body=body, radiating_dof=dof, omega=omega, **common), keep_details=True))
        problems = [cpt.DiffractionProblem(body=body, wave_direction=b, omega=omega, **common)
                    for b in directions]
        results += [solver.solve(p, keep_details=True) for p in problems]
        wavenumbers[i] = results[0].wavenumber
        sources = np.stack([np.asarray(r.sources) for r in results], axis=1)
        # on the hull: the solver's own potentials; at the waterline: the sources' potential
        phi = np.concatenate([
            np.stack([np.asarray(r.potential)[hull_mask] for r in results], axis=1),
            _potential(gf, mesh_all, points[n_h:], sources, wavenumbers[i], depth)])
        for j in range(6):
            h_rad[i, j] = compute_kochin(results[j], theta)
        for b, problem in enumerate(problems):
            h_diff[i, b] = compute_kochin(results[6 + b], theta)
            for s_, moving in enumerate(motions):
                x = moving[i, b]
                total_phi = airy_waves_potential(points, problem) + phi[:, 6 + b] \
                    + phi[:, :6] @ x
                total_grad = np.stack([op @ total_phi for op in hull.gradient], axis=1)
                # tangential: the surface gradient of the potential; normal: the body's
                normal_velocity = -1j * omega * (dof_motion @ x)  # velocity
                nn = hull.normals
                total_grad = total_grad - np.sum(total_grad * nn, axis=1)[:, None] * nn \
                    + normal_velocity[:, None] * nn
                terms[s_, i, b] = near_field_drift(
                    hull, omega=float(omega), rho=rho, g=g, rotation_center=rotation_center,
                    motion=x, potential=total_phi[:n_h], velocity=total_grad,
                    waterline_potential=total_phi[n_h:])
        _clear_capytaine_caches()  # the block-circulant cache grows per frequency
        if progress is not None:
            progress(i + 1, n_w, float(omega), time.perf_counter() - t0)
    seconds = time.perf_counter() - start
    out = []
    for s_, moving in enumerate(motions):
        far = far_field_from_kochin(np.asarray(omegas, float), wavenumbers,
                                    np.asarray(directions, float), theta, h_diff, h_rad,
                                    moving, depth=depth, rho=rho, g=g)
        out.append(DriftResult(far, terms[s_].sum(axis=2), terms[s_], h_diff, h_rad, theta,
                               seconds))
    out[0].others = out[1:]
    return out[0]


def _dof_motion(hull: Hull, rotation_center: NDArray) -> NDArray[np.float64]:
    """(n_hull, 6): the normal displacement of each hull panel per unit motion of each DOF."""
    r = hull.centres - np.asarray(rotation_center, float)
    out = np.zeros((len(r), 6))
    out[:, :3] = hull.normals
    out[:, 3:] = _cross(r, hull.normals)  # (e_k x r) . n = e_k . (r x n)
    return out


def _potential(gf, mesh, points: NDArray, sources: NDArray, wavenumber: float, depth: float
               ) -> NDArray:
    """Potential (points, s) of the source distributions ``sources`` (panels, s), in blocks
    of :data:`POINTS_PER_BLOCK` points."""
    phi = np.zeros((len(points), sources.shape[1]), complex)
    for lo in range(0, len(points), POINTS_PER_BLOCK):
        hi = min(lo + POINTS_PER_BLOCK, len(points))
        s, _ = gf.evaluate(points[lo:hi], mesh, free_surface=0.0, water_depth=depth,
                           wavenumber=wavenumber, adjoint_double_layer=True,
                           early_dot_product=True, diagonal_term_in_double_layer=False)
        phi[lo:hi] = np.asarray(s) @ sources
    return phi


def drift_attributes(result: DriftResult, conditions: dict[str, Any]) -> dict[str, Any]:
    """What a database records about its drift coefficients."""
    return {"kochin_angles": int(len(result.theta)), "seconds": float(result.seconds),
            "near_field_terms": list(DRIFT_TERMS), "bem_method": "indirect",
            **conditions}
