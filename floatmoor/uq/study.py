"""Strict reading of uncertainty-quantification study files (TOML).

A study names what is run, which inputs are uncertain, how the gPC surrogate is built and
which quantities of interest it is built for (gpc paper section 3.4, steps 1 to 9)::

    title = "Lindahl chain, hydrodynamic coefficients"
    case = "../lindahl/lindahl_r0.20_T1.25.toml"   # relative to this file; or
    # model = "taut_string" with [parameters] fixing the model's other parameters
    base_overrides = ["simulation.duration=5.0"]   # optional --set texts for every run

    [[inputs]]
    key = "line_types.chain.normal_drag_coefficient"   # a --set key path of the case
    distribution = "uniform"
    lower = 1.25
    upper = 3.75

    [method]
    kind = "quadrature"   # order; or "regression": order, q_norm, samples, seed
    order = 5

    [[quantities]]
    name = "tension_cycle"
    line = "chain"        # or dof = "Surge" (capytaine's DOF names)
    statistic = "history" # max, mean_cycle_max, std, mean, min (after the ramp) or history
    window = [13.75, 15.0]  # [s], history only

Everything is checked before anything runs: unknown, missing and mistyped keys, unphysical
values, and every uncertain key against the case (the case must load with the input's mean
set), each error one :class:`~floatmoor.errors.CaseError` naming the study file, the key path,
what was expected and what was found.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path as FilePath
from typing import Sequence

import numpy as np
import openturns as ot

from floatmoor.case.files import read_input_text
from floatmoor.case.limits import parse_toml
from floatmoor.case.load import load_case
from floatmoor.case.overrides import parse_override
from floatmoor.case.reader import ReadContext, TableReader
from floatmoor.case.setting import Setting, SettingTable
from floatmoor.case.schema import Case
from floatmoor.errors import CaseError
from floatmoor.io.dataset import DOFS
from floatmoor.simulation.forced import output_times
from floatmoor.uq.basis import probe_input
from floatmoor.uq.inputs import DISTRIBUTIONS, UncertainInput, check_input
from floatmoor.uq.propagate import QuadratureMethod, RegressionMethod, design
from floatmoor.uq.taut_string import BUILTIN_MODELS, ModelParameter

__all__ = ["Study", "Quantity", "load_study", "LINE_STATISTICS", "DOF_STATISTICS", "HISTORY",
           "MAX_RUNS", "MAX_ORDER", "DEFAULT_SURROGATE_SAMPLES", "nominal_values", "MIN_Q_NORM",
           "MAX_BASIS_SIZE", "MAX_SEED", "hyperbolic_basis_size", "STUDY_TABLES"]

#: The history statistic: the quantity's samples over a time window (a vector output).
HISTORY = "history"
#: Statistics of a line's fairlead tension after the ramp, as the run summary gives them
#: (:func:`floatmoor.post.summary.run_summary`), and its history.
LINE_STATISTICS = ("max", "mean_cycle_max", "std", "mean", "min", HISTORY)
#: Statistics of a floater DOF's displacement after the ramp (the run summary gives no cycle
#: maxima of motions), and its history.
DOF_STATISTICS = ("max", "std", "mean", "min", HISTORY)
#: Most model runs a design may ask for: (p + 1)^d quadrature grows fast (p = 5, d = 6 is
#: 46 656 runs of a mooring simulation); a larger design is almost surely a slip.
MAX_RUNS = 20000
#: Highest polynomial order: Gauss rules and orthonormal polynomials lose accuracy in double
#: precision beyond ~20, and the paper's studies converge by p = 4 to 6.
MAX_ORDER = 20
#: Smallest q-norm of a hyperbolic basis. At q <= log 2 / log MAX_ORDER (0.23) the set
#: {k : ||k||_q <= p} already holds no interaction term (2^(1/q) > p): the main effects alone,
#: so a smaller q changes nothing, and at q ~ 1e-16 k^q rounds to 1 and OpenTURNS'
#: enumeration of the set never ends.
MIN_Q_NORM = 0.1
#: Most candidate polynomials of a regression basis. Least-angle regression holds the design
#: matrix of samples x candidates (MAX_RUNS x 5000 doubles: 800 MB) and its work grows with
#: their product; the paper's buoy study uses 21 (p = 5, d = 2). A full basis of order 20 in 5
#: inputs already has 53 130: q_norm < 1 or a lower order keeps a large study within it.
MAX_BASIS_SIZE = 5000
#: Largest sampling seed: OpenTURNS' generator takes 32-bit seeds (floatmoor.uq.designs).
MAX_SEED = 2**32 - 1
#: Surrogate samples for densities and bands (gpc paper section 4: 3000 for every study).
DEFAULT_SURROGATE_SAMPLES = 3000
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_METHODS = ("quadrature", "regression")

# -- the keys of a study file, declared once (docs/reference/case_file.md#study-files) --------

_ONE_OF = "one of `case`, `model`"
_TOP = SettingTable("", {
    "title": Setting("string", doc="Title of the study, in its report and output."),
    "case": Setting("string", default_text=_ONE_OF, doc="Case file the runs are made of, "
                    "relative to the study file; instead of `model`."),
    "model": Setting("string", choices=tuple(BUILTIN_MODELS), default_text=_ONE_OF,
                     doc="A built-in model instead of a case: `taut_string`, the released taut "
                     "string of cases/taut_string.md (a verification of the method)."),
    "base_overrides": Setting("array of strings", default=[], doc="`--set` texts "
                              "(`path.to.key=VALUE`) applied to every run of the case."),
    "surrogate_samples": Setting("integer", ge=100, le=1_000_000,
                                 default=DEFAULT_SURROGATE_SAMPLES,
                                 doc="Samples of the surrogate from which the output statistics "
                                 "and densities are estimated."),
    "inputs": Setting("tables", doc="The uncertain inputs, one table each; a distribution's "
                      "parameters are in the unit of its key."),
    "method": Setting("table", doc="How the surrogate's coefficients are computed."),
    "parameters": Setting("table", default={}, doc="The built-in model's parameters that are "
                          "not uncertain (`model`); the model's own value where not given."),
    "quantities": Setting("tables", default_text="required with `case`", doc="The quantities "
                          "of interest the surrogate is built for (with `case`)."),
})
#: ``[[inputs]]``: a distribution's parameters (floatmoor.uq.inputs.DISTRIBUTIONS) are in the
#: unit of its key, whatever that is.
_INPUT = SettingTable("inputs[]", {
    "key": Setting("string", doc="What is uncertain: a `--set` key path of the case (e.g. "
                   "`line_types.chain.normal_drag_coefficient`), or a parameter of the built-in "
                   "model."),
    "distribution": Setting("string", choices=tuple(DISTRIBUTIONS), doc="Probability "
                            "distribution of the input; its parameters are the keys below that "
                            "it needs."),
    "lower": Setting("number", unit="", doc="Lower bound (`uniform`, `truncated_normal`, "
                     "`beta`, `triangular`)."),
    "upper": Setting("number", unit="", doc="Upper bound (`uniform`, `truncated_normal`, "
                     "`beta`, `triangular`)."),
    "mean": Setting("number", unit="", doc="Mean (`normal`, `lognormal`: of the variable "
                    "itself; `truncated_normal`: of the normal before truncation)."),
    "std": Setting("number", unit="", doc="Standard deviation (`normal`, `lognormal`, "
                   "`truncated_normal`, as for `mean`)."),
    "alpha": Setting("number", unit="", doc="First shape parameter (`beta`)."),
    "beta": Setting("number", unit="", doc="Second shape parameter (`beta`): density "
                    "proportional to (x - lower)^(alpha - 1) (upper - x)^(beta - 1)."),
    "mode": Setting("number", unit="", doc="Most likely value (`triangular`)."),
    "shape": Setting("number", unit="", doc="Shape parameter k (`gamma`): density proportional "
                     "to (x - location)^(k - 1) exp(-rate (x - location))."),
    "rate": Setting("number", unit="", doc="Rate parameter, in 1 / the unit of the key "
                    "(`gamma`)."),
    "location": Setting("number", unit="", doc="Lower bound of the support (`gamma`)."),
})
_METHOD = SettingTable("method", {
    "kind": Setting("string", choices=_METHODS, doc="`quadrature` (Gauss rule, (order + "
                    "1)^inputs runs) or `regression` (least squares on a sampled design)."),
    "order": Setting("integer", ge=1, le=MAX_ORDER, doc="Total polynomial order of the "
                     "surrogate."),
    "q_norm": Setting("number", unit="", ge=MIN_Q_NORM, le=1.0, doc="Hyperbolic truncation of "
                      "the polynomial basis, 1 for the full total order (`regression`)."),
    "samples": Setting("integer", ge=2, le=MAX_RUNS, doc="Number of runs of the design "
                       "(`regression`)."),
    "seed": Setting("integer", ge=0, le=MAX_SEED, doc="Seed of the sampled design "
                    "(`regression`)."),
})


def _parameter(parameter: ModelParameter) -> Setting:
    """``[parameters]`` key of a built-in model's parameter, as the model declares it."""
    what = parameter.long_name
    return Setting("number", unit=parameter.units, default_text="the model's value",
                   doc=f"{what[:1].upper()}{what[1:]} [{parameter.units}].")


