"""BEM runs with capytaine: a floater and its settings in, a hydrodynamic dataset out.

For each finite frequency the six radiation problems and one diffraction problem per wave
direction are solved on the hull with its lid (irregular frequencies); omega = infinity is
solved without the lid (docs/theory/hydrodynamics.md, practical note 1: the lid spoils A_inf) and omega = 0 only
in infinite depth (pitfall 2). The finite-depth Green function uses the "python" Prony
decomposition, the one that supports omega = infinity. The cache of block-circulant matrices
is cleared after every frequency (pitfall 5). Hydrostatics are integrated on the merged hull
mesh (pitfall 4) by :func:`floatmoor.hydro.hydrostatics.hull_hydrostatics`: the buoyancy (hull)
part only; the weight terms depend on the mass properties and are added by
:func:`floatmoor.hydro.radiation.hydrostatic_stiffness_total`.

A hull read from a file (``kind = "mesh"``) is checked before anything is solved
(:mod:`floatmoor.hydro.mesh_checks`): a hull that is not watertight below the waterline or
whose normals point inward is refused (:class:`floatmoor.io.bem_data.BemFileError`); the
panel-size and irregular-frequency findings are warnings, recorded with the file's name, hash
and panel counts in the database's attributes (``mesh_file_json``, ``mesh_checks_json``), as
is the independent hydrostatic integration its ``hydrostatics`` check compares with
(``mesh_reference_json``).

capytaine's "python" Prony decomposition of the finite-depth Green function draws the end of
its fitting range at random (up to 1 % past it, against a singular point), from an unseeded
generator: two builds of the same inputs differed by ~1e-5 in A and up to 3e-3 in A_inf. The
generator is reseeded (:data:`PRONY_SEED`) at the start of every run, so that a database is
reproducible from its inputs.

Conventions: capytaine's (DOF names Surge .. Yaw about ``rotation_center``, e^{-i omega t}
time dependence, wave direction 0 = waves travelling towards +x).
"""

from __future__ import annotations

import math
import time
from typing import Callable

import numpy as np
import xarray as xr

from floatmoor.case.schema import Environment, Floater, HydroSettings
from floatmoor.hydro.geometry import HullMesh, build_mesh
from floatmoor.hydro.hydrostatics import hull_hydrostatics

__all__ = ["DOFS", "BEM_METHOD", "BemResult", "run_bem", "lid_depth_for", "LID_KH",
           "wavenumber", "PRONY_SEED", "CheckedMesh", "checked_mesh"]

DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
#: capytaine's boundary integral formulation. "direct" (potential) rather than capytaine's
#: default "indirect" (sources): on the DeepCwind mesh the indirect method's heave damping
#: disagreed with its own excitation force (Haskind relation) by 29 % at 0.54 rad/s, where the
#: damping nearly cancels, against 3.4 % with the direct method (surge: 2.4 % and 1.2 %).
BEM_METHOD = "direct"
#: Largest wavenumber times lid depth that kept the lid harmless on the trial databases
#: (docs/theory/hydrodynamics.md, practical note 3: k d <= 0.15 worked; a lid at z = 0 or too deep spoiled the
#: damping at the top frequencies).
LID_KH = 0.15

#: Seed of capytaine's Prony-decomposition generator for every BEM run (module docstring).
PRONY_SEED = 16

Progress = Callable[[int, int, float, float], None]


def wavenumber(omega: float, depth: float, g: float) -> float:
    """Solution k of omega^2 = g k tanh(k h) (deep water when ``depth`` is inf) [rad/m]."""
    k = omega * omega / g
    if not math.isfinite(depth) or k * depth > 20.0:
        return k
    for _ in range(100):  # Newton on f(k) = g k tanh(kh) - omega^2 from the deep-water value
        th = math.tanh(k * depth)
        f = g * k * th - omega * omega
        df = g * th + g * k * depth * (1.0 - th * th)
        step = f / df
        k -= step
        if abs(step) < 1e-14 * k:
            break
    return k


def lid_depth_for(omega_max: float, depth: float, g: float) -> float:
    """Lid depth giving k d = :data:`LID_KH` at the top frequency [m]."""
    return LID_KH / wavenumber(omega_max, depth, g)


class CheckedMesh:
    """The hull mesh a BEM run solves on, after the checks made before solving."""

    def __init__(self, mesh: HullMesh, lid_depth: float | None, mesh_checks=None,
                 mesh_reference=None) -> None:
        self.mesh = mesh
        self.lid_depth = lid_depth
        self.mesh_checks = mesh_checks  #: list of mesh_checks.MeshCheck (a mesh file), or None
        self.mesh_reference = mesh_reference  #: mesh_checks.reference_hydrostatics, or None


