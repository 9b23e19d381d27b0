"""
Uncertainty propagation by polynomial chaos
===========================================

A generalised polynomial chaos surrogate of the released taut string (case E), whose tension
and mass per length are uncertain: the mean, the 95 % band and the first-order Sobol' indices
of the midpoint's displacement over one period, checked against Monte Carlo on the exact model.
"""

# %%
# The string of length L = 3 m, released at rest from a half sine of amplitude 1 m, moves as
# y(x, t) = sin(pi x / L) cos(pi c t / L) with c = sqrt(T / m) (the wave equation's solution).
# T ~ U(100, 116) N and m ~ U(1, 5) kg/m, as in the verification case of the gPC study of
# mooring uncertainty in J. Mar. Sci. Eng. 8(3):162 (2020), doi:10.3390/jmse8030162. Legendre
# polynomials are the chaos of uniform inputs; a 9 x 9 Gauss-Legendre grid (order 8)
# projects the model on them from 81 runs. The spread of the wave speed c makes the spread of
# the phase grow with time, so a whole period needs a higher order than the paper's single
# instant (t = 0.25 s, order 6).
import matplotlib.pyplot as plt
import numpy as np

from floatmoor import uq

inputs = [uq.UncertainInput("T", "uniform", {"lower": 100.0, "upper": 116.0}),
          uq.UncertainInput("m", "uniform", {"lower": 1.0, "upper": 5.0})]
times = np.linspace(0.0, 1.0, 101)  # s, one period of the nominal string
ORDER = 8  # polynomial degree of the chaos
string = uq.BUILTIN_MODELS["taut_string"].function


def midpoint_history(z: np.ndarray) -> np.ndarray:
    """y(x = 1.5 m, t) [m] at the input values z = (T, m)."""
    return string(T=z[0], m=z[1], x=1.5, t=times)


surrogate = uq.propagate(midpoint_history, inputs, uq.QuadratureMethod(order=ORDER))
low, high = surrogate.bands(level=0.95, n=4000, seed=1)

# %%
# Monte Carlo on the exact model, with the same input distributions, checks the surrogate's
# mean: their difference should stay within a few standard errors of the Monte Carlo mean.
MC_RUNS = 20000
z = surrogate.sample_inputs(MC_RUNS, seed=2)
exact = string(T=z[:, :1], m=z[:, 1:], x=1.5, t=times[None, :])
standard_error = exact.std(axis=0) / np.sqrt(MC_RUNS)
gap = np.abs(surrogate.mean - exact.mean(axis=0))
print(f"{surrogate.n_runs} model runs for the surrogate; its mean is within "
      f"{np.max(gap[1:] / standard_error[1:]):.1f} standard errors of {MC_RUNS} Monte Carlo "
      f"runs (largest difference {gap.max():.4f} m)")

fig, (band, sobol) = plt.subplots(2, 1, figsize=(8.0, 7.0), sharex=True)
band.fill_between(times, low, high, color="C0", alpha=0.25, label="95 % band (gPC)")
band.plot(times, surrogate.mean, color="C0", label="mean (gPC)")
band.plot(times, exact.mean(axis=0), "k--", lw=1.0, label=f"mean ({MC_RUNS} Monte Carlo runs)")
band.plot(times, string(x=1.5, t=times), color="0.5", lw=0.8, label="nominal T, m")
band.set(ylabel="midpoint displacement [m]", title="taut string, T and m uniform")
band.legend(loc="lower left", fontsize=8)
for k, inp in enumerate(inputs):
    sobol.plot(times, surrogate.sobol_first[k], label=f"first order, {inp.key}")
sobol.set(xlabel="time [s]", ylabel="Sobol' index [-]", ylim=(-0.02, 1.02))
sobol.legend(loc="center right", fontsize=8)
for ax in (band, sobol):
    ax.grid(alpha=0.3)
fig.tight_layout()
