"""Study files, grid expansion, the sweep archive and its figures (pipeline.study.sweep*)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import types
from pathlib import Path

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.errors import ArchiveError, ConfigError
from rockscreen.pipeline.report.sweep_plots import plot_sweep
from rockscreen.pipeline.study.sweep import (
    ARCHIVE_KIND,
    CASE_COLUMNS,
    case_excitation,
    format_cases_table,
    format_markdown_tables,
    is_sweep_archive,
    load_study,
    parse_study,
    read_cases,
    read_history,
    run_study,
    write_sweep_archive,
)
from rockscreen.solver.constants import G

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "seed_study"

TOWER = """
[tower]
name = "test tower"
width_m = 2.06
height_m = 5.80
eta = 0.9
tower_weight_kN = 339.0
building_weight_kN = 96840.67
"""

DOUBLE = """
[[group]]
name = "double"
model = "double-block"
excitation = "harmonic"
amplitudes = ["0.4g", "3m/s2"]
frequencies_hz = [3, 5]
duration_s = 1.0
friction = [[1.0, 0.7], [2.0, 1.5]]
"""

PULSE = """
[[group]]
name = "pulse"
model = "rocking"
excitation = "pulse"
shape = "one-sine"
amplitudes = ["2.25g"]
frequencies_hz = [7.98]
"""


def fake_solve(case, tower):
    """A stand-in solver: theta follows the base acceleration, scaled; no physics."""
    acc, dt = case_excitation(case)
    t = np.arange(acc.size) * dt
    theta = 1e-4 * acc
    peak = float(np.max(np.abs(theta)))
    return types.SimpleNamespace(
        status="came_to_rest",
        overturned=False,
        theta_max=peak,
        theta_max_over_alpha=peak / tower.alpha,
        n_impacts=2,
        slip_max=0.0 if case.model == "double-block" else math.nan,
        slip_residual=0.0,
        eta=0.9 if case.eta is None else case.eta,
        alpha=tower.alpha,
        p=1.546,
        t_end=float(t[-1]),
        t=t,
        theta=theta,
        theta_dot=np.gradient(theta, dt),
        u=np.zeros_like(t),
        regime=np.ones(t.size, dtype=np.int8),
    )


def test_seed_study_files_expand_to_the_papers_grids():
    study = load_study(EXAMPLES / "tables_2_3.toml")
    cases = study.cases()
    assert len(cases) == 60
    assert {c.frequency for c in cases} == {3.0, 4.0, 5.0, 6.0, 7.0}
    assert {(c.mu_s, c.mu_k) for c in cases} == {
        (1.0, 0.7),
        (1.25, 1.0),
        (2.0, 1.5),
        (2.8, 2.0),
        (3.2, 2.0),
        (3.6, 2.2),
    }
    assert {c.amplitude_text for c in cases} == {"0.4g", "0.5g"}
    assert [c.index for c in cases] == list(range(60))
    # the frequency varies fastest, so one figure panel's runs are contiguous
    assert [c.frequency for c in cases[:5]] == [3.0, 4.0, 5.0, 6.0, 7.0]
    assert len(load_study(EXAMPLES / "table_4.toml").cases()) == 5


def test_tower_weights_become_masses():
    study = parse_study(TOWER + DOUBLE)
    assert study.tower.tower_mass == pytest.approx(339e3 / G)
    assert study.tower.building_mass == pytest.approx(96840.67e3 / G)
    assert study.tower.alpha == pytest.approx(math.atan(1.03 / 2.90))
    case = study.cases()[0]
    assert case.amplitude == pytest.approx(0.4 * G)
    assert study.cases()[-1].amplitude == pytest.approx(3.0)


def test_rocking_group_has_no_friction_and_eta_list_expands():
    study = parse_study(TOWER + PULSE.replace("amplitudes", "eta = [0.8, 0.9]\namplitudes"))
    cases = study.cases()
    assert [c.eta for c in cases] == [0.8, 0.9]
    assert all(math.isnan(c.mu_s) and math.isnan(c.mu_k) for c in cases)
    assert cases[0].duration is None and cases[0].shape == "one-sine"


@pytest.mark.parametrize(
    ("text", "match"),
    [
        (
            TOWER + DOUBLE.replace('model = "double-block"', 'model = "triple"'),
            "'model' = 'triple'.*rocking, double-block",
        ),
        (
            TOWER + DOUBLE.replace('excitation = "harmonic"', 'excitation = "noise"'),
            "harmonic, pulse",
        ),
        (TOWER + DOUBLE.replace('"0.4g"', "0.4"), "bare number is refused"),
        (TOWER + DOUBLE.replace('"0.4g"', '"0.4furlong"'), "unknown acceleration unit"),
        (TOWER + DOUBLE.replace("[1.0, 0.7]", "[0.5, 0.7]"), "mu_k=0.7 must not exceed mu_s=0.5"),
        (TOWER + DOUBLE.replace("[1.0, 0.7]", "[1.0]"), r"pair \[mu_s, mu_k\]"),
        (TOWER + DOUBLE.replace("duration_s = 1.0", ""), "'duration_s' is required"),
        (
            TOWER + DOUBLE.replace("duration_s = 1.0", "duration_s = -2"),
            "'duration_s' = -2.0 must be > 0",
        ),
        (
            TOWER + DOUBLE.replace("frequencies_hz = [3, 5]", "frequencies_hz = []"),
            "non-empty list",
        ),
        (
            TOWER + DOUBLE.replace("frequencies_hz = [3, 5]", "frequencies_hz = [0]"),
            "item 0 must be a number > 0",
        ),
        (TOWER + DOUBLE + 'colour = "red"\n', "unknown key 'colour'; allowed keys"),
        (
            TOWER
            + DOUBLE.replace(
                'excitation = "harmonic"', 'excitation = "harmonic"\nshape = "one-sine"'
            ),
            "only allowed with excitation = 'pulse'",
        ),
        (
            TOWER + PULSE.replace('shape = "one-sine"', 'shape = "triangle"'),
            "'shape' = 'triangle'.*one-sine",
        ),
        (TOWER + PULSE + "friction = [[1.0, 0.7]]\n", "only allowed with model = 'double-block'"),
        (TOWER + PULSE + "eta = 1.5\n", r"'eta' = 1.5 must be a number in \(0, 1\]"),
        (TOWER.replace("tower_weight_kN = 339.0", "") + DOUBLE, "needs the masses"),
        (TOWER + "tower_mass_kg = 1.0\n" + DOUBLE, "either tower_mass_kg or tower_weight_kN"),
        (
            TOWER.replace("width_m = 2.06", 'width_m = "wide"'),
            "'width_m' = 'wide' must be a finite number",
        ),
        (TOWER, r"at least one \[\[group\]\]"),
        (DOUBLE, r"a \[tower\] table is required"),
        ("title = [", "not valid TOML"),
    ],
)
def test_bad_study_files_name_key_value_and_allowed(text, match):
    with pytest.raises(ConfigError, match=match):
        parse_study(text, source="bad.toml")


def test_missing_study_file(tmp_path):
    with pytest.raises(ConfigError, match="cannot read study file"):
        load_study(tmp_path / "absent.toml")


def same_result(a, b) -> bool:
    """Whether two CaseResults are equal, field by field and history by history."""
    if repr(a.case) != repr(b.case):  # a case's NaN friction breaks ==
        return False
    fields = [k for k in vars(a) if k not in ("case", "histories")]
    if any(not _same_value(getattr(a, k), getattr(b, k)) for k in fields):
        return False
    return a.histories.keys() == b.histories.keys() and all(
        np.array_equal(a.histories[k], b.histories[k], equal_nan=True) for k in a.histories
    )


def _same_value(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or a == b
    return a == b


@pytest.mark.slow
def test_run_with_two_workers_equals_one_worker_in_case_order():
    """jobs=2 computes on the executor's worker processes: same results, same order."""
    study = parse_study(TOWER + DOUBLE + PULSE, source="two.toml")
    serial = list(run_study(study, jobs=1))
    notes = []
    parallel = list(run_study(study, jobs=2, notify=notes.append))
    assert len(serial) == len(study.cases()) > 2
    assert [r.case.index for r in parallel] == [c.index for c in study.cases()]
    assert all(same_result(a, b) for a, b in zip(parallel, serial, strict=True))
    assert notes == []  # two workers, more cases than that: no cap