#: ``[parameters]`` of each built-in model, from the model's own parameters.
_PARAMETERS = {name: SettingTable("parameters", {key: _parameter(parameter) for key, parameter
                                                 in model.parameters.items()})
               for name, model in BUILTIN_MODELS.items()}
_QUANTITY = SettingTable("quantities[]", {
    "name": Setting("string", doc="Name of the quantity: letters, digits and _, starting with "
                    "a letter."),
    "line": Setting("string", allowed_text="the name of a line of the case", doc="A line of the "
                    "case, whose fairlead tension is the quantity; instead of `dof`."),
    "dof": Setting("string", allowed_text='"Surge", "Sway", "Heave", "Roll", "Pitch" or "Yaw" '
                   "(with a floater)", doc="A DOF of the case's floater, whose motion is the "
                   "quantity; instead of `line`."),
    "statistic": Setting("string", choices=LINE_STATISTICS, doc="Statistic of the time series "
                         "after the ramp (`max`, `mean_cycle_max` for a periodic motion, `std`, "
                         "`mean`, `min`) or `history`, its samples over `window`."),
    "window": Setting("vector", size=2, unit="s", ge=0.0,
                      allowed_text="0 <= start < end <= simulation.duration, two samples or "
                      "more", doc="Time window [start, end] of a `history`."),
})
#: Every declared table of a study file, for the reference page (floatmoor.uq.input_reference).
STUDY_TABLES: tuple[SettingTable, ...] = (_TOP, _INPUT, _METHOD, *_PARAMETERS.values(),
                                          _QUANTITY)


