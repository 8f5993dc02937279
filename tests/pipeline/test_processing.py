"""Processing steps, provenance, the Nyquist rule and quality checks."""

from __future__ import annotations

import numpy as np
import pytest
from obspy import Stream, Trace
from obspy.core.util import AttribDict

from rockscreen.pipeline.errors import ProcessingError
from rockscreen.pipeline.processing.steps import (
    ProcessingConfig,
    bandpass,
    baseline_polynomial,
    process_stream,
    process_trace,
    resample,
    taper,
)
from rockscreen.pipeline.records.quality import QualityError, QualityLimits, check_array

DT = 0.01


def make_trace(data, dt=DT, station="ABC"):
    trace = Trace(np.asarray(data, dtype=np.float64), header={"delta": dt, "station": station})
    trace.stats.channel = "HNE"
    trace.stats.rockscreen = AttribDict(units="m/s2", provenance=[{"step": "read"}])
    return trace


@pytest.fixture
def quake():
    rng = np.random.default_rng(1)
    t = np.arange(3000) * DT
    return np.exp(-(((t - 12.0) / 4.0) ** 2)) * rng.standard_normal(t.size) + 0.2 + 0.01 * t


def test_process_trace_records_every_step(quake):
    trace = make_trace(quake)
    out = process_trace(trace)
    steps = [entry["step"] for entry in out.stats.rockscreen.provenance]
    assert steps == ["read", "quality_checks", "demean", "detrend", "taper", "filter"]
    filt = out.stats.rockscreen.provenance[-1]
    assert filt == {
        "step": "filter",
        "type": "butterworth bandpass",
        "freqmin_hz": 0.1,
        "freqmax_hz": 20.0,
        "order": 4,
        "zerophase": True,
    }
    # The input is untouched (a processed copy is returned).
    assert [e["step"] for e in trace.stats.rockscreen.provenance] == ["read"]
    np.testing.assert_array_equal(trace.data, quake)
    assert abs(out.data.mean()) < 1e-3 * np.abs(out.data).max()


def test_optional_steps_recorded(quake):
    config = ProcessingConfig(resample_hz=50.0, baseline_correction=True, freqmax_hz=10.0)
    out = process_trace(make_trace(quake), config)
    steps = [entry["step"] for entry in out.stats.rockscreen.provenance]
    assert steps[-2:] == ["resample", "baseline_correction"]
    assert out.stats.delta == pytest.approx(0.02)
    assert out.stats.npts == quake.size // 2


@pytest.mark.parametrize("freqmax", [50.0, 60.0])
def test_corner_at_or_above_nyquist_is_an_error(quake, freqmax):
    with pytest.raises(ProcessingError, match="Nyquist"):
        bandpass(quake, DT, 0.1, freqmax)
    with pytest.raises(ProcessingError, match=r"ABC.*Nyquist"):
        process_trace(make_trace(quake), ProcessingConfig(freqmax_hz=freqmax))


def test_default_band_works_for_50_hz_records(quake):
    # El Centro 1940 is sampled at 50 Hz: the default 20 Hz corner sits below its Nyquist.
    out = process_trace(make_trace(quake[::2], dt=0.02))
    assert np.isfinite(out.data).all()


def test_resampling_below_the_band_is_an_error(quake):
    with pytest.raises(ProcessingError, match="freqmax_hz"):
        process_trace(make_trace(quake), ProcessingConfig(resample_hz=40.0))


def test_bandpass_keeps_the_band_and_removes_the_rest():
    t = np.arange(20000) * DT
    inside = np.sin(2 * np.pi * 1.0 * t)
    outside = np.sin(2 * np.pi * 40.0 * t) + 1.5  # high frequency and an offset
    out = bandpass(inside + outside, DT, 0.1, 20.0, order=4)
    core = slice(5000, 15000)
    # Zero phase: the in-band sine comes out in place, not delayed.
    np.testing.assert_allclose(out[core], inside[core], atol=2e-3)


def test_explicit_highpass_and_lowpass():
    t = np.arange(4000) * DT
    x = np.sin(2 * np.pi * 5.0 * t)
    assert np.abs(bandpass(x, DT, None, 1.0)[1000:3000]).max() < 1e-3
    assert np.abs(bandpass(x, DT, 1.0, None)[1000:3000]).max() == pytest.approx(1.0, rel=1e-2)
    np.testing.assert_array_equal(bandpass(x, DT, None, None), x)