def test_run_caps_the_workers_at_the_cases_with_a_note():
    study = parse_study(TOWER + PULSE)
    notes = []
    results = list(run_study(study, jobs=3, solve=fake_solve, notify=notes.append))
    assert [r.case.index for r in results] == [0]
    assert notes == ["--jobs 3 capped at 1 (1 chunk to compute)"]


CUSTOM_SOLVE = """
import json, math, sys, types
from rockscreen.pipeline.study.sweep import parse_study, run_study


def halved(case, tower):  # a user's solve, defined in the main script (pickled by name)
    return types.SimpleNamespace(
        status="came_to_rest", overturned=False, theta_max=case.amplitude / 2,
        theta_max_over_alpha=math.nan, n_impacts=case.index,
    )


if __name__ == "__main__":
    study = parse_study(sys.stdin.read())
    out = {
        jobs: [(r.case.index, r.theta_max, r.n_impacts) for r in run_study(
            study, jobs=jobs, solve=halved)]
        for jobs in (1, 2)
    }
    print(json.dumps(out))
"""


@pytest.mark.slow
def test_run_ships_a_custom_solve_to_the_workers(tmp_path):
    script = tmp_path / "custom.py"
    script.write_text(CUSTOM_SOLVE, encoding="utf-8")
    study = TOWER + DOUBLE + PULSE
    done = subprocess.run(
        [sys.executable, str(script)], input=study, capture_output=True, text=True, timeout=300
    )
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout)
    cases = parse_study(study).cases()
    assert out["2"] == out["1"]
    assert out["1"] == [[c.index, c.amplitude / 2, c.index] for c in cases]


