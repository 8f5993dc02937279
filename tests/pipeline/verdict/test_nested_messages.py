"""Messages inside messages (a clause inside a clause) and a row's note columns."""

import math

import numpy as np
import pytest

from rockscreen.pipeline.verdict.catalogue import SUBJECTS
from rockscreen.pipeline.verdict.messages import (
    MessageSpec,
    catalogue,
    dumps,
    loads,
    message,
    note_columns,
    note_messages,
    register,
    render,
)

register(
    MessageSpec("test.outer", "outer: {inner}", "esterno: {inner}"),
    MessageSpec("test.list", "items {items:, }", "voci {items:, }"),
    MessageSpec("test.x", "x = {x:.2f}", "x = {x:.2f}"),
)


def test_a_message_inside_a_message_renders_in_the_same_language():
    inner = (message("test.x", x=np.float64(0.5)), message("test.x", x=2))
    outer = message("test.outer", inner=inner)
    assert render(outer) == "outer: x = 0.50; x = 2.00"
    assert render(outer, "it") == "esterno: x = 0,50; x = 2,00"
    listed = message("test.list", items=list(inner))
    assert render(listed) == "items x = 0.50, x = 2.00"
    assert render(listed, "it") == "voci x = 0,50, x = 2,00"
    assert isinstance(inner[0].kwargs["x"], float) and hash(listed)  # plain and hashable


def test_nested_messages_round_trip_and_are_checked():
    outer = message("test.outer", inner=message("test.x", x=math.nan))
    (back,) = loads(dumps([outer]))
    assert back.code == "test.outer" and math.isnan(back.kwargs["inner"].kwargs["x"])
    with pytest.raises(ValueError, match="not in this rockscreen's catalogue"):
        loads('[["test.outer", {"inner": {"code": "no.such", "params": {}}}]]')
    with pytest.raises(ValueError, match="code, params"):
        loads('[["test.outer", {"inner": {"text": "English"}}]]')
    with pytest.raises(TypeError, match="expected a number"):
        message("test.x", x=object())


def test_a_rows_note_columns():
    said = [message("test.x", x=1.0), message("test.x", x=2.5)]
    columns = note_columns(said)
    assert columns["note"] == "x = 1.00; x = 2.50"
    assert note_messages(columns) == tuple(said)
    assert note_messages({"note": "older"}) is None  # an archive before note codes
    assert note_messages({"note_codes": math.nan}) is None
    assert note_messages(note_columns(())) == ()


def test_every_subject_is_loaded_and_its_codes_prefixed():
    codes = catalogue()
    assert {"run.sf_cap", "fit.collapse", "lv1model.model", "scenario.p_bound"} <= set(codes)
    assert "general" in SUBJECTS and len(SUBJECTS) == len(set(SUBJECTS))
    assert all("." in code for code in codes)


def test_every_code_the_pipeline_names_is_in_the_catalogue():
    """A typo in a rare branch's code fails here, not on a user's tower."""
    import re
    from pathlib import Path

    import rockscreen.pipeline as pipeline

    codes = catalogue()
    prefixes = sorted({code.split(".")[0] for code in codes} - {"test"})
    literal = re.compile(rf'"((?:{"|".join(prefixes)})\.[a-z0-9_]+)"')
    named = set()
    for path in Path(pipeline.__file__).parent.rglob("*.py"):
        if "verdict" in path.parts:
            continue
        named |= set(literal.findall(path.read_text(encoding="utf-8")))
    assert len(named) > 60
    assert sorted(named - set(codes)) == []


def test_every_part_model_names_its_fragility_in_the_catalogue():
    """A new part model (engine registry) needs its ``fit.part_<name>`` entry."""
    from rockscreen.pipeline.risk.checks.tower_checks import part_model_names

    names = part_model_names()
    assert names
    assert [n for n in names if f"fit.part_{n}" not in catalogue()] == []