@dataclass(frozen=True)
class Quantity:
    """One quantity of interest.

    ``target`` is a line name (``kind`` "line": fairlead tension [N]), a DOF name (``kind``
    "dof": displacement [m or rad]) or the built-in model's output (``kind`` "model").
    ``window`` is the [start, end] time window [s] of a history, else None.
    """

    name: str
    kind: str
    target: str
    statistic: str
    window: tuple[float, float] | None = None
    units: str = ""

    @property
    def is_history(self) -> bool:
        """Whether the quantity is a vector over time."""
        return self.statistic == HISTORY

    def describe(self) -> str:
        """A short description for long names and captions."""
        what = {"line": f"fairlead tension of line {self.target}",
                "dof": f"{self.target} displacement",
                "model": f"output {self.target} of the model"}[self.kind]
        if self.kind == "model":
            return what
        if self.is_history:
            return f"{what} over t = {self.window[0]:g} to {self.window[1]:g} s"
        if self.statistic == "mean_cycle_max":
            return f"mean of the per-cycle maxima of the {what} after the ramp"
        return f"{self.statistic} of the {what} after the ramp"


@dataclass(frozen=True)
class Study:
    """A checked study file (:func:`load_study`)."""

    path: str  #: the study file as given
    text: str  #: its text (stored in the results)
    title: str
    inputs: tuple[UncertainInput, ...]
    method: QuadratureMethod | RegressionMethod
    quantities: tuple[Quantity, ...]
    case: str | None = None  #: case file path (resolved against the study's folder)
    model: str | None = None  #: built-in model name
    parameters: dict[str, float] = field(default_factory=dict)  #: the model's fixed ones
    base_overrides: tuple[str, ...] = ()
    surrogate_samples: int = DEFAULT_SURROGATE_SAMPLES

    @property
    def keys(self) -> tuple[str, ...]:
        """The uncertain inputs' keys, in order."""
        return tuple(inp.key for inp in self.inputs)

    @property
    def method_name(self) -> str:
        """``quadrature`` or ``regression``."""
        return "quadrature" if isinstance(self.method, QuadratureMethod) else "regression"