def test_run_jobs_must_be_positive():
    study = parse_study(TOWER + PULSE)
    with pytest.raises(ConfigError, match="jobs=0"):
        list(run_study(study, jobs=0, solve=fake_solve))


@pytest.fixture
def fake_archive(tmp_path):
    study = parse_study(TOWER + DOUBLE + PULSE, source="fake.toml")
    path = tmp_path / "fake.h5"
    seen = []
    write_sweep_archive(path, study, run_study(study, solve=fake_solve), on_result=seen.append)
    assert [r.case.index for r in seen] == list(range(9))
    return path


def test_archive_layout(fake_archive):
    assert is_sweep_archive(fake_archive)
    assert not fake_archive.with_name("fake.h5.part").exists()
    with h5py.File(fake_archive, "r") as h5:
        assert h5.attrs["kind"] == ARCHIVE_KIND
        assert "[[group]]" in h5.attrs["study_toml"]
        assert h5.attrs["created_utc"].endswith("+00:00")
        assert h5.attrs["rockscreen_version"]
        assert h5["tower"].attrs["alpha_rad"] == pytest.approx(math.atan(1.03 / 2.90))
        cases = h5["cases"]
        assert cases.shape == (9,)
        assert list(cases.attrs["columns"]) == [c[0] for c in CASE_COLUMNS]
        units = dict(zip(cases.attrs["columns"], cases.attrs["units"], strict=True))
        assert units["theta_max_rad"] == "rad" and units["frequency_hz"] == "Hz"
        hist = h5["histories/0"]
        assert {k: hist[k].attrs["units"] for k in ("t", "theta", "u", "regime")} == {
            "t": "s",
            "theta": "rad",
            "u": "m",
            "regime": "",
        }
    rows = read_cases(fake_archive)
    assert rows[0]["model"] == "double-block" and rows[0]["amplitude"] == "0.4g"
    assert rows[0]["amplitude_g"] == pytest.approx(0.4)
    assert rows[-1]["model"] == "rocking" and math.isnan(rows[-1]["mu_s"])
    assert rows[-1]["duration_s"] == pytest.approx(1 / 7.98)
    hist = read_history(fake_archive, 0)
    np.testing.assert_allclose(hist["theta"], 1e-4 * 0.4 * G * np.cos(2 * np.pi * 3 * hist["t"]))
    table = format_cases_table(rows)
    assert "theta_max [rad]" in table and "f [Hz]" in table
    assert len(table.splitlines()) == 2 + 9


