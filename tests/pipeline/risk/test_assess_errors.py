"""Issue 30: an unexpected error in one tower's work is that tower's failure, not the run's.

A tower whose work raises (here through the test seam of the engine's solvers: a block
builder that raises for one tower's height) is listed in ``/failures`` (kind ``error``,
the exception named) with an ``undefined`` summary row; the other towers are assessed,
the archive is written and the command's last line counts it.
"""

from __future__ import annotations

from functools import partial

from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.engine.solvers import Solvers, use_solvers
from rockscreen.pipeline.report.risk_summary import not_assessed_line
from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive
from rockscreen.pipeline.risk.assess.run import AssessOptions
from rockscreen.pipeline.risk.assess.stripes import StripeOptions
from rockscreen.pipeline.verdict.messages import loads
from rockscreen.solver.block import RockingBlock
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record

#: The height of the tower whose work raises [m].
BROKEN_HEIGHT_M = 9.0


_record = partial(suite_record, seed_base=200, frequency_hz=(1.5, 0.5), name="R-{i}")


def _block(width: float, height: float, **kwargs):
    """The real block, except for the broken tower: an error no stage foresees."""
    if height == BROKEN_HEIGHT_M:
        raise ZeroDivisionError("a seam's error\nover two lines")
    return RockingBlock.from_dimensions(width, height, **kwargs)


def test_a_tower_that_raises_is_a_failure_and_the_others_are_assessed(tmp_path):
    towers = [
        Tower(id=f"LE-{i}", width_m=2.0, height_m=h, lat=40.2, lon=18.0, soil_class="B")
        for i, h in ((1, 8.0), (2, BROKEN_HEIGHT_M), (3, 10.0))
    ]
    options = AssessOptions(
        return_periods_y=(475.0,),
        stripe=StripeOptions(models=("ground",)),
        selection={"n_records": 7, "scale_limits": (0.1, 4.0), "tolerance": (-0.5, 1.0)},
        bootstrap_resamples=0,
        allow_noncompliant=True,
    )
    inputs = AssessInputs(
        inventory=tmp_path / "towers.csv", suite=[_record(i) for i in range(10)],
        suite_label="test",
    )  # fmt: skip
    out = tmp_path / "a.h5"
    with use_solvers(Solvers(block=_block)):
        result = assess_to_archive(towers, options, out, inputs, jobs=1, notify=lambda t: None)
    by_id = {row["id"]: row for row in result.summary}
    assert list(by_id) == ["LE-1", "LE-2", "LE-3"]
    assert by_id["LE-2"]["risk_class"] == "undefined" and by_id["LE-2"]["n_solves"] == 0
    assert by_id["LE-2"]["note"] == (
        "not assessed: an unexpected error in its computation (ZeroDivisionError: a seam's "
        "error over two lines); in /failures (rockscreen inspect)"
    )
    for tower in ("LE-1", "LE-3"):
        assert by_id[tower]["n_solves"] > 0 and by_id[tower]["risk_class"] != "undefined"
    # the screening risk says why the failed tower has none (issue 31); the others have one
    assert [m.code for m in loads(by_id["LE-2"]["risk_note_codes"])] == ["risk.failed"]
    assert all(by_id[t]["risk_rank"] > 0 for t in ("LE-1", "LE-3"))
    assert {row["tower_id"] for row in result.ida} == {"LE-1", "LE-3"}
    (failure,) = result.failures
    assert failure == {
        "kind": "error",
        "subject": "LE-2",
        "reason": "tower LE-2: ZeroDivisionError: a seam's error over two lines",
    }
    assert out.exists() and not out.with_name("a.h5.part").exists()
    assert not_assessed_line(result.failures, 3, str(out)).startswith(
        "1 of 3 tower(s) not assessed (1 error); each with its reason and fix in /failures"
    )
    shown = CliRunner().invoke(main, ["inspect", str(out)])
    assert shown.exit_code == 0, shown.output
    assert "  error: LE-2: tower LE-2: ZeroDivisionError: a seam's error" in shown.stdout
