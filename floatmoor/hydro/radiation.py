"""Time-domain radiation quantities from a database (docs/theory/floater.md).

Cummins: (M + A_inf) x'' + int_0^t K(t - tau) x'(tau) dtau + C x = f, with the radiation
impulse response

    K(t) = (2 / pi) int_0^inf B(omega) cos(omega t) d omega.

Integration choices (tested against closed-form pairs in tests/hydro/test_radiation.py):

* B(omega) is the piecewise-linear interpolant of the BEM values, with B(0) = 0 added below
  the first frequency (radiation damping vanishes at zero frequency).
* Each linear piece is integrated against cos(omega t) exactly (Filon-type closed form), so
  the frequency step causes no aliasing or spurious periodicity of K(t); K inherits only the
  interpolation error of B.
* Above the top BEM frequency omega_N the damping is continued by the tail
  B(omega) = B(omega_N) (omega_N / omega)^p (docs/theory/hydrodynamics.md, practical note 8: surge and pitch
  damping have not decayed at the top frequency). By default p is fitted per DOF so that the
  Kramers-Kronig rebuild of A(omega_N) is exact (:func:`fit_tail_exponents`: the only
  information the BEM data hold about the tail); a fixed p (:data:`TAIL_EXPONENT`) can be
  given instead. The tail is integrated the same way on a geometric grid up to
  :data:`TAIL_EXTENT` x omega_N; the part beyond contributes at most
  B(omega_N) omega_N / ((p - 1) TAIL_EXTENT^(p-1)) to K (1e-7 B(omega_N) omega_N for p = 3,
  3e-4 for p = 1.2).
* K(t) is truncated at ``t_max``; :func:`truncation_time` gives the default, the time step
  resolves the tail's frequency content.

The Kramers-Kronig rebuild A(omega) = A_inf - (1 / omega) int_0^t_max K(t) sin(omega t) dt
(Ogilvie 1964) is integrated with the composite Simpson rule on the K grid.
"""

from __future__ import annotations

import hashlib
import math

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from floatmoor.case.schema import Floater

__all__ = [
    "TAIL_EXPONENT", "TAIL_EXTENT", "TAIL_MIN", "TAIL_MAX", "fit_tail_exponents",
    "impulse_response", "piecewise_linear_cosine_transform", "sine_moments",
    "added_mass_from_kernel", "consistent_infinite_added_mass", "truncation_time", "RadiationKernel", "radiation_kernel",
    "kernel_samples",
    "hydrostatic_stiffness_total", "added_mass_at", "KERNEL_NEGLIGIBLE",
]

#: Kernel entries below this fraction of the largest are not summed: the memory convolution
#: (:mod:`floatmoor.body.cummins`) and the state-space realisation
#: (:func:`floatmoor.hydro.state_space.fit.significant_pairs`) drop the same pairs.
KERNEL_NEGLIGIBLE = 1e-12

#: Exponent p of the damping tail B(omega_N) (omega_N / omega)^p above the top BEM frequency
#: when it is not fitted (and for DOFs without damping at omega_N): a choice, not a derived
#: value.
TAIL_EXPONENT = 3.0
#: Range of the fitted tail exponents (:func:`fit_tail_exponents`): from a tail slower than any
#: finite-energy damping needs (p > 1 for a finite K(0)) to one that is practically a cut-off.
TAIL_MIN, TAIL_MAX = 1.2, 8.0
#: The tail is integrated up to this multiple of the top BEM frequency.
TAIL_EXTENT = 1000.0
#: Points per decade of the tail's geometric frequency grid.
_TAIL_POINTS_PER_DECADE = 200
#: Values (times x frequency nodes) of a cosine-transform operator built at once: the
#: transforms build their operator a block of times (or nodes) at a time, so that their memory
#: (the block and a few temporaries of its size, 4 MB each) does not grow with the number of
#: times. Whole, the tail operator of a 0.01 s body step's kernel (31417 times, 10 per step,
#: x 601 nodes) took 151 MB, and building it 0.9 GB. That kernel costs 1.6 s of
#: CPU in blocks of 2^19 values, 6 % more than in blocks of 2^20 and 25 % less than in 2^17.
_BLOCK_VALUES = 2 ** 19


