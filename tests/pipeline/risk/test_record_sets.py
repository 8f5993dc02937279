"""A site's record set that could not be made is a typed :class:`FailedSet`, not a string."""

from __future__ import annotations

import math

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.hazard.selection import SuiteRecord
from rockscreen.pipeline.risk.assess.record_sets import FailedSet, failed_set, is_failed
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.verdict.messages import note_messages, render
from rockscreen.stations.inventory import Tower

MESSINA = (38.1, 15.65)  # lat, lon [deg]


def test_a_failed_set_carries_its_site_return_period_and_reason():
    key = (15.65, 38.1, "B", "T1")
    failed = failed_set(key, 475, ValueError("the suite has 2 records, 7 are needed"))
    assert isinstance(failed, FailedSet) and is_failed(failed)
    assert failed.key == key and failed.tr == 475.0
    assert failed.reason.code == "site.records_failed"
    assert failed.reason_text == (
        "record set at lon=15.65 lat=38.1 TR=475 y: the suite has 2 records, 7 are needed"
    )
    assert render(failed.reason, "it").startswith("insieme di registrazioni a lon=15,65 lat=38,1")
    assert not is_failed("record set at lon=15.65 lat=38.1 TR=475 y: no record")


def test_a_tower_whose_record_set_fails_is_a_selection_failure_with_its_note(monkeypatch):
    def no_set(lon, lat, tr, *args, **kwargs):
        raise HazardError(f"no record of the suite matches the spectrum at TR={tr:g} y")

    monkeypatch.setattr("rockscreen.pipeline.risk.assess.worker.site_record_set", no_set)
    rng = np.random.default_rng(3)
    suite = [
        SuiteRecord(f"S-{i}", *(rng.normal(0, 0.5, 800) for _ in range(3)), 0.01, "test")
        for i in range(2)
    ]
    alpha, radius = 0.15, 2.0
    tower = Tower(
        id="T1",
        width_m=2 * radius * math.sin(alpha),
        height_m=2 * radius * math.cos(alpha),
        lat=MESSINA[0],
        lon=MESSINA[1],
    )
    options = AssessOptions(return_periods_y=(475.0,), selection={"n_records": 7})
    result = run_assess([tower], options, SerialExecutor(), suite=suite)
    (failure,) = [f for f in result.failures if f["subject"] == "T1"]
    assert failure["kind"] == "selection"
    assert failure["reason"].startswith("record set at lon=15.65 lat=38.1 TR=")
    assert failure["reason"].endswith("no record of the suite matches the spectrum at TR=475 y")
    (row,) = result.summary
    codes = [m.code for m in note_messages(row)]
    assert "site.records_failed" in codes
    assert result.selection == []
