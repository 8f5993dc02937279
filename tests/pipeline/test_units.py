import pytest

from rockscreen.pipeline.errors import UnitsError
from rockscreen.pipeline.units import parse_acceleration, unit_factor
from rockscreen.solver.constants import G


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("0.4g", 0.4 * G),
        ("3.92m/s2", 3.92),
        ("392 cm/s2", 3.92),
        ("-1e-1 g", -0.1 * G),
        ("10gal", 0.1),
    ],
)
def test_parse_acceleration(text, expected):
    assert parse_acceleration(text) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text", ["0.4", "3", "abc", "0.4 furlongs"])
def test_bare_or_unknown_amplitude_is_refused(text):
    with pytest.raises(UnitsError, match="amplitude"):
        parse_acceleration(text)


def test_unit_factor_unknown():
    with pytest.raises(UnitsError, match="allowed"):
        unit_factor("ft/s2")