def test_failed_run_leaves_no_file(tmp_path):
    study = parse_study(TOWER + DOUBLE)

    def broken(case, tower):
        if case.index == 3:
            raise RuntimeError("boom")
        return fake_solve(case, tower)

    path = tmp_path / "out.h5"
    with pytest.raises(RuntimeError, match="boom"):
        write_sweep_archive(path, study, run_study(study, solve=broken))
    assert list(tmp_path.iterdir()) == []


def test_not_a_sweep_archive(tmp_path):
    text = tmp_path / "a.h5"
    text.write_text("not hdf5")
    other = tmp_path / "b.h5"
    with h5py.File(other, "w") as h5:
        h5.attrs["kind"] = "something-else"
    assert not is_sweep_archive(text)
    assert not is_sweep_archive(other)
    assert not is_sweep_archive(tmp_path / "absent.h5")
    with pytest.raises(ArchiveError, match="not a rockscreen sweep archive"):
        read_cases(other)


def test_figures_render(fake_archive, tmp_path):
    written = plot_sweep(fake_archive, tmp_path / "figs")
    names = sorted(p.name for p in written)
    # group 1: one figure per amplitude + a summary (two frequencies); group 2: one figure
    assert names == sorted(
        ["fake_g1_0p4g.png", "fake_g1_3m_s2.png", "fake_g1_theta_max.png", "fake_g2_2p25g.png"]
    )
    for path in written:
        assert path.stat().st_size > 5000
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


# ----------------------------------------------------------------- with the real solver

# The same excitation on the ground (single block) and on the church (double block).
HARMONIC = """excitation = "harmonic"
amplitudes = ["0.3g", "0.5g"]
frequencies_hz = [4]
duration_s = 1.0
"""
REAL = f"""{TOWER}
[[group]]
name = "on the ground"
model = "rocking"
{HARMONIC}
[[group]]
name = "on the church"
model = "double-block"
{HARMONIC}friction = [[2.0, 1.5]]
"""


def test_real_solver_end_to_end(tmp_path):
    study = parse_study(REAL, source="real.toml")
    path = tmp_path / "real.h5"
    write_sweep_archive(path, study, run_study(study))
    rows = read_cases(path)
    single, double = rows[:2], rows[2:]
    # 0.3 g < g tan(alpha) = 0.355 g: no uplift, on the ground or on the church
    for row in (single[0], double[0]):
        assert row["status"] == "no_motion" and row["theta_max_rad"] == 0.0
    # 0.5 g < mu_s g: the church never slides, and with m/M = 0.0035 its top moves with
    # the ground, so the double block is the single block on the ground motion
    assert single[1]["theta_max_rad"] > 0.0
    assert double[1]["slip_max_m"] == 0.0
    assert double[1]["theta_max_rad"] == pytest.approx(single[1]["theta_max_rad"], rel=1e-3)
    hist = read_history(path, 3)
    assert hist["t"].shape == hist["theta"].shape == hist["u"].shape == hist["regime"].shape
    assert np.max(np.abs(hist["theta"])) == pytest.approx(double[1]["theta_max_rad"], rel=1e-6)


def test_duration_list_is_a_grid_dimension():
    study = parse_study(TOWER + DOUBLE.replace("duration_s = 1.0", "duration_s = [1.0, 2.5]"))
    cases = study.cases()
    assert len(cases) == 2 * 2 * 2 * 2
    assert [(c.duration, c.frequency) for c in cases[:4]] == [
        (1.0, 3),
        (1.0, 5),
        (2.5, 3),
        (2.5, 5),
    ]
    assert study.groups[0].size() == len(cases)