def checked_mesh(floater: Floater, hydro: HydroSettings,
                 environment: Environment) -> CheckedMesh:
    """Mesh the floater as :func:`run_bem` does and, for a hull read from a file, read it and
    run the mesh checks, refusing a fatal failure: everything ``hydro build`` does before it
    solves (``floatmoor check`` runs it too).

    Raises
    ------
    floatmoor.io.bem_data.BemFileError
        A hull mesh file that cannot be read or fails a fatal check.
    """
    g = environment.gravity
    depth = math.inf if hydro.infinite_depth else environment.water_depth
    omegas = np.asarray(hydro.frequencies, dtype=float)
    lid_depth = None
    if hydro.lid:
        lid_depth = hydro.lid_depth if hydro.lid_depth is not None else \
            lid_depth_for(float(omegas.max()), depth, g)
    ref = np.asarray(floater.reference_point, dtype=float)
    mesh = build_mesh(floater.geometry, panel_size=hydro.panel_size,
                      reference_xy=(float(ref[0]), float(ref[1])), lid_depth=lid_depth,
                      symmetry=hydro.symmetry, radial_panels=hydro.radial_panels,
                      water_depth=environment.water_depth)
    if mesh.source is None:
        return CheckedMesh(mesh, lid_depth)
    from floatmoor.hydro.mesh_checks import refuse_failed, run_mesh_checks
    from floatmoor.io.bem_data import BemFileError

    vertices = np.asarray(mesh.full_hull.vertices, dtype=float)
    if not np.all(np.isfinite(vertices)):  # finite in the file, overflowing once placed
        raise BemFileError(floater.geometry.path, "vertices", "finite coordinates after "
                           "length_unit and position", "coordinates beyond the largest float")
    omega_max = float(omegas.max())
    with np.errstate(all="ignore"):  # extreme but finite hulls: the checks give inf or
        mesh_checks, mesh_reference = run_mesh_checks(  # nan figures, not numpy warnings
            mesh, omega_max=omega_max,
            wavelength=2.0 * math.pi / wavenumber(omega_max, depth, g), g=g,
            rotation_center=ref)
    refuse_failed(mesh_checks, floater.geometry.path)
    return CheckedMesh(mesh, lid_depth, mesh_checks, mesh_reference)


class BemResult:
    """Arrays of one BEM run (complex values as Python complex), with the mesh and timings."""

    def __init__(self, omega, directions, added_mass, damping, fk, diffraction, a_inf, a_zero,
                 hydrostatics, mesh: HullMesh, lid_depth, seconds, bem_depth,
                 mesh_checks=None, mesh_reference=None):
        self.omega = omega
        self.directions = directions
        self.added_mass = added_mass
        self.radiation_damping = damping
        self.froude_krylov = fk
        self.diffraction = diffraction
        self.added_mass_infinite = a_inf
        self.added_mass_zero = a_zero
        self.hydrostatics = hydrostatics
        self.mesh = mesh
        self.lid_depth = lid_depth
        self.build_seconds = seconds
        self.bem_depth = bem_depth
        #: for a hull read from a file: its MeshCheck list and reference hydrostatics
        self.mesh_checks = mesh_checks
        self.mesh_reference = mesh_reference


def _clear_capytaine_caches() -> None:
    """Drop the block-circulant conversions capytaine caches per matrix (pitfall 5)."""
    try:
        from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix
    except ImportError:  # pragma: no cover - other capytaine 3 layouts
        return
    NestedBlockCirculantMatrix.to_BlockCirculantMatrix.cache_clear()


def _seed_prony() -> None:
    """Reseed capytaine's Prony-decomposition generator (module docstring)."""
    try:
        from capytaine.tools import prony_decomposition
    except ImportError:  # pragma: no cover - other capytaine 3 layouts
        return
    if hasattr(prony_decomposition, "RNG"):
        prony_decomposition.RNG = np.random.default_rng(PRONY_SEED)