def cosine_transform_operator(omega: NDArray[np.float64], t: NDArray[np.float64]
                              ) -> NDArray[np.float64]:
    """Matrix L (m, n) with L @ f = int_{omega_0}^{omega_n-1} f(omega) cos(omega t) d omega
    exactly for the piecewise-linear f through the n nodes, at the m times ``t``.

    On a segment [w0, w1] with slope s: int (f0 + s (w - w0)) cos(w t) dw
    = [f sin(w t) / t + s cos(w t) / t^2] from w0 to w1; at t = 0 the trapezoidal rule. The
    sine terms of an inner node cancel between its two segments, so only the two end nodes
    have them: L_j = d_(j-1) - d_j with d_j = (cos(w_(j+1) t) - cos(w_j t)) / (h_j t^2),
    plus -sin(w_0 t) / t at the first node and sin(w_(n-1) t) / t at the last (the largest
    cost of a transform is these cosines).
    """
    omega = np.asarray(omega, dtype=float)
    t = np.asarray(t, dtype=float)
    h = np.diff(omega)
    small = np.abs(t) < 1e-12
    ti = t[~small][:, None]
    big = np.zeros((len(ti), len(omega)))
    if len(ti) and len(omega) > 1:  # in place where it can be: the largest arrays of a transform
        first = np.sin(omega[0] * ti[:, 0]) / ti[:, 0]
        last = np.sin(omega[-1] * ti[:, 0]) / ti[:, 0]
        cos = omega[None, :] * ti
        np.cos(cos, out=cos)
        d = cos[:, 1:] - cos[:, :-1]
        del cos
        scale = h[None, :] * ti
        scale *= ti
        d /= scale
        del scale
        np.subtract(d[:, :-1], d[:, 1:], out=big[:, 1:-1])
        big[:, 0] = -first - d[:, 0]
        big[:, -1] = last + d[:, -1]
    if not small.any():
        return big
    out = np.zeros((len(t), len(omega)))
    trap = np.zeros(len(omega))
    trap[:-1] += 0.5 * h
    trap[1:] += 0.5 * h
    out[small] = trap
    out[~small] = big
    return out