def test_markdown_tables_pivot_friction_by_frequency(fake_archive):
    text = format_markdown_tables(read_cases(fake_archive), "Fake")
    assert text.startswith("### Fake")
    assert "| mu_s / mu_k | eta | 3 Hz | 5 Hz |" in text
    assert "| 2 / 1.5 | 0.9 |" in text and "| single block | 0.9 |" in text
    # three tables: double at 0.4g and 3m/s2, the pulse
    assert text.count("|---|---|") == 3


def test_formulation_key_is_a_grid_dimension_and_validated():
    text = TOWER + DOUBLE.replace(
        "duration_s = 1.0", 'duration_s = 1.0\nformulation = ["consistent", "di-gennaro-2023"]'
    )
    study = parse_study(text)
    cases = study.cases()
    assert len(cases) == 16
    assert [c.formulation for c in cases[:8]] == ["consistent"] * 4 + ["di-gennaro-2023"] * 4
    with pytest.raises(ConfigError, match="formulation.*is not one of"):
        parse_study(
            TOWER + DOUBLE.replace("duration_s = 1.0", 'duration_s = 1.0\nformulation = "x"')
        )
    with pytest.raises(ConfigError, match="only allowed with model = 'double-block'"):
        parse_study(TOWER + PULSE + 'formulation = "di-gennaro-2023"\n')


def test_archive_v2_has_format_utf8_strings_and_the_formulation(tmp_path):
    study = parse_study(TOWER + DOUBLE.replace('name = "double"', 'name = "' + "é" * 80 + '"'))
    path = tmp_path / "long.h5"
    write_sweep_archive(path, study, run_study(study, solve=fake_solve))
    with h5py.File(path, "r") as h5:
        assert (h5.attrs["format"], h5.attrs["kind"], h5.attrs["format_version"]) == (
            "rockscreen-archive",
            "sweep",
            "2",
        )
        units = dict(zip(h5["cases"].attrs["columns"], h5["cases"].attrs["units"], strict=True))
        assert units["mu_s"] == "1" and units["amplitude_m_s2"] == "m/s2"
        assert "-" not in set(units.values())
    rows = read_cases(path)
    assert rows[0]["group"] == "é" * 80  # not truncated
    assert rows[0]["formulation"] == "consistent"


def _v1_archive(path, version=1):
    table = np.array(
        [(0, b"old", b"double-block", 0.0123)],
        dtype=[("index", "i4"), ("group", "S64"), ("model", "S16"), ("theta_max_rad", "f8")],
    )
    with h5py.File(path, "w") as h5:
        h5.attrs["kind"] = "rockscreen-sweep"
        h5.attrs["format_version"] = version
        h5.create_group("tower").attrs["name"] = "old tower"
        h5.create_dataset("cases", data=table)
        h5.create_dataset("histories/0/theta", data=np.zeros(3))


def test_version_1_sweep_archives_are_read(tmp_path):
    path = tmp_path / "v1.h5"
    _v1_archive(path)
    assert is_sweep_archive(path)
    rows = read_cases(path)
    assert rows == [
        {
            "index": 0,
            "group": "old",
            "model": "double-block",
            "theta_max_rad": 0.0123,
            "formulation": "consistent",
        }
    ]
    assert read_history(path, 0)["theta"].shape == (3,)


def test_unknown_sweep_archive_version_is_refused_in_one_line(tmp_path):
    path = tmp_path / "v9.h5"
    _v1_archive(path, version=9)
    with pytest.raises(ArchiveError, match=r"format_version '9' is not supported") as err:
        read_cases(path)
    assert "\n" not in str(err.value)


def test_a_malformed_sweep_table_is_one_line(fake_archive):
    from rockscreen.pipeline.archive.kinds import open_archive
    from rockscreen.pipeline.archive.sweep_archive import read_cases

    with h5py.File(fake_archive, "r+") as h5:
        del h5["cases"]
        h5.create_dataset("cases", data=np.arange(3))
    for read in (open_archive, read_cases):
        with pytest.raises(ArchiveError, match="/cases is not a table"):
            read(fake_archive)
