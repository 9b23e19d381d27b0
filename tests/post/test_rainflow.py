"""Rainflow counting (ASTM E1049-85 (2017) section 5.4.4) against the standard's example and
against an independent four-point implementation (tests/oracles/rainflow_numpy.py)."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from floatmoor.post.rainflow import aggregate_ranges, rainflow_cycles, turning_points
from tests.oracles import rainflow_numpy as oracle


pytestmark = pytest.mark.oracle

#: ASTM E1049-85 (reapproved 2017), Fig. 6(a): the load history of the rainflow example.
ASTM_HISTORY = [-2.0, 1.0, -3.0, 5.0, -1.0, 3.0, -4.0, 4.0, -2.0]
#: Its published result (the standard's Fig. 6 table; the same values are the reference of the
#: test suite of the PyPI package ``rainflow``): range -> cycles.
ASTM_RANGES = [3.0, 4.0, 6.0, 8.0, 9.0]
ASTM_COUNTS = [0.5, 1.5, 0.5, 1.0, 0.5]


def test_astm_e1049_example_gives_the_published_cycles_exactly():
    cycles = rainflow_cycles(ASTM_HISTORY)
    ranges, counts = aggregate_ranges(cycles.ranges, cycles.counts)
    assert ranges.tolist() == ASTM_RANGES
    assert counts.tolist() == ASTM_COUNTS


def test_astm_e1049_example_counting_order_and_means():
    # Section 5.4.4 step by step: A-B (3) half, B-C (4) half, E-F (4) full, C-D (8) half,
    # then the residue D-G (9), G-H (8), H-I (6) as half cycles.
    cycles = rainflow_cycles(ASTM_HISTORY)
    assert cycles.ranges.tolist() == [3.0, 4.0, 4.0, 8.0, 9.0, 8.0, 6.0]
    assert cycles.counts.tolist() == [0.5, 0.5, 1.0, 0.5, 0.5, 0.5, 0.5]
    assert cycles.means.tolist() == [-0.5, -1.0, 1.0, 1.0, 0.5, 0.0, 1.0]


def test_samples_between_reversals_and_plateaus_change_nothing():
    # The example sampled densely (straight lines between reversals) with repeated samples.
    dense = np.concatenate([np.linspace(a, b, 7)[:-1] for a, b in
                            zip(ASTM_HISTORY[:-1], ASTM_HISTORY[1:])] + [[ASTM_HISTORY[-1]]])
    dense = np.repeat(dense, 2)
    np.testing.assert_array_equal(turning_points(dense), ASTM_HISTORY)
    cycles = rainflow_cycles(dense)
    ranges, counts = aggregate_ranges(cycles.ranges, cycles.counts)
    assert ranges.tolist() == ASTM_RANGES and counts.tolist() == ASTM_COUNTS


def test_short_and_constant_records():
    assert rainflow_cycles([1.0, 1.0, 1.0]).ranges.size == 0
    assert rainflow_cycles([]).ranges.size == 0
    one = rainflow_cycles([0.0, 2.0])
    assert one.ranges.tolist() == [2.0] and one.counts.tolist() == [0.5]
    with pytest.raises(ValueError, match="NaN"):
        rainflow_cycles([0.0, np.nan, 1.0])


def _by_range_and_mean(ranges, means, counts) -> Counter:
    total: Counter = Counter()
    for r, m, c in zip(ranges, means, counts):
        total[(float(r), float(m))] += float(c)
    return total


@pytest.mark.parametrize("seed", range(5))
def test_kernel_matches_the_four_point_oracle(seed):
    # Integer-valued random records: many ties, where the two methods' comparisons must agree.
    rng = np.random.default_rng(seed)
    for _ in range(40):
        x = rng.integers(-6, 7, size=int(rng.integers(1, 400))).astype(float)
        np.testing.assert_array_equal(turning_points(x), oracle.reversals(x))
        mine = rainflow_cycles(x)
        ref = oracle.four_point_cycles(x)
        assert _by_range_and_mean(*mine) == _by_range_and_mean(*ref)
        # every reversal-to-reversal range is counted exactly once (full = two halves)
        assert 2.0 * mine.counts.sum() == pytest.approx(max(turning_points(x).size - 1, 0))
