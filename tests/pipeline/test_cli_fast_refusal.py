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
