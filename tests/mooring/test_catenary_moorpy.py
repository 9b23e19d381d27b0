"""The catenary kernel against MoorPy's ``Catenary.catenary`` (NREL, a port of FAST v7's
catenary; Jonkman 2007), a cross-code check of the same closed-form model
(docs/development.md#4-kinds-of-tests).

MoorPy's conventions: it returns (HA, VA, -HF, -VF, info) for end A at the origin and end B
at (XF, ZF); a negative ``CB`` means "no seabed contact, end A is -CB above the seabed"; its
``Tol`` is an absolute error on the end position [m].
"""

from __future__ import annotations

import contextlib
import io
import math

import numpy as np
import pytest

from floatmoor.mooring import _catenary_kernels as k


pytestmark = pytest.mark.peer

catenary = pytest.importorskip("moorpy.Catenary").catenary

#: Both codes solve the same equations; with MoorPy converged to 1e-10 m and ours to 1e-14 L
#: they agree to ~1e-10 of the fairlead tension (observed); 1e-6 is the agreement asked of
#: the quasi-static model against MoorPy in the project brief.
PEER_RTOL = 1e-6
#: MoorPy's absolute tolerance on the end position [m] (its default, 1e-6 m, would limit the
#: agreement to ~1e-6 L / (conditioning), too loose for a meaningful 1e-6 comparison).
MOORPY_TOL = 1e-10
#: Configurations on which MoorPy may fail without failing this test: MoorPy gives up after
#: three Newton attempts and then either raises CatenaryError or returns a last-resort
#: straight-spring / bilinear approximation (ProfileType -1 / -2), which is not the catenary.
#: None occurred in this seeded set when the test was written; allow a few, and report them.
MAX_MOORPY_FAILURES = 3
N_PER_KIND = 15

KINDS = ["suspended, free", "touchdown", "touchdown with friction", "nearly taut",
         "anchor uplift"]


def configurations():
    rng = np.random.default_rng(20261122)
    for kind in KINDS:
        for _ in range(N_PER_KIND):
            L = rng.uniform(100.0, 1500.0)
            W = rng.uniform(100.0, 3000.0)
            EA = W * L * 10 ** rng.uniform(2.5, 5.0)
            CB, seabed = 0.0, 1
            if kind == "suspended, free":  # free line, fairlead above or below the anchor
                seabed = 0
                ratio, angle = rng.uniform(0.7, 0.98), rng.uniform(-0.3, 1.3)
            elif kind == "touchdown":
                ratio, angle = rng.uniform(0.75, 0.97), rng.uniform(0.1, 0.9)
            elif kind == "touchdown with friction":
                CB = rng.uniform(0.1, 1.0)
                ratio, angle = rng.uniform(0.75, 0.97), rng.uniform(0.1, 0.9)
            elif kind == "nearly taut":
                seabed = int(rng.integers(2))
                ratio, angle = rng.uniform(0.995, 1.002), rng.uniform(0.2, 1.2)
            else:  # anchor on the seabed but pulled upward by the line
                ratio, angle = rng.uniform(0.97, 0.995), rng.uniform(0.5, 1.2)
            yield kind, (ratio * L * math.cos(angle), ratio * L * math.sin(angle), L, EA, W, CB,
                         seabed)


def test_tensions_agree_with_moorpy():
    out = np.empty(k.N_OUT_2D)
    worst = dict.fromkeys(KINDS, 0.0)
    profiles = set()
    failures = []
    n = 0
    for kind, (XF, ZF, L, EA, W, CB, seabed) in configurations():
        status = k.catenary_solve(XF, ZF, L, EA, W, CB, seabed, math.nan, math.nan, 1e-14, 100,
                                  out)
        assert status == k.CAT_OK
        ours = out[[k.I_HF, k.I_VF, k.I_HA, k.I_VA]].copy()
        profiles.add(int(out[k.I_PROFILE]))
        if out[k.I_VA] > 0.0:
            profiles.add("anchor uplift")
        if out[k.I_PROFILE] == k.PROFILE_TOUCHDOWN and CB > 0.0:
            profiles.add("friction, anchor loaded" if out[k.I_HA] > 0.0 else
                         "friction, anchor unloaded")
        moorpy_cb = CB if seabed else -10.0 * L  # free line: seabed far below end A
        try:
            with contextlib.redirect_stdout(io.StringIO()):  # MoorPy prints its failures
                fah, fav, fbh, fbv, info = catenary(XF, ZF, L, EA, W, CB=moorpy_cb,
                                                    Tol=MOORPY_TOL, MaxIter=200)
        except Exception as error:  # MoorPy's CatenaryError (or worse)
            failures.append((kind, repr(error)))
            continue
        if info["ProfileType"] in (-1, -2):
            failures.append((kind, info.get("message", "approximation")))
            continue
        theirs = np.array([-fbh, -fbv, fah, fav])
        err = np.max(np.abs(ours - theirs)) / math.hypot(ours[0], ours[1])
        worst[kind] = max(worst[kind], err)
        n += 1
        assert err <= PEER_RTOL, (kind, (XF, ZF, L, EA, W, CB, seabed), ours, theirs)
    print(f"\n{n} configurations compared with MoorPy, {len(failures)} skipped "
          f"(MoorPy failed: {failures}); worst relative difference by kind: "
          + ", ".join(f"{kind} {err:.1e}" for kind, err in worst.items())
          + f" (tolerance {PEER_RTOL:.0e})")
    assert len(failures) <= MAX_MOORPY_FAILURES
    assert n >= 50
    assert {k.PROFILE_SUSPENDED, k.PROFILE_TAUT, k.PROFILE_TOUCHDOWN, "anchor uplift",
            "friction, anchor loaded", "friction, anchor unloaded"} <= profiles
