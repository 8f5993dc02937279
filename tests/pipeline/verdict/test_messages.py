import math

import pytest

from rockscreen.pipeline.verdict.messages import (
    LANGUAGES,
    Message,
    MessageSpec,
    catalogue,
    dumps,
    loads,
    message,
    register,
    render,
    render_all,
)
from rockscreen.pipeline.verdict.status import Bound, Status


def test_every_entry_has_both_languages_with_the_same_fields():
    entries = catalogue()
    assert entries
    for spec in entries.values():
        assert spec.en and spec.it, spec.code
        assert spec.fields("en") == spec.fields("it"), spec.code


def test_a_missing_translation_or_field_mismatch_is_refused():
    with pytest.raises(ValueError, match="both"):
        register(MessageSpec("test.no_it", "text {x}", ""))
    with pytest.raises(ValueError, match="fields differ"):
        register(MessageSpec("test.mismatch", "a {x}", "b {y}"))


def test_message_checks_code_and_parameters():
    with pytest.raises(KeyError, match="not in the catalogue"):
        message("no.such.code")
    with pytest.raises(TypeError, match="takes"):
        message("basis.noncompliant")


def test_numbers_take_the_languages_decimal_separator():
    register(MessageSpec("test.number", "ag = {ag:.3f} g", "ag = {ag:.3f} g"))
    msg = message("test.number", ag=0.254)
    assert render(msg, "en") == "ag = 0.254 g"
    assert render(msg, "it") == "ag = 0,254 g"
    assert render_all([msg, msg], "en") == "ag = 0.254 g; ag = 0.254 g"
    with pytest.raises(KeyError, match="language"):
        render(msg, "fr")


def test_round_trip_through_stored_text_keeps_nan():
    register(MessageSpec("test.value", "v {v}", "v {v}"))
    msgs = (message("test.value", v=math.nan), message("test.value", v=1.5))
    back = loads(dumps(msgs))
    assert back[1] == msgs[1]
    assert math.isnan(back[0].kwargs["v"])
    assert loads("") == ()


@pytest.mark.parametrize(
    "text", ["not json", "{}", '[["no.such.code", {}]]', '[["basis.noncompliant", {}]]', "[1]"]
)
def test_stored_text_is_checked(text):
    with pytest.raises(ValueError):
        loads(text)


def test_status_and_bound():
    assert Status("not_made") is Status.NOT_MADE
    assert Bound.parse(b"lower") is Bound.LOWER and Bound.LOWER.sign == ">"
    assert Bound.parse(None) is Bound.NONE and Bound.parse(" Upper ").sign == "<"
    with pytest.raises(ValueError, match="expected one of"):
        Bound.parse("maybe")
    assert set(LANGUAGES) == {"en", "it"}
    assert isinstance(message("basis.noncompliant", detail="x"), Message)
