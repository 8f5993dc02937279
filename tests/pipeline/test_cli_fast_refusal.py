"""A mistyped path is refused before ObsPy, numba or h5py are imported (issue 24).

Each case runs the CLI in a fresh interpreter and looks at ``sys.modules`` when it exits:
no timing, the imports themselves are the cost.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

HEAVY = ("obspy", "numba", "h5py", "scipy", "matplotlib")

_PROBE = textwrap.dedent(
    """
    import sys
    from rockscreen.pipeline.cli import main
    try:
        main(sys.argv[1:])
    except SystemExit as exc:
        heavy = sorted({m.split(".")[0] for m in sys.modules} & set(HEAVY))
        print("EXIT", exc.code, "MODULES", ",".join(heavy) or "-")
    """
)


def _probe(tmp_path, *args):
    proc = subprocess.run(
        [sys.executable, "-c", _PROBE.replace("HEAVY", repr(HEAVY)), *args],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        timeout=120,
    )
    return proc.stdout.strip().splitlines()[-1], proc.stderr.strip().splitlines()


@pytest.mark.parametrize(
    ("command", "needle"),
    [
        (["inspect", "missing.h5"], "does not exist"),
        (["report", "towers.csv"], "not an HDF5 file"),
        (["export", "missing.h5", "--csv", "o.csv"], "does not exist"),
        (["plot", "towers.csv", "--map"], "not an HDF5 file"),
        (["inspect", "sub"], "is a folder"),
        (["run", "r.mseed", "--towers", "missing.csv"], "inventory missing.csv: no such file"),
        (
            ["run", "missing.mseed", "--towers", "towers.csv"],
            "none of the 1 record files can be read: missing.mseed: no such file",
        ),
        (
            ["run", "r.mseed", "--towers", "towers.csv", "--stations", "nope.xml"],
            "station metadata 'nope.xml': no such file",
        ),
        (["assess", "--towers", "missing.csv"], "inventory missing.csv: no such file"),
        (
            ["scenario", "--shakemap", "towers.csv", "--fragility", "towers.csv"],
            "not an HDF5 file",
        ),
        (["sweep", "missing.toml"], "study file missing.toml: no such file"),
        (
            ["hazard", "--lon", "13", "--lat", "42", "--return-period", "475", "--suite", "no"],
            "suite no: no such file",
        ),
    ],
)
def test_a_bad_path_is_refused_before_the_heavy_imports(tmp_path, command, needle):
    (tmp_path / "towers.csv").write_text("id,width_m,height_m\nT1,3,20\n")
    (tmp_path / "sub").mkdir()
    status, stderr = _probe(tmp_path, *command)
    assert status == "EXIT 1 MODULES -"
    assert len(stderr) == 1 and stderr[0].startswith("rockscreen: error: ") and needle in stderr[0]


def test_an_hdf5_file_past_a_user_block_passes_the_signature_check(tmp_path):
    from rockscreen.pipeline.cli.inputs import HDF5_SIGNATURE, check_archive_path

    path = tmp_path / "ub.h5"
    path.write_bytes(b"\0" * 512 + HDF5_SIGNATURE + b"\0" * 64)
    check_archive_path(path)  # no error: HDF5 looks at 0, 512, 1024, ...


def test_a_missing_suite_is_a_usage_error_before_the_heavy_imports(tmp_path):
    (tmp_path / "towers.csv").write_text("id,width_m,height_m\nT1,3,20\n")
    status, stderr = _probe(tmp_path, "assess", "--towers", "towers.csv", "--suite", "missing")
    assert status == "EXIT 2 MODULES -"
    assert stderr[-1] == "Error: Invalid value for '--suite': Path 'missing' does not exist."


def test_a_missing_record_beside_readable_ones_is_named_once(tmp_path):
    from rockscreen.pipeline.motion.synthetic import write_example_records

    paths, xml = write_example_records(tmp_path / "rec")
    (tmp_path / "towers.csv").write_text("id,width_m,height_m,lat,lon\nT1,3,20,41.04,14.42\n")
    command = [sys.executable, "-m", "rockscreen.pipeline", "run", str(paths[0]), "gone.mseed"]
    command += ["--towers", "towers.csv", "--stations", str(xml), "--jobs", "1"]
    done = subprocess.run(command, capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stderr.count("gone.mseed") == 1
    assert "rockscreen: skipped gone.mseed: no such file" in done.stderr.splitlines()
