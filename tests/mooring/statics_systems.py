"""Small mooring systems for the statics tests, built from the case schema's objects.

Depth 200 m. Chain: 115 kg/m, EA 4.93e8 N, steel density (a 76 mm studless chain); rope:
8 kg/m, EA 1.5e8 N, 1380 kg/m^3 (polyester). Seabed friction off (C_B = 0), as MoorPy 1.3
applies none to a line end resting on the seabed.
"""

from __future__ import annotations

import math

from floatmoor.case.schema import (
    DynamicSettings, Environment, Line, LineType, Point, QuasiStaticSettings, Seabed, Section,
)

ENVIRONMENT = Environment(water_density=1025.0, water_depth=200.0, gravity=9.81)
SEABED = Seabed(stiffness=1e5, damping_ratio=1.0, friction_coefficient=0.0, slip_speed=0.01)
QS = QuasiStaticSettings(tolerance=1e-12, max_iterations=100, seabed_friction=False)
DYN = DynamicSettings(elements=10, order=5, cfl=0.8, max_time_step=None, slack_filter=True,
                      seabed_contact="implicit")


def line_type(name: str, mass: float, ea: float, density: float) -> LineType:
    return LineType(name=name, mass_per_length=mass, axial_stiffness=ea, diameter=0.1,
                    material_density=density, normal_drag_coefficient=1.2,
                    tangential_drag_coefficient=0.2, added_mass_coefficient=1.0,
                    tangential_added_mass_coefficient=0.0, internal_damping_ratio=0.0)


CHAIN = line_type("chain", 115.0, 4.93e8, 7850.0)
ROPE = line_type("rope", 8.0, 1.5e8, 1380.0)


def make_line(name: str, pieces, points, qs: QuasiStaticSettings = QS) -> Line:
    """A line of sections ``pieces`` = [(type, length, start, end), ...]."""
    where = {p.name: p.position for p in points}
    sections = tuple(Section(line=name, index=i, line_type=t, length=length, start=a, end=b,
                             dynamic=DYN) for i, (t, length, a, b) in enumerate(pieces))
    return Line(name=name, sections=sections, anchor=where[pieces[0][2]],
                fairlead=where[pieces[-1][3]], model="quasi-static", quasi_static=qs,
                dynamic=DYN, start=pieces[0][2], end=pieces[-1][3])


def at(radius: float, degrees: float, z: float) -> tuple[float, float, float]:
    a = math.radians(degrees)
    return (radius * math.cos(a), radius * math.sin(a), z)


def chain_rope_chain(anchor_x: float = -930.0, buoy_volume: float = 10.0):
    """One line: chain 300 m - clump (3 t, 0.5 m^3) - rope 450 m - buoy (2 t, 10 m^3) -
    chain 200 m to a body point 20 m below the surface."""
    points = [Point("anchor", "fixed", (anchor_x, 0.0, -200.0)),
              Point("clump", "free", (-520.0, 0.0, -170.0), mass=3000.0, volume=0.5),
              Point("buoy", "free", (-150.0, 0.0, -60.0), mass=2000.0, volume=buoy_volume),
              Point("fair", "body", (0.0, 0.0, -20.0))]
    line = make_line("l1", [(CHAIN, 300.0, "anchor", "clump"), (ROPE, 450.0, "clump", "buoy"),
                            (CHAIN, 200.0, "buoy", "fair")], points)
    return points, [line]


def three_lines():
    """Three lines at 120 degrees from fairleads 40 m off the body's axis, 15 m deep:
    chain-rope with a clump weight; a rope to a bridle point held by two chains; chain-rope-
    chain with a clump weight and a buoy."""
    points = [Point("f1", "body", at(40.0, 0.0, -15.0)),
              Point("f2", "body", at(40.0, 120.0, -15.0)),
              Point("f3", "body", at(40.0, 240.0, -15.0)),
              Point("a1", "fixed", at(880.0, 0.0, -200.0)),
              Point("c1", "free", at(560.0, 0.0, -170.0), mass=4000.0, volume=0.5),
              Point("a2a", "fixed", at(860.0, 110.0, -200.0)),
              Point("a2b", "fixed", at(860.0, 130.0, -200.0)),
              Point("b2", "free", at(200.0, 120.0, -80.0)),
              Point("a3", "fixed", at(940.0, 240.0, -200.0)),
              Point("c3", "free", at(600.0, 240.0, -180.0), mass=3000.0, volume=0.5),
              Point("u3", "free", at(220.0, 240.0, -70.0), mass=2000.0, volume=10.0)]
    lines = [make_line("l1", [(CHAIN, 300.0, "a1", "c1"), (ROPE, 560.0, "c1", "f1")], points),
             make_line("l2", [(ROPE, 170.0, "f2", "b2")], points),
             make_line("l2a", [(CHAIN, 700.0, "a2a", "b2")], points),
             make_line("l2b", [(CHAIN, 700.0, "a2b", "b2")], points),
             make_line("l3", [(CHAIN, 300.0, "a3", "c3"), (ROPE, 420.0, "c3", "u3"),
                              (CHAIN, 200.0, "u3", "f3")], points)]
    return points, lines
