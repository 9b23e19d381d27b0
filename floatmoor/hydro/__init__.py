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

Modules import capytaine only when they mesh or solve, so reading a database needs no BEM.
"""

from floatmoor.hydro.database import HydroDatabaseError, load_for_case, read_database
from floatmoor.hydro.excitation_transfer import ExcitationInterpolator
from floatmoor.hydro.radiation import radiation_kernel

__all__ = ["HydroDatabaseError", "load_for_case", "read_database", "ExcitationInterpolator",
           "radiation_kernel"]
