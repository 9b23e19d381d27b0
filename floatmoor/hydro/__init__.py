"""Linear hydrodynamics of floaters: capytaine BEM databases and their time-domain use.

* :mod:`~floatmoor.hydro.geometry`: parametric meshes (cylinder, semisubmersible);
* :mod:`~floatmoor.hydro.mesh_file`, :mod:`~floatmoor.hydro.mesh_checks`: hull meshes read
  from files, and their checks;
* :mod:`~floatmoor.hydro.build`: BEM runs;
* :mod:`~floatmoor.hydro.database`: ``hydrodb/NAME.nc`` files, staleness and damage;
* :mod:`~floatmoor.hydro.radiation`: A_inf, K(t), Kramers-Kronig rebuild, total stiffness;
* :mod:`~floatmoor.hydro.excitation_transfer`: X(omega, beta) interpolation;
* :mod:`~floatmoor.hydro.checks`: the checks every database passes;
* :mod:`~floatmoor.hydro.natural_periods`: mooring stiffness and natural periods.
* :mod:`~floatmoor.hydro.state_space`: state-space realisations of K(t), fitted and stored
  (integrated with the body by :mod:`floatmoor.body.state_space_radiation`).

Modules import capytaine only when they mesh or solve, so reading a database needs no BEM.
"""

from floatmoor._exports import lazy_exports

#: Public name -> the module that defines it (docs/development.md#public-api).
_API = {
    "read_database": "floatmoor.hydro.database",
    "write_database": "floatmoor.hydro.database",
    "build_database": "floatmoor.hydro.database",
    "load_for_case": "floatmoor.hydro.database",
    "database_path": "floatmoor.hydro.database",
    "HydroDatabaseError": "floatmoor.hydro.database",
    "import_database": "floatmoor.hydro.importing",
    "build_mesh": "floatmoor.hydro.geometry",
    "mesh_from_file": "floatmoor.hydro.mesh_file",
    "run_bem": "floatmoor.hydro.build",
    "run_checks": "floatmoor.hydro.checks",
    "run_mesh_checks": "floatmoor.hydro.mesh_checks",
    "radiation_kernel": "floatmoor.hydro.radiation",
    "RadiationKernel": "floatmoor.hydro.radiation",
    "ExcitationInterpolator": "floatmoor.hydro.excitation_transfer",
    "rao_for_case": "floatmoor.hydro.rao",
    "rao_dataset": "floatmoor.hydro.rao",
    "drift_for_case": "floatmoor.hydro.drift_build",
    "add_drift": "floatmoor.hydro.drift_build",
    "solve_drift": "floatmoor.hydro.drift",
    "check_drift": "floatmoor.hydro.drift_checks",
}
__all__, __getattr__, __dir__ = lazy_exports(__name__, _API)
