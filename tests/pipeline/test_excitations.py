import numpy as np
import pytest

from rockscreen.pipeline.motion.excitations import harmonic, pulse
from rockscreen.solver.errors import ParameterError


def test_harmonic_is_a_cosine():
    acc, dt = harmonic(2.0, 5.0, 1.0, dt=1e-3)
    t = np.arange(acc.size) * dt
    assert acc.size == 1001
    np.testing.assert_allclose(acc, 2.0 * np.cos(2 * np.pi * 5.0 * t))


@pytest.mark.parametrize(
    ("shape", "length"),
    [("one-sine", 1.0), ("one-cosine", 1.0), ("half-sine", 0.5), ("rectangular", 0.5)],
)
def test_pulse_lengths_and_padding(shape, length):
    acc, dt = pulse(shape, 3.0, 1.0, dt=1e-3, duration=2.0)
    t = np.arange(acc.size) * dt
    assert t[-1] == pytest.approx(2.0)
    assert np.all(acc[t > length + 1e-9] == 0.0)
    assert np.max(np.abs(acc)) == pytest.approx(3.0, rel=1e-5)


def test_bad_pulse_arguments():
    with pytest.raises(ParameterError, match="shape"):
        pulse("triangle", 1.0, 1.0)
    with pytest.raises(ParameterError, match="frequency"):
        pulse("one-sine", 1.0, 0.0)