def run_bem(floater: Floater, hydro: HydroSettings, environment: Environment, *,
            progress: Progress | None = None) -> BemResult:
    """Mesh the floater and solve the radiation and diffraction problems.

    Parameters
    ----------
    floater, hydro, environment
        From the case.
    progress
        Called after each frequency with (done, total, omega, seconds of that frequency).

    Raises
    ------
    floatmoor.io.bem_data.BemFileError
        A hull mesh file that cannot be read or fails a fatal check (nothing is solved).
    """
    import logging

    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force

    logging.getLogger("capytaine").setLevel(logging.ERROR)
    _seed_prony()
    start = time.perf_counter()
    rho, g = environment.water_density, environment.gravity
    depth = math.inf if hydro.infinite_depth else environment.water_depth
    omegas = np.asarray(hydro.frequencies, dtype=float)
    ref = np.asarray(floater.reference_point, dtype=float)
    checked = checked_mesh(floater, hydro, environment)
    mesh, lid_depth = checked.mesh, checked.lid_depth
    mesh_checks, mesh_reference = checked.mesh_checks, checked.mesh_reference
    dofs = cpt.rigid_body_dofs(rotation_center=ref)
    body = cpt.FloatingBody(mesh=mesh.hull, lid_mesh=mesh.lid, dofs=dofs, center_of_mass=ref,
                            name=floater.name)
    body_no_lid = cpt.FloatingBody(mesh=mesh.hull, dofs=cpt.rigid_body_dofs(rotation_center=ref),
                                   center_of_mass=ref, name=floater.name)
    solver = cpt.BEMSolver(green_function=cpt.Delhommeau(
        finite_depth_prony_decomposition_method="python"), method=BEM_METHOD)
    common = dict(water_depth=depth, rho=rho, g=g)

    n_w, n_b = len(omegas), len(hydro.directions)
    added = np.zeros((n_w, 6, 6))
    damping = np.zeros((n_w, 6, 6))
    fk = np.zeros((n_w, n_b, 6), dtype=complex)
    diff = np.zeros((n_w, n_b, 6), dtype=complex)
    total = n_w + 1 + (1 if not math.isfinite(depth) else 0)
    for i, omega in enumerate(omegas):
        t0 = time.perf_counter()
        for j, dof in enumerate(DOFS):
            res = solver.solve(cpt.RadiationProblem(body=body, radiating_dof=dof, omega=omega,
                                                    **common), keep_details=False)
            for k, other in enumerate(DOFS):
                added[i, j, k] = res.added_mass[other]
                damping[i, j, k] = res.radiation_damping[other]
        for b, beta in enumerate(hydro.directions):
            problem = cpt.DiffractionProblem(body=body, wave_direction=beta, omega=omega,
                                             **common)
            res = solver.solve(problem, keep_details=False)
            froude = froude_krylov_force(problem)
            for k, other in enumerate(DOFS):
                diff[i, b, k] = res.forces[other]
                fk[i, b, k] = froude[other]
        _clear_capytaine_caches()
        if progress is not None:
            progress(i + 1, total, float(omega), time.perf_counter() - t0)

    def limit(omega: float) -> np.ndarray:
        out = np.zeros((6, 6))
        for j, dof in enumerate(DOFS):
            res = solver.solve(cpt.RadiationProblem(body=body_no_lid, radiating_dof=dof,
                                                    omega=omega, **common), keep_details=False)
            for k, other in enumerate(DOFS):
                out[j, k] = res.added_mass[other]
        _clear_capytaine_caches()
        return out

    t0 = time.perf_counter()
    a_inf = limit(np.inf)
    if progress is not None:
        progress(n_w + 1, total, math.inf, time.perf_counter() - t0)
    a_zero = None
    if not math.isfinite(depth):
        t0 = time.perf_counter()
        a_zero = limit(0.0)
        if progress is not None:
            progress(total, total, 0.0, time.perf_counter() - t0)

    hydrostatics = hull_hydrostatics(mesh.full_hull, rho=rho, g=g, rotation_center=ref)
    return BemResult(omegas, np.asarray(hydro.directions, float), added, damping, fk, diff,
                     a_inf, a_zero, hydrostatics, mesh, lid_depth,
                     time.perf_counter() - start, depth, mesh_checks, mesh_reference)


def bem_dataset_arrays(result: BemResult) -> dict[str, xr.DataArray]:
    """The result as labelled arrays in capytaine's layout (complex values still complex)."""
    dof = list(DOFS)
    coords_rad = {"omega": result.omega, "radiating_dof": dof, "influenced_dof": dof}
    coords_exc = {"omega": result.omega, "wave_direction": result.directions,
                  "influenced_dof": dof}
    out = {
        "added_mass": xr.DataArray(result.added_mass, coords_rad,
                                   ("omega", "radiating_dof", "influenced_dof")),
        "radiation_damping": xr.DataArray(result.radiation_damping, coords_rad,
                                          ("omega", "radiating_dof", "influenced_dof")),
        "Froude_Krylov_force": xr.DataArray(result.froude_krylov, coords_exc,
                                            ("omega", "wave_direction", "influenced_dof")),
        "diffraction_force": xr.DataArray(result.diffraction, coords_exc,
                                          ("omega", "wave_direction", "influenced_dof")),
        "added_mass_infinite": xr.DataArray(result.added_mass_infinite,
                                            {"radiating_dof": dof, "influenced_dof": dof},
                                            ("radiating_dof", "influenced_dof")),
        "hydrostatic_stiffness": xr.DataArray(result.hydrostatics["hydrostatic_stiffness"],
                                              {"influenced_dof": dof, "radiating_dof": dof},
                                              ("influenced_dof", "radiating_dof")),
    }
    out["excitation_force"] = out["Froude_Krylov_force"] + out["diffraction_force"]
    if result.added_mass_zero is not None:
        out["added_mass_zero"] = xr.DataArray(result.added_mass_zero,
                                              {"radiating_dof": dof, "influenced_dof": dof},
                                              ("radiating_dof", "influenced_dof"))
    return out
