"""State-space realisations of the radiation impulse response K(t): their identification from
a database and their storage in it (docs/theory/floater.md#radiation-convolution-or-state-space).

The radiation memory of the Cummins equation, mu_i(t) = sum_j int_0^t K_ji(t - tau) v_j(tau)
dtau, is replaced by linear states driven by the body velocity: for each significant pair
(j radiating, i influenced) of the database's K(t) (:func:`floatmoor.hydro.radiation.
radiation_kernel`, indices as the database's damping),

    z' = A z + b v_j,   mu_i += c . z,   so that   K_ji(t) ~ c exp(A t) b.

* :mod:`~floatmoor.hydro.state_space.kernel_fit`: one kernel's identification (poles by
  Kung's SVD realisation, residues by constrained least squares, the order);
* :mod:`~floatmoor.hydro.state_space.fit`: a database's significant pairs fitted, and whether
  a stored realisation still belongs to the database;
* :mod:`~floatmoor.hydro.state_space.realisation`: the realisation objects (one pair's, a
  database's) and their frequency response;
* :mod:`~floatmoor.hydro.state_space.modal_form`: the real modal form they are kept in;
* :mod:`~floatmoor.hydro.state_space.storage`: the realisation in the database's netCDF file.

The realisation is kept in real modal form (a 1 x 1 block per real pole, a 2 x 2 block
[[sigma, omega], [-omega, sigma]] per complex pair, b of ones and zeros), whose frequency
response H(i omega) = int_0^inf K(t) e^{-i omega t} dt = B(omega) + i omega (A(omega) - A_inf)
checks it against the database's BEM values. Storage (``floatmoor hydro fit-state-space``):
variables ``state_space_*`` and attributes in the database file, without touching the BEM
variables or the recorded inputs (the database does not become stale).

The time-domain side, the states integrated with the body in its RK4 step, is
:mod:`floatmoor.body.state_space_radiation` and its kernels
:mod:`floatmoor.body._state_space_radiation_kernels`.
"""

__all__: list[str] = []
