"""``assess``'s fast paths give the reference path's verdicts, intensities and fits.

The fast paths (``docs/risk.md``, "Speed"): each solve's free motion stops once its verdict
is certain (``StripeOptions.early_stop``), and the censored fits and their bootstrap use
Newton's method (``AssessOptions.fit_method``). The reference path follows every free
motion to rest and fits with scipy's trust-region method. On zero-padded records (as the
embedded suites', whose trailing zeros are free motion) and towers that run all three
models, both must give the same stripe counts, the same statuses, theta_max/alpha to the
integration's accuracy, the same IDA scale factors and the same fits to 1e-6.
"""

from __future__ import annotations

from functools import partial

import pytest

from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.assess.stripes import StripeOptions

from rockscreen_testsupport.records import suite_record
from rockscreen_testsupport.towers import block_tower

MESSINA = (38.1, 15.65)  # lat, lon [deg]
#: Relative agreement of theta_max/alpha and of the fitted values [-].
RTOL = 1e-6
FLOOR_DATA = {"building_height_m": 10.0, "base_height_m": 8.0}
DOUBLE_DATA = {"tower_mass_kg": 3e4, "building_mass_kg": 1e6, "mu_s": 1.0, "mu_k": 0.7}


#: 10 s of motion at 100 Hz, then 20 s of zeros (one length, as the embedded suites).
_record = partial(
    suite_record,
    seed_base=40,
    n_samples=1000,
    pga_m_s2=2.5,
    frequency_hz=(1.2, 0.3),
    envelope_duration_s=6.0,
    pad_samples=2000,
    name="P-{i:02d}",
)


_tower = partial(block_tower, site=MESSINA)


@pytest.fixture(scope="module")
def both_paths():
    suite = [_record(i) for i in range(8)]
    towers = [
        _tower("G1", 1.5, 0.12),
        _tower("G2", 3.0, 0.20),
        _tower("F1", 2.0, 0.15, **FLOOR_DATA),
        _tower("D1", 2.0, 0.15, **FLOOR_DATA, **DOUBLE_DATA),
    ]
    common = {
        "return_periods_y": (201.0, 475.0, 975.0),
        "selection": {"n_records": 7},
        "allow_noncompliant": True,
        "bootstrap_resamples": 60,
    }
    fast = run_assess(towers, AssessOptions(**common), SerialExecutor(), suite=suite)
    reference = run_assess(
        towers,
        AssessOptions(stripe=StripeOptions(early_stop=False), fit_method="trust-exact", **common),
        SerialExecutor(),
        suite=suite,
    )
    return fast, reference


def test_same_stripe_counts_and_statuses(both_paths):
    fast, reference = both_paths
    assert fast.stripes == reference.stripes
    assert len(fast.outcomes) == len(reference.outcomes) > 0
    moved = 0
    for a, b in zip(fast.outcomes, reference.outcomes, strict=True):
        assert {k: a[k] for k in a if k != "theta_max_over_alpha"} == {
            k: b[k] for k in b if k != "theta_max_over_alpha"
        }
        ratio, expected = a["theta_max_over_alpha"], b["theta_max_over_alpha"]
        if not a["overturned"]:
            assert ratio == pytest.approx(expected, rel=RTOL, nan_ok=True)
        moved += a["status"] == "came_to_rest"
    assert moved > 0
    assert {o["model"] for o in fast.outcomes} == {"ground", "floor", "double"}


def test_same_ida_intensities(both_paths):
    fast, reference = both_paths
    assert len(fast.ida) == len(reference.ida) > 0
    for a, b in zip(fast.ida, reference.ida, strict=True):
        assert {k: a[k] for k in a if k != "n_solves"} == {k: b[k] for k in b if k != "n_solves"}
        assert a["n_solves"] == b["n_solves"]
    assert any(not row["censored"] for row in fast.ida)


def test_same_fits_and_indices(both_paths):
    fast, reference = both_paths
    for a, b in zip(fast.summary, reference.summary, strict=True):
        assert a.keys() == b.keys()
        for key, expected in b.items():
            value = a[key]
            if isinstance(expected, float) and not isinstance(expected, bool):
                assert value == pytest.approx(expected, rel=RTOL, nan_ok=True), key
            elif key != "note":
                assert value == expected, key