def test_taper_ends():
    out = taper(np.ones(1000), 0.05)
    assert out[0] == 0.0 and out[-1] == 0.0
    np.testing.assert_array_equal(out[50:950], 1.0)
    with pytest.raises(ProcessingError, match="taper fraction"):
        taper(np.ones(10), 0.6)


def test_resample_ratio():
    x = np.sin(np.arange(1000) * 0.01)
    y, dt = resample(x, 0.005, 100.0)
    assert dt == pytest.approx(0.01) and y.size == 500
    with pytest.raises(ProcessingError, match="simple fraction"):
        resample(x, 0.005, 200.0 / np.pi)


def test_baseline_correction_removes_polynomial_drift():
    t = np.arange(4000) * DT
    drift = 1e-3 * (t / t[-1]) ** 2  # a constant offset in acceleration after the taper
    signal = np.sin(2 * np.pi * 2.0 * t) * np.exp(-(((t - 20) / 5) ** 2))
    corrected = baseline_polynomial(signal + drift, DT, order=6)
    velocity_end = np.trapezoid(corrected, dx=DT)
    assert abs(velocity_end) < abs(np.trapezoid(signal + drift, dx=DT))


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"detrend": "quadratic"}, "detrend"),
        ({"taper_fraction": 0.7}, "taper_fraction"),
        ({"freqmin_hz": 5.0, "freqmax_hz": 1.0}, "freqmin_hz"),
        ({"freqmin_hz": -1.0}, "freqmin_hz"),
        ({"filter_order": 0}, "filter_order"),
        ({"baseline_order": 1}, "baseline_order"),
    ],
)
def test_config_validation(kwargs, name):
    with pytest.raises(ProcessingError, match=name):
        ProcessingConfig(**kwargs)


def test_config_to_dict_is_complete():
    config = ProcessingConfig().to_dict()
    assert config["freqmin_hz"] == 0.1 and config["quality"]["min_sampling_rate_hz"] == 20.0


# --- quality -----------------------------------------------------------------------------


def test_good_record_has_no_findings(quake):
    assert check_array(quake, DT) == []


def test_quality_reasons():
    bad = np.sin(np.arange(40) / 3.0)
    bad[5] = np.nan
    findings = {f.check: f.reason for f in check_array(bad, 0.1)}
    assert set(findings) == {"sampling_rate", "non_finite", "too_short"}
    assert "10 Hz is below the minimum 20 Hz" in findings["sampling_rate"]
    assert "1 of 40 samples" in findings["non_finite"]
    assert "4 s" in findings["too_short"]


def test_flat_record():
    (finding,) = check_array(np.full(1000, 0.3), DT)
    assert finding.check == "flat"


def test_clipped_record(quake):
    clipped = np.clip(quake, -1.0, 1.0)
    (finding,) = check_array(clipped, DT)
    assert finding.check == "clipped"
    assert "consecutive samples" in finding.reason


def test_processing_refuses_failing_trace_with_reasons(quake):
    trace = make_trace(np.clip(quake, -1.0, 1.0))
    with pytest.raises(QualityError, match="clipped") as info:
        process_trace(trace)
    assert [f.check for f in info.value.findings] == ["clipped"]
    assert isinstance(info.value, ProcessingError)
    out = process_trace(trace, ProcessingConfig(check_quality=False))
    assert "quality_checks" not in [e["step"] for e in out.stats.rockscreen.provenance]


def test_quality_limits_validation():
    with pytest.raises(ProcessingError, match="clip_run"):
        QualityLimits(clip_run=1)
    with pytest.raises(ProcessingError, match="min_duration_s"):
        QualityLimits(min_duration_s=-1.0)


def test_process_stream_skips_and_reports(quake):
    stream = Stream([make_trace(quake), make_trace(np.full(1000, 1.0), station="FLAT")])
    processed, failures = process_stream(stream)
    assert len(processed) == 1
    assert failures[0][0] == ".FLAT..HNE" and "flat" in failures[0][1]


@pytest.mark.data
def test_real_records_pass_quality_and_process(shared_data):
    from rockscreen.pipeline.records.io import read_stream

    folder = shared_data / "laquila2009"
    (trace,) = read_stream(folder / "IT.AQV..HNN.mseed", stations=folder / "stations.xml")
    out = process_trace(trace)
    # ITACA already band-passed this record: our 0.1-20 Hz pass barely changes its PGA.
    assert np.abs(out.data).max() == pytest.approx(np.abs(trace.data).max(), rel=0.05)
    (elcentro,) = read_stream(shared_data / "formats" / "at2" / "elCentro.AT2")
    assert check_array(elcentro.data, elcentro.stats.delta) == []
    process_trace(elcentro)
