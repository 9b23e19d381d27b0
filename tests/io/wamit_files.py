"""WAMIT numeric files written by tests from known SI values: first-order files from a
floatmoor database (``write_wamit``), mean drift ``.8``/``.9`` and difference-frequency QTF
``.12d`` lines in WAMIT's layout, normalisation (rho g A^2 ULEN^k) and e^{+i omega t} phases."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

#: A WAMIT numeric file's first line (skipped by the reader).
HEADER = " WAMIT Numeric Output -- Filename  test.9     28-Nov-2026  12:00:00"


def scale(rho: float, g: float, ulen: float, mode: int) -> float:
    """rho g L^k of WAMIT's second-order normalisation (k = 1 forces, 2 moments)."""
    return rho * g * ulen ** (1 if mode <= 3 else 2)


def polar(x: complex) -> str:
    """``Mod Pha Re Im`` columns of a complex value (phase in degrees)."""
    return (f"{abs(x): .6E} {math.degrees(math.atan2(x.imag, x.real)):12.5f} "
            f"{x.real: .6E} {x.imag: .6E}")


def drift_lines(periods, betas, value, modes=(1, 2, 3, 4, 5, 6), header=True):
    """``PER BETA1 BETA2 I Mod Pha Re Im`` lines; ``value(per, beta, i)`` non-dimensional."""
    lines = [HEADER] if header else []
    for per in periods:
        for beta in betas:
            for i in modes:
                lines.append(f"  {per: .6E}  {beta: .6E}  {beta: .6E} {i:5d} "
                             + polar(complex(value(per, beta, i))))
    return lines


def qtf_lines(periods, value, beta=0.0, triangle="wamit", header=True):
    """``PER1 PER2 BETA1 BETA2 I Mod Pha Re Im`` lines of a WAMIT (e^{+i omega t}) QTF
    ``value(per1, per2, i)``, non-dimensional; ``triangle``: "wamit" (PER1 <= PER2, as WAMIT
    writes), "other" (PER1 >= PER2) or "both"."""
    lines = [HEADER] if header else []
    for p2 in periods:
        for p1 in periods:
            keep = {"wamit": p1 <= p2, "other": p1 >= p2, "both": True}[triangle]
            if not keep:
                continue
            for i in range(1, 7):
                lines.append(f"  {p1: .6E}  {p2: .6E}  {beta: .6E}  {beta: .6E} {i:5d} "
                             + polar(complex(value(p1, p2, i))))
    return lines


def write(folder: Path, name: str, lines) -> Path:
    path = Path(folder) / name
    path.write_text("".join(line + "\n" for line in lines))
    return path


def write_wamit(folder: Path, ds, stem: str = "body") -> dict[str, Path]:
    """The database's added mass, damping, A_inf, excitation and hydrostatics as WAMIT
    ``.1``, ``.3`` and ``.hst`` (ULEN = 1, about the database's rotation centre)."""
    from floatmoor.hydro.database import merge_complex

    rho, g = float(ds.attrs["water_density"]), float(ds.attrs["gravity"])
    omega = ds["omega"].values
    order = ("omega", "radiating_dof", "influenced_dof")
    a = ds["added_mass"].transpose(*order).values
    b = ds["radiation_damping"].transpose(*order).values
    a_inf = ds["added_mass_infinite"].transpose("radiating_dof", "influenced_dof").values
    one = [f"  {0.0: .6E} {i:5d} {j:5d} {a_inf[j - 1, i - 1] / rho: .6E}"
           for i in range(1, 7) for j in range(1, 7)]
    for w in range(len(omega)):
        per = 2 * math.pi / omega[w]
        one += [f"  {per: .6E} {i:5d} {j:5d} {a[w, j - 1, i - 1] / rho: .6E} "
                f"{b[w, j - 1, i - 1] / (rho * omega[w]): .6E}"
                for i in range(1, 7) for j in range(1, 7)]
    x = merge_complex(ds, "excitation_force").transpose(
        "omega", "wave_direction", "influenced_dof").values
    betas = np.degrees(ds["wave_direction"].values)
    three = []
    for w in range(len(omega)):
        for h, beta in enumerate(betas):
            for i in range(1, 7):
                value = np.conj(x[w, h, i - 1]) / (rho * g)
                three.append(f"  {2 * math.pi / omega[w]: .6E}  {beta: .6E} {i:5d} "
                             + polar(complex(value)))
    c = ds["hydrostatic_stiffness"].transpose("influenced_dof", "radiating_dof").values
    hst = [f"{i:6d}{j:6d}  {c[i - 1, j - 1] / (rho * g): .6E}"
           for i in range(1, 7) for j in range(1, 7)]
    return {".1": write(folder, f"{stem}.1", one), ".3": write(folder, f"{stem}.3", three),
            ".hst": write(folder, f"{stem}.hst", hst)}
