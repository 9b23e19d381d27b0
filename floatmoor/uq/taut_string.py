"""The taut string of the gpc paper section 4.1 (case E): a verification model of UQ.

A string of length L fixed at both ends, released at rest from a half sine of amplitude A,
under tension T with mass per unit length m, has the transverse displacement (paper eq. 20,
the solution of the wave equation y_tt = (T / m) y_xx, eq. 18)

    y(x, t) = A sin(pi x / L) cos(pi c t / L),   c = sqrt(T / m).

The reference values (paper Table 1) give a period 2 L / c = 1 s: A = 1 m, L = 3 m,
T = 108 N, m = 3 kg/m; the paper's uncertain inputs are T ~ U(100, 116) N, m ~ U(1, 5) kg/m at
x = 1.5 m, t = 0.25 s.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["taut_string", "BuiltinModel", "ModelParameter", "BUILTIN_MODELS"]


def taut_string(T: ArrayLike = 108.0, m: ArrayLike = 3.0, x: ArrayLike = 1.5,
                t: ArrayLike = 0.25, A: float = 1.0, L: float = 3.0) -> NDArray[np.float64]:
    """Transverse displacement y [m] of the released taut string (module docstring).

    Parameters
    ----------
    T
        Tension [N], > 0.
    m
        Mass per unit length [kg/m], > 0.
    x
        Position along the string [m], in [0, L].
    t
        Time since release [s].
    A
        Amplitude of the initial half sine [m].
    L
        Length of the string [m], > 0.
    """
    celerity = np.sqrt(np.asarray(T, dtype=float) / np.asarray(m, dtype=float))
    return A * np.sin(np.pi * np.asarray(x, dtype=float) / L) * np.cos(np.pi * celerity
                                                                        * np.asarray(t) / L)


@dataclass(frozen=True)
class ModelParameter:
    """A parameter of a built-in model: its units, default and meaning.

    Attributes
    ----------
    units
        Its units (SI).
    default
        Its value where a study does not make it uncertain.
    long_name
        What it is.
    """

    units: str
    default: float
    long_name: str


@dataclass(frozen=True)
class BuiltinModel:
    """A model a study can name instead of a case: ``function(**parameters) -> output``.

    Attributes
    ----------
    function
        The model.
    parameters
        Its parameters by name.
    output_name, output_units, output_long_name
        Its output's name, units and meaning.
    """

    function: Callable[..., NDArray[np.float64]]
    parameters: dict[str, ModelParameter]
    output_name: str
    output_units: str
    output_long_name: str


#: Built-in models by name.
BUILTIN_MODELS: dict[str, BuiltinModel] = {
    "taut_string": BuiltinModel(
        function=taut_string,
        parameters={
            "T": ModelParameter("N", 108.0, "string tension"),
            "m": ModelParameter("kg/m", 3.0, "mass per unit length"),
            "x": ModelParameter("m", 1.5, "position along the string"),
            "t": ModelParameter("s", 0.25, "time since release"),
            "A": ModelParameter("m", 1.0, "amplitude of the initial half sine"),
            "L": ModelParameter("m", 3.0, "string length"),
        },
        output_name="displacement",
        output_units="m",
        output_long_name="transverse displacement of the string",
    ),
}