def load_study(path: str | FilePath) -> Study:
    """Read and check a study file.

    Raises
    ------
    CaseError
        For any problem with the study file, its case, a key or a quantity; nothing has been
        run or written.
    """
    source = str(path)
    text = read_input_text(path, "study")
    root = TableReader(parse_toml(text, source), (), ReadContext(source))
    title = _TOP.read(root, "title")
    has_case, has_model = root.has("case"), root.has("model")
    if has_case == has_model:
        raise _error(root, "case", 'either case = "FILE.toml" or model = "NAME" (one of '
                     'them)', "both case and model" if has_case else "neither")
    inputs = _inputs(root)
    method = _method(_TOP.table(root, "method"), len(inputs))
    _probe_inputs(root, inputs, method.order)
    samples = _TOP.read(root, "surrogate_samples")
    if has_model:
        model_name, parameters = _model(root, inputs)
        if root.has("quantities"):
            raise root.error("quantities", "no [[quantities]] with a built-in model (its "
                             "output is the one quantity)", root.data["quantities"])
        model = BUILTIN_MODELS[model_name]
        quantities = (Quantity(model.output_name, "model", model.output_name, "value",
                               units=model.output_units),)
        root.finish()
        return Study(source, text, title, inputs, method, quantities, model=model_name,
                     parameters=parameters, surrogate_samples=samples)
    case_path, base, overrides = _case(root, FilePath(source).parent)
    _check_keys(root, case_path, overrides, inputs)
    quantities = _quantities(root, base)
    root.finish()
    return Study(source, text, title, inputs, method, quantities, case=case_path,
                 base_overrides=overrides, surrogate_samples=samples)


def nominal_values(inputs: Sequence[UncertainInput]) -> np.ndarray:
    """The inputs' means: the weighted mean of the nodes of a Gauss rule, exact for any rule
    that integrates degree-1 polynomials exactly."""
    nodes, weights = design(list(inputs), QuadratureMethod(1))
    return np.asarray(weights, dtype=float) @ np.asarray(nodes, dtype=float)


def _error(t: TableReader, key: str | tuple[str | int, ...], expected: str,
           found: str) -> CaseError:
    """An error at ``key`` of ``t`` with an already worded ``found``."""
    return t.context.error(t.path + (key if isinstance(key, tuple) else (key,)), expected,
                           found)


# -- sections -----------------------------------------------------------------------------------

def _inputs(root: TableReader) -> tuple[UncertainInput, ...]:
    inputs: list[UncertainInput] = []
    for t in _TOP.tables(root, "inputs"):
        key = _INPUT.read(t, "key")
        if any(inp.key == key for inp in inputs):
            raise t.error("key", "a key given once among the inputs", key)
        name = _INPUT.read(t, "distribution")
        parameters = {p: _INPUT.read(t, p) for p in DISTRIBUTIONS[name]}
        t.finish()
        inp = UncertainInput(key, name, parameters)
        try:
            check_input(inp)
        except ValueError as err:
            raise t.context.error(t.path, f"valid {name} parameters ({err})", ", ".join(
                f"{k} = {v:g}" for k, v in parameters.items())) from None
        inputs.append(inp)
    return tuple(inputs)


