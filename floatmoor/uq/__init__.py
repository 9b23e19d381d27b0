"""Uncertainty quantification by generalised polynomial chaos (gpc paper section 3), on
OpenTURNS: the public Python API.

>>> from floatmoor import uq
>>> inputs = [uq.UncertainInput("T", "uniform", {"lower": 100.0, "upper": 116.0}),
...           uq.UncertainInput("m", "uniform", {"lower": 1.0, "upper": 5.0})]
>>> model = uq.BUILTIN_MODELS["taut_string"].function
>>> s = uq.propagate(lambda z: model(T=z[0], m=z[1]), inputs, uq.QuadratureMethod(order=6))
>>> round(float(s.mean[0]), 5)
-0.09385
"""

from floatmoor.uq import designs
from floatmoor.uq.inputs import DISTRIBUTIONS, UncertainInput, check_input, joint_distribution
from floatmoor.uq.propagate import QuadratureMethod, RegressionMethod, design, fit, propagate
from floatmoor.uq.surrogate import Surrogate
from floatmoor.uq.taut_string import BUILTIN_MODELS, BuiltinModel, ModelParameter

__all__ = ["UncertainInput", "DISTRIBUTIONS", "check_input", "joint_distribution",
           "QuadratureMethod", "RegressionMethod", "design", "fit", "propagate", "Surrogate",
           "designs", "BUILTIN_MODELS", "BuiltinModel", "ModelParameter"]
