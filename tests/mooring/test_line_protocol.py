"""One protocol for every line model and system solver (docs/development.md#adding-a-line-model):
the runs ask it for capabilities instead of testing classes, and the simulation's modules
import one way."""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import numpy as np
import pytest

from floatmoor.case.load import load_case
from floatmoor.mooring.dg.line import DynamicLine
from floatmoor.mooring.dg.system import DynamicSystem
from floatmoor.mooring.quasidynamic import QuasiDynamicLine
from floatmoor.mooring.quasistatic import QuasiStaticLine
from floatmoor.mooring.stepping import MooringSolver, PathStepper
from floatmoor.mooring.statics_solver import SystemStatics

REPO = Path(__file__).parents[2]
LINDAHL = REPO / "cases" / "lindahl" / "lindahl_r0.20_T1.25.toml"
SIMULATION = REPO / "floatmoor" / "simulation"
LINES = (QuasiStaticLine, QuasiDynamicLine, DynamicLine)
SYSTEMS = (SystemStatics, DynamicSystem)
#: The class names a run must not switch on.
MODEL_CLASSES = {c.__name__ for c in (*LINES, *SYSTEMS, PathStepper, MooringSolver)}


def _positional(cls: type) -> list[str]:
    params = inspect.signature(cls.solve_path).parameters.values()
    return [p.name for p in params if p.kind == p.POSITIONAL_OR_KEYWORD][1:]


def test_every_model_implements_the_protocol():
    assert all(issubclass(c, PathStepper) for c in LINES)
    assert all(issubclass(c, MooringSolver) for c in SYSTEMS)
    assert [c.has_memory for c in LINES] == [False, True, True]
    assert [c.has_memory for c in SYSTEMS] == [False, True]
    assert [c.batched for c in (*LINES, *SYSTEMS)] == [False, False, True, False, False]
    assert [c.resolves_dynamics for c in (*LINES, *SYSTEMS)] == [False, False, True,
                                                                 False, True]


def test_solve_path_takes_its_arguments_in_one_order():
    """Times, the ends' path and velocities, then the outputs: the same for every line
    model, and for both system solvers."""
    lines = [_positional(c) for c in LINES]
    assert all(p[:6] == ["time", "path", "velocity", "fairlead_force", "anchor_force",
                         "laid_length"] and len(p) == 7 for p in lines), lines
    systems = [_positional(c) for c in SYSTEMS]
    assert all(p[0] == "time" and p[3:6] == ["start_force", "end_force", "laid_length"]
               and len(p) == 8 for p in systems), systems
    assert systems[0][6] == "positions" and systems[1][6] == "point_positions"


def test_quasi_static_line_steps_and_draws_as_the_others():
    case = load_case(LINDAHL, ['lines.chain.model="quasi-static"'])
    line = case.lines[0]
    model = QuasiStaticLine.from_case(line, case.environment, case.seabed)
    path = np.asarray(line.fairlead, dtype=float) + np.array([[0.0, 0.0, 0.0],
                                                              [0.1, 0.0, -0.05]])
    force = model.advance(1.0, path[1], np.zeros(3))
    fairlead, anchor = model.end_forces()
    other = QuasiStaticLine.from_case(line, case.environment, case.seabed)
    solution = other.solve(path[1])
    np.testing.assert_allclose(force, solution.fairlead_force, rtol=1e-9)
    np.testing.assert_allclose(fairlead, solution.fairlead_force, rtol=1e-9)
    np.testing.assert_allclose(anchor, solution.anchor_force, rtol=1e-9)
    positions, tension = model.current_shape(path[1])
    assert positions.shape == (model.arc_length.size, 3) and tension.shape == (positions.shape[0],)
    np.testing.assert_allclose(positions[-1], path[1], atol=1e-6)
    assert model.start_moving(lambda t: (path[:1], np.zeros((1, 3))), 0.1) is False


def _isinstance_on_models(path: Path) -> list[str]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call) and getattr(node.func, "id", "") == "isinstance":
            names = {n.id for n in ast.walk(node.args[1]) if isinstance(n, ast.Name)}
            names |= {n.attr for n in ast.walk(node.args[1]) if isinstance(n, ast.Attribute)}
            if names & MODEL_CLASSES:
                found.append(f"{path.name}:{node.lineno}")
    return found


def test_the_simulation_asks_capabilities_not_classes():
    found = [hit for path in sorted(SIMULATION.glob("*.py")) for hit in
             _isinstance_on_models(path)]
    assert not found, found


def _imported(path: Path) -> set[str]:
    """Every floatmoor module ``path`` imports, TYPE_CHECKING blocks and functions included."""
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom) and node.module:
            out.add(node.module)
        elif isinstance(node, ast.Import):
            out.update(a.name for a in node.names)
    return {m for m in out if m.startswith("floatmoor.")}


@pytest.mark.parametrize("module, runners", [
    ("assembly", {"coupled_run", "forced", "run"}),
    ("groups", {"assembly", "coupled_run", "forced", "coupled", "recorder"}),
])
def test_assembly_and_groups_do_not_import_the_runners(module, runners):
    """The runners build on the assembly and the groups, never the other way (no import
    circle hidden behind TYPE_CHECKING)."""
    imported = _imported(SIMULATION / f"{module}.py")
    assert not {f"floatmoor.simulation.{r}" for r in runners} & imported