def _method(t: TableReader, dimension: int) -> QuadratureMethod | RegressionMethod:
    kind = _METHOD.read(t, "kind")
    order = _METHOD.read(t, "order")
    if kind == "quadrature":
        runs = (order + 1) ** dimension
        if runs > MAX_RUNS:
            raise _error(t, "order", f"an order giving at most {MAX_RUNS} runs ((order + 1)^"
                          f"{dimension} with {dimension} inputs)", f"{order} ({runs} runs)")
        t.finish()
        return QuadratureMethod(order)
    q_norm = _METHOD.read(t, "q_norm")
    size = hyperbolic_basis_size(dimension, order, q_norm, MAX_BASIS_SIZE)
    if size <= MAX_BASIS_SIZE:  # small enough to enumerate: OpenTURNS' own count (its strata
        # may add a few indices at the boundary)
        size = ot.HyperbolicAnisotropicEnumerateFunction(
            dimension, q_norm).getBasisSizeFromTotalDegree(order)
    if size > MAX_BASIS_SIZE:
        raise _error(t, "order", f"an order and q_norm giving at most {MAX_BASIS_SIZE} basis "
                     f"polynomials with {dimension} inputs (floatmoor.uq.study.MAX_BASIS_SIZE)",
                     f"order {order} with q_norm {q_norm:g} (more than {MAX_BASIS_SIZE})")
    samples = _METHOD.read(t, "samples")
    seed = _METHOD.read(t, "seed")
    t.finish()
    return RegressionMethod(order, q_norm, samples, seed)


def _probe_inputs(root: TableReader, inputs: Sequence[UncertainInput], order: int) -> None:
    """Each input's distribution, Gauss rule and basis must be computable (probe_input)."""
    for i, inp in enumerate(inputs):
        problem = probe_input(inp, order)
        if problem:
            raise _error(root, ("inputs", i), f"{inp.distribution} parameters whose "
                         f"distribution, Gauss rule and basis of order {order} are finite "
                         "in double precision", ", ".join(f"{k} = {v:g}" for k, v in
                                                          inp.parameters.items())
                         + f": {problem}")


def hyperbolic_basis_size(dimension: int, order: int, q_norm: float, limit: int) -> int:
    """The number of multi-indices k of ``dimension`` entries with ||k||_q <= ``order``
    (sum k_j^q <= order^q), counted up to ``limit + 1`` and no further (so that the count of a
    huge basis stops early). Counted depth first; a branch of zeros is one path, so the work
    is about ``dimension`` x the count."""
    budget = float(order) ** q_norm * (1.0 + 1e-12)  # the boundary belongs to the set
    count = 0
    stack = [(0, 0.0)]  # (entries fixed, sum of k_j^q so far)
    while stack and count <= limit:
        fixed, used = stack.pop()
        if fixed == dimension:
            count += 1
            continue
        stack.append((fixed + 1, used))  # k_j = 0
        for k in range(1, order + 1):
            total = used + float(k) ** q_norm
            if total > budget:
                break
            stack.append((fixed + 1, total))
    return count


def _model(root: TableReader, inputs: Sequence[UncertainInput]) -> tuple[str, dict[str, float]]:
    name = _TOP.read(root, "model")
    model = BUILTIN_MODELS[name]
    known = tuple(model.parameters)
    for i, inp in enumerate(inputs):
        if inp.key not in known:
            raise root.error(("inputs", i, "key"), f"a parameter of model {name} ("
                             + ", ".join(known) + ")", inp.key)
    t = _TOP.table(root, "parameters")
    fixed = {}
    for key in t.data:
        if key not in known:
            continue  # finish() names it
        if key in {inp.key for inp in inputs}:
            raise t.error(key, "a parameter that is not also an uncertain input",
                          t.data[key])
        fixed[key] = _PARAMETERS[name].read(t, key)
    t.finish()
    return name, fixed


def _case(root: TableReader, folder: FilePath) -> tuple[str, Case, tuple[str, ...]]:
    raw = _TOP.read(root, "case")
    case_path = FilePath(raw) if FilePath(raw).is_absolute() else folder / raw
    if not case_path.is_file():
        raise _error(root, "case", "a case file (path relative to the study file)",
                         f'"{raw}": no such file ({case_path})')
    overrides = _string_list(root, "base_overrides")
    for i, text in enumerate(overrides):
        try:
            parse_override(text, str(case_path))
        except CaseError as err:
            raise _error(root, ("base_overrides", i), "a --set text path.to.key=VALUE",
                             f'"{text}" ({err})') from None
    try:
        base = load_case(case_path, overrides)
    except CaseError as err:
        raise _error(root, "base_overrides" if overrides else "case",
                         "a case that loads" + (" with these overrides" if overrides else ""),
                         f"{err}") from None
    return str(case_path), base, tuple(overrides)