def piecewise_linear_cosine_transform(omega: NDArray[np.float64], values: NDArray[np.float64],
                                      t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Exact int_{omega_0}^{omega_n} f(omega) cos(omega t) d omega of the piecewise-linear f.

    Parameters
    ----------
    omega
        Increasing nodes, shape (n,).
    values
        f at the nodes, shape (n, ...) (trailing dimensions are transformed together).
    t
        Times, shape (m,).

    Returns
    -------
    Array of shape (m, ...).
    """
    f = np.asarray(values, dtype=float)
    flat = f.reshape(len(f), -1)
    t = np.asarray(t, dtype=float)
    out = np.empty((len(t), flat.shape[1]))
    block = max(1, _BLOCK_VALUES // len(f))
    for start in range(0, len(t), block):  # the operator a block of times at a time
        rows = slice(start, start + block)
        # einsum, not BLAS: a multithreaded BLAS product of a few columns differs in its last
        # bits with the thread count, and a campaign's workers (one BLAS thread each on Dask)
        # must give a serial run's numbers
        out[rows] = np.einsum("ij,jk->ik", cosine_transform_operator(omega, t[rows]), flat)
    return out.reshape((len(t),) + f.shape[1:])


def sine_moments(omega: NDArray[np.float64], t: NDArray[np.float64], frequency: float
                 ) -> NDArray[np.float64]:
    """u (n,) with u @ f = int_{t_0}^{t_m-1} F(t) sin(frequency t) dt (Simpson's rule on
    ``t``, :func:`scipy.integrate.simpson`) of the cosine transform F = L @ f
    (:func:`cosine_transform_operator`) of any f at the n nodes ``omega``: the integral of
    each column of L against the sine.

    The columns are built a few nodes at a time (each with its neighbours, which its
    segments reach), so that the memory does not grow with the number of times.
    """
    from scipy.integrate import simpson

    omega = np.asarray(omega, dtype=float)
    t = np.asarray(t, dtype=float)
    sine = np.sin(frequency * t)[:, None]
    out = np.empty(len(omega))
    block = max(1, _BLOCK_VALUES // len(t))
    for start in range(0, len(omega), block):
        stop = min(start + block, len(omega))
        lo, hi = max(start - 1, 0), min(stop + 1, len(omega))
        columns = cosine_transform_operator(omega[lo:hi], t)[:, start - lo:stop - lo]
        out[start:stop] = simpson(columns * sine, x=t, axis=0)
    return out


def _tail_grid(omega_top: float, exponent: float) -> tuple[NDArray, NDArray]:
    decades = math.log10(TAIL_EXTENT)
    n = int(_TAIL_POINTS_PER_DECADE * decades) + 1
    w = omega_top * np.logspace(0.0, decades, n)
    return w, (omega_top / w) ** exponent


def _tail_transforms(omega_top: float, exponents: NDArray[np.float64],
                     t: NDArray[np.float64]) -> NDArray[np.float64]:
    """int_{omega_N}^{TAIL_EXTENT omega_N} (omega_N / omega)^p cos(omega t) d omega at the
    times ``t`` (m, k), one column per exponent p of ``exponents`` (k,), on the tail's
    geometric grid."""
    grid, _ = _tail_grid(omega_top, 1.0)
    shapes = np.stack([(omega_top / grid) ** float(p) for p in exponents], axis=1)
    return piecewise_linear_cosine_transform(grid, shapes, t)


def impulse_response(omega: NDArray[np.float64], damping: NDArray[np.float64],
                     t: NDArray[np.float64], *,
                     tail_exponent: float | NDArray[np.float64] | None = TAIL_EXPONENT
                     ) -> NDArray[np.float64]:
    """K(t) = (2/pi) int_0^inf B(omega) cos(omega t) d omega (see the module docstring).

    Parameters
    ----------
    omega
        BEM frequencies, increasing, > 0 [rad/s].
    damping
        B(omega), shape (n, ...) [kg/s ...].
    t
        Times [s].
    tail_exponent
        p of the high-frequency tail (one value, or one per element of ``damping[0]``), or
        None for no tail (B = 0 above the top frequency).
    """
    omega = np.asarray(omega, dtype=float)
    b = np.asarray(damping, dtype=float)
    w = np.concatenate([[0.0], omega])
    f = np.concatenate([np.zeros((1,) + b.shape[1:]), b])
    k = piecewise_linear_cosine_transform(w, f, t)
    if tail_exponent is not None:
        exponents = np.broadcast_to(np.asarray(tail_exponent, dtype=float), b.shape[1:])
        unique = np.unique(exponents)
        tails = _tail_transforms(float(omega[-1]), unique, t)
        for i, p in enumerate(unique):
            mask = exponents == p
            k[:, mask] += np.outer(tails[:, i], b[-1][mask])
    return (2.0 / math.pi) * k


def fit_tail_exponents(omega: NDArray[np.float64], damping: NDArray[np.float64],
                       added_mass: NDArray[np.float64], a_inf: NDArray[np.float64],
                       t: NDArray[np.float64]) -> NDArray[np.float64]:
    """Tail exponents (6, 6) that make the Kramers-Kronig rebuild exact at the top frequency.

    The BEM data say one thing about the damping beyond omega_N: through Kramers-Kronig, the
    added mass A(omega_N) fixes the weighted integral of the tail. For each diagonal DOF with
    damping at omega_N, p in [:data:`TAIL_MIN`, :data:`TAIL_MAX`] is solved (Brent) so that
    A_KK(omega_N) = A_BEM(omega_N) on the truncated K grid ``t``; the nearer bound is kept
    when no p in the range does it. Off-diagonal terms take the mean of their two diagonal
    exponents; DOFs without damping at omega_N keep :data:`TAIL_EXPONENT`. The check then
    tests the rebuild at every other frequency of the band.
    """
    from scipy.integrate import simpson
    from scipy.optimize import brentq

    omega = np.asarray(omega, float)
    w_top = float(omega[-1])
    band = impulse_response(omega, damping, t, tail_exponent=None)
    sine = np.sin(w_top * t)
    s_band = simpson(band * sine[:, None, None], x=t, axis=0)
    # int tail(p) sin = u @ (omega_N / omega)^p on the tail grid: the tail's operator is
    # integrated against the sine once (a few nodes at a time), not built whole and applied
    # to each p Brent tries
    grid, _ = _tail_grid(w_top, 1.0)
    moments = (2.0 / math.pi) * sine_moments(grid, t, w_top)

    def s_tail(p: float) -> float:
        return float(np.einsum("i,i->", moments, (w_top / grid) ** p))

    b_top = damping[-1]
    scale = np.abs(np.diagonal(b_top)).max()
    out = np.full((6, 6), TAIL_EXPONENT)
    for i in range(6):
        if b_top[i, i] <= 1e-9 * scale:
            continue
        target = ((a_inf[i, i] - added_mass[-1, i, i]) * w_top - s_band[i, i]) / b_top[i, i]
        lo, hi = s_tail(TAIL_MIN) - target, s_tail(TAIL_MAX) - target
        if lo * hi < 0.0:
            out[i, i] = brentq(lambda p: s_tail(p) - target, TAIL_MIN, TAIL_MAX, xtol=1e-3)
        else:
            out[i, i] = TAIL_MIN if abs(lo) < abs(hi) else TAIL_MAX
    diag = np.diag(out).copy()
    for i in range(6):
        for j in range(6):
            if i != j:
                out[i, j] = 0.5 * (diag[i] + diag[j])
    return out


def added_mass_from_kernel(t: NDArray[np.float64], kernel: NDArray[np.float64],
                           a_inf: NDArray[np.float64], omega: NDArray[np.float64]
                           ) -> NDArray[np.float64]:
    """A(omega) = A_inf - (1/omega) int_0^t_max K(t) sin(omega t) dt (Simpson on the K grid).

    ``t`` must be uniform with an even number of intervals; ``kernel`` has shape (m, ...).
    """
    from scipy.integrate import simpson

    t = np.asarray(t, float)
    out = np.empty((len(omega),) + kernel.shape[1:])
    for i, w in enumerate(np.asarray(omega, float)):
        s = np.sin(w * t).reshape((-1,) + (1,) * (kernel.ndim - 1))
        out[i] = a_inf - simpson(kernel * s, x=t, axis=0) / w
    return out


def consistent_infinite_added_mass(ds: xr.Dataset, time: NDArray[np.float64],
                                   kernel: NDArray[np.float64]) -> NDArray[np.float64]:
    """A_inf consistent with K(t) and the BEM added mass over the band (6, 6): the mean over
    the BEM frequencies of A(w) + (1 / w) int K(t) sin(w t) dt (Ogilvie 1964), so that the
    time-domain model's A(w) = A_inf - (1 / w) int K sin matches the BEM A(w) best in the
    mean. On the buoy database the implied values scatter by 0.2 % (heave) over the band,
    while the BEM A_inf (computed without the lid, docs/theory/hydrodynamics.md, practical note 1) sits 0.75 % below
    their mean: with it, the heave response near resonance misses the RAO by 2 %."""
    omega = ds["omega"].values
    added = ds["added_mass"].transpose("omega", "radiating_dof", "influenced_dof").values
    # A(w) - (A_inf - (1 / w) int K sin) with A_inf = 0: the A_inf each frequency implies
    implied = added - added_mass_from_kernel(time, kernel, np.zeros((6, 6)), omega)
    return implied.mean(axis=0)


def truncation_time(omega: NDArray[np.float64]) -> float:
    """Default truncation time of K(t): pi / (median frequency step) [s].

    The piecewise-linear B resolves features no narrower than the step; K(t) beyond
    pi / step would mostly be an artefact of the grid. The decay check (|K| below 1e-3 of its
    peak from there on) tells whether the truncation loses anything.
    """
    omega = np.asarray(omega, float)
    return float(math.pi / np.median(np.diff(omega)))


def default_time_step(omega: NDArray[np.float64]) -> float:
    """Time step of the K grid: 1/40 of the period of the top BEM frequency [s]."""
    return float(2.0 * math.pi / np.max(omega) / 40.0)


class RadiationKernel:
    """K(t) of a database on a uniform grid, with A_inf.

    Attributes
    ----------
    time
        (m,) [s], from 0 to the truncation time.
    kernel
        (m, 6, 6), indices (radiating, influenced) as the database's damping.
    added_mass_infinite
        (6, 6).

    Parameters
    ----------
    time, kernel
        The attributes of the same names.
    a_inf
        The attribute ``added_mass_infinite``.
    tail_exponent
        The exponents of the damping's high-frequency tail the kernel was computed with
        (:func:`fit_tail_exponents`).
    """

    def __init__(self, time: NDArray, kernel: NDArray, a_inf: NDArray,
                 tail_exponent: NDArray[np.float64]):
        self.time = time
        self.kernel = kernel
        self.added_mass_infinite = a_inf
        self.tail_exponent = tail_exponent

    @property
    def truncation_time(self) -> float:
        """[s]"""
        return float(self.time[-1])


#: The tail exponents fitted in this process, by the fit's inputs (:func:`_fit_key`): another
#: run of the same database at the same step (a campaign worker's next run, a resumed run)
#: takes them from here instead of fitting them again (half the cost of a kernel). Only the
#: exponents are kept: a kept kernel (9 MB for the buoy at a 0.01 s body step) held 20 MB
#: more of a run's resident memory, the heap above it not being returned.
_FITTED_EXPONENTS: dict[bytes, NDArray[np.float64]] = {}
#: How many fits are kept (36 values each).
_FITS_KEPT = 16


def _fit_key(arrays: tuple[NDArray[np.float64], ...]) -> bytes:
    """A digest of the inputs of :func:`fit_tail_exponents`."""
    digest = hashlib.sha256()
    for array in arrays:
        values = np.ascontiguousarray(array, dtype=float)
        digest.update(repr(values.shape).encode())
        digest.update(values.tobytes())
    return digest.digest()


def radiation_kernel(ds: xr.Dataset, *, t_max: float | None = None, dt: float | None = None,
                     tail_exponent: float | str = "fitted") -> RadiationKernel:
    """K(t) of a database (defaults: :func:`truncation_time`, :func:`default_time_step`, tail
    exponents from :func:`fit_tail_exponents`, or one given exponent). The fitted exponents
    of the same inputs are fitted once per process (:data:`_FITTED_EXPONENTS`).

    Parameters
    ----------
    ds
        The database.
    t_max
        Truncation time [s] (None: :func:`truncation_time`).
    dt
        Time step of the grid [s] (None: :func:`default_time_step`).
    tail_exponent
        ``"fitted"`` (:func:`fit_tail_exponents`) or one exponent for every pair.

    Returns
    -------
    RadiationKernel
        K(t) on the grid, with A_inf.
    """
    omega = ds["omega"].values
    t_max = truncation_time(omega) if t_max is None else t_max
    dt = default_time_step(omega) if dt is None else dt
    n = int(math.ceil(t_max / dt))
    n += n % 2  # even number of intervals for Simpson
    t = np.linspace(0.0, n * dt, n + 1)
    damping = ds["radiation_damping"].transpose("omega", "radiating_dof", "influenced_dof").values
    a_inf = ds["added_mass_infinite"].transpose("radiating_dof", "influenced_dof").values
    if isinstance(tail_exponent, str):
        added = ds["added_mass"].transpose("omega", "radiating_dof", "influenced_dof").values
        key = _fit_key((omega, damping, added, a_inf, t))
        exponents = _FITTED_EXPONENTS.pop(key, None)
        if exponents is None:
            exponents = fit_tail_exponents(omega, damping, added, a_inf, t)
        _FITTED_EXPONENTS[key] = exponents  # the newest last
        while len(_FITTED_EXPONENTS) > _FITS_KEPT:
            del _FITTED_EXPONENTS[next(iter(_FITTED_EXPONENTS))]
        exponents = exponents.copy()
    else:
        exponents = np.full((6, 6), float(tail_exponent))
    return RadiationKernel(t, kernel_samples(ds, t, exponents), a_inf, exponents)


def kernel_samples(ds: xr.Dataset, t: NDArray[np.float64],
                   tail_exponent: NDArray[np.float64]) -> NDArray[np.float64]:
    """K(t) (n, 6, 6), indices (radiating, influenced), of a database at the times ``t`` [s]
    with the given tail exponents (6, 6) (those of a :class:`RadiationKernel`)."""
    damping = ds["radiation_damping"].transpose("omega", "radiating_dof", "influenced_dof").values
    return impulse_response(ds["omega"].values, damping, np.asarray(t, float),
                            tail_exponent=tail_exponent)


def added_mass_at(ds: xr.Dataset, omega: float) -> NDArray[np.float64]:
    """A(omega) (6, 6) interpolated linearly in frequency; outside the BEM range the nearest
    BEM value (below) or A_inf (above the top frequency is not extrapolated: the nearest)."""
    w = ds["omega"].values
    a = ds["added_mass"].transpose("omega", "radiating_dof", "influenced_dof").values
    out = np.empty((6, 6))
    for i in range(6):
        for j in range(6):
            out[i, j] = np.interp(omega, w, a[:, i, j])
    return out


def hydrostatic_stiffness_total(ds: xr.Dataset, floater: Floater) -> NDArray[np.float64]:
    """Hydrostatic plus gravity stiffness (6, 6) about the rotation centre [N/m, N, N m].

    The database holds the hull (buoyancy) part; the weight m g of the floater adds
    -m g (z_G - z_c) to C44 and C55 and m g (x_G - x_c), m g (y_G - y_c) to C46 and C56
    (linearised restoring moment of the weight about the rotation centre c).
    """
    c = ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values.copy()
    g = float(ds.attrs["gravity"])
    rc = ds["rotation_center"].values
    r = np.subtract(floater.centre_of_mass, rc)
    w = floater.mass * g
    c[3, 3] += -w * r[2]
    c[4, 4] += -w * r[2]
    c[3, 5] += w * r[0]
    c[4, 5] += w * r[1]
    return c