def _string_list(root: TableReader, key: str) -> list[str]:
    value = _TOP.read(root, key)
    expected = "an array of strings"
    if not isinstance(value, list):
        raise root.error(key, expected, value)
    for i, item in enumerate(value):
        if not isinstance(item, str) or not item.strip():
            raise root.error((key, i), "a non-empty string", item)
    return list(value)


def _check_keys(root: TableReader, case_path: str, overrides: Sequence[str],
                inputs: Sequence[UncertainInput]) -> None:
    """Every input key must be a key of the case: the case loads with the input's mean."""
    means = nominal_values(inputs)
    set_by_base = {text.partition("=")[0].strip(): text for text in overrides}
    for i, (inp, mean) in enumerate(zip(inputs, means)):
        if inp.key in set_by_base:
            raise _error(root, ("inputs", i, "key"), "a key not also set by base_overrides",
                             f'"{inp.key}" (base_overrides has "{set_by_base[inp.key]}")')
        text = f"{inp.key}={float(mean)!r}"
        try:
            load_case(case_path, [*overrides, text])
        except CaseError as err:
            raise _error(root, ("inputs", i, "key"), "a --set key path of the case that takes "
                             f"the input's mean {float(mean):g}",
                             f'"{inp.key}", which the case refuses: {err}') from None


def _quantities(root: TableReader, case: Case) -> tuple[Quantity, ...]:
    lines = [line.name for line in case.lines]
    dofs = list(DOFS) if case.floater is not None else []
    times = output_times(case.simulation)
    out: list[Quantity] = []
    for t in _TOP.tables(root, "quantities"):
        name = _QUANTITY.read(t, "name")
        if not _NAME.match(name):
            raise t.error("name", "a name of letters, digits and _ starting with a letter",
                          name)
        if any(q.name == name for q in out):
            raise t.error("name", "a name given once among the quantities", name)
        if t.has("line") == t.has("dof"):
            raise _error(t, "line", 'either line = "NAME" or dof = "NAME" (one of them)',
                         "both line and dof" if t.has("line") else "neither")
        if t.has("line"):
            kind, target = "line", _QUANTITY.read(t, "line", choices=tuple(lines))
            statistic = _QUANTITY.read(t, "statistic")
            units = "N"
            if statistic == "mean_cycle_max" and (case.motion is None
                                                  or case.motion.cycle_period is None):
                raise t.error("statistic", "a statistic the case gives (mean_cycle_max needs "
                              "periodic [motion])", statistic)
        else:
            if not dofs:
                raise t.error("dof", "a line quantity (the case has no [floater])",
                              t.data["dof"])
            kind, target = "dof", _QUANTITY.read(t, "dof", choices=tuple(dofs))
            statistic = _QUANTITY.read(t, "statistic", choices=DOF_STATISTICS)
            units = "m" if DOFS.index(target) < 3 else "rad"
        window = None
        if statistic == HISTORY:
            window = _window(t, times)
        elif t.has("window"):
            raise t.error("window", f'no window (only with statistic = "{HISTORY}"; scalar '
                          "statistics are taken after the ramp)", t.data["window"])
        t.finish()
        out.append(Quantity(name, kind, target, statistic, window, units))
    return tuple(out)


def _window(t: TableReader, times: np.ndarray) -> tuple[float, float]:
    duration = float(times[-1])
    start, end = _QUANTITY.read(t, "window")
    if not start < end <= duration * (1.0 + 1e-12):
        raise t.error("window", f"[start, end] with 0 <= start < end <= {duration:g} s (the "
                      "simulated duration)", [start, end])
    inside = np.count_nonzero((times >= start - 1e-9) & (times <= end + 1e-9))
    if inside < 2:
        raise t.error("window", "a window holding at least two output samples", [start, end])
    return start, end
