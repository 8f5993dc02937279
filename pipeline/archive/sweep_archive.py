"""The sweep archive: HDF5 file of a ``rockscreen sweep`` run (writer and readers).

Layout (format version ``"2"``)::

    /                 attrs: format = "rockscreen-archive", kind = "sweep",
                             format_version = "2", rockscreen_version, created_utc,
                             study_title, study_source, study_toml
    /tower            attrs: name, width_m, height_m, alpha_rad, eta, tower_mass_kg,
                             building_mass_kg, each with "<key>.units"
    /cases            one row per case (:data:`CASE_COLUMNS`), attrs columns, units;
                      text columns are variable-length UTF-8 strings
    /histories/<i>    t [s], theta [rad], theta_dot [rad/s], u [m], regime (code)

The format name, versions and units spellings are those of :mod:`pipeline.archive.schema`.
The readers also read sweep archives of format version 1 (root ``kind =
"rockscreen-sweep"``, ``format_version = 1``, fixed-length byte strings, units ``"-"``);
their rows come back with the version-2 columns (``formulation`` "consistent").
"""

from __future__ import annotations

import datetime as _dt
import os
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline import __version__
from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.archive.safety import check_tree, closed_on_failure, reading
from rockscreen.pipeline.archive.schema import (
    ACCELERATION,
    ANGLE,
    ANGULAR_VELOCITY,
    DIMENSIONLESS,
    FORMAT,
    FORMAT_VERSION,
    LENGTH,
    MASS,
    TEXT,
    TIME,
)
from rockscreen.pipeline.engine.results import CaseResult
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.units import float_or_nan
from rockscreen.solver.constants import G

#: Value of the root attribute ``kind`` that marks a sweep archive.
ARCHIVE_KIND = "sweep"
#: Layout version written (the schema's :data:`~rockscreen.pipeline.archive.schema.FORMAT_VERSION`).
ARCHIVE_FORMAT_VERSION = FORMAT_VERSION
#: Root ``kind`` of the sweep archives of format version 1 (read, never written).
LEGACY_KIND = "rockscreen-sweep"
#: Format versions this reader takes.
SUPPORTED_SWEEP_VERSIONS = ("1", "2")

#: History arrays kept per case, with their units (``regime`` is a code: no units).
HISTORY_UNITS = {
    "t": TIME,
    "theta": ANGLE,
    "theta_dot": ANGULAR_VELOCITY,
    "u": LENGTH,
    "regime": TEXT,
}

#: Attributes of ``/tower`` (each also stored as ``"<key>.units"``) -> units.
TOWER_UNITS = {
    "width_m": LENGTH,
    "height_m": LENGTH,
    "alpha_rad": ANGLE,
    "eta": DIMENSIONLESS,
    "tower_mass_kg": MASS,
    "building_mass_kg": MASS,
}

_STR = "str"
#: Columns of ``/cases``: (name, numpy dtype or "str", units).
CASE_COLUMNS = (
    ("index", "i4", DIMENSIONLESS),
    ("group_index", "i4", DIMENSIONLESS),
    ("group", _STR, TEXT),
    ("model", _STR, TEXT),
    ("formulation", _STR, TEXT),
    ("excitation", _STR, TEXT),
    ("shape", _STR, TEXT),
    ("amplitude", _STR, TEXT),
    ("amplitude_m_s2", "f8", ACCELERATION),
    ("amplitude_g", "f8", "g"),
    ("frequency_hz", "f8", "Hz"),
    ("duration_s", "f8", TIME),
    ("dt_s", "f8", TIME),
    ("mu_s", "f8", DIMENSIONLESS),
    ("mu_k", "f8", DIMENSIONLESS),
    ("eta", "f8", DIMENSIONLESS),
    ("status", _STR, TEXT),
    ("overturned", "?", TEXT),
    ("theta_max_rad", "f8", ANGLE),
    ("theta_max_over_alpha", "f8", DIMENSIONLESS),
    ("n_impacts", "i4", DIMENSIONLESS),
    ("slip_max_m", "f8", LENGTH),
    ("slip_residual_m", "f8", LENGTH),
    ("t_end_s", "f8", TIME),
)


def _cases_dtype() -> np.dtype:
    text = h5py.string_dtype(encoding="utf-8")
    return np.dtype([(n, text if d == _STR else d) for n, d, _ in CASE_COLUMNS])


def _case_row(result: CaseResult) -> tuple:
    c = result.case
    return (
        c.index,
        c.group_index,
        c.group,
        c.model,
        c.formulation,
        c.excitation,
        c.shape,
        c.amplitude_text,
        c.amplitude,
        c.amplitude / G,
        c.frequency,
        result.duration,
        result.dt,
        c.mu_s,
        c.mu_k,
        result.eta,
        result.status,
        result.overturned,
        result.theta_max,
        result.theta_max_over_alpha,
        result.n_impacts,
        result.slip_max,
        result.slip_residual,
        result.t_end,
    )


def _write_root(h5: Any, study: Any) -> None:
    h5.attrs["format"] = FORMAT
    h5.attrs["kind"] = ARCHIVE_KIND
    h5.attrs["format_version"] = ARCHIVE_FORMAT_VERSION
    h5.attrs["rockscreen_version"] = __version__
    h5.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    h5.attrs["study_title"] = study.title
    h5.attrs["study_source"] = study.source
    h5.attrs["study_toml"] = study.source_text
    tower = study.tower
    grp = h5.create_group("tower")
    grp.attrs["name"] = tower.name
    values = {
        "width_m": tower.width,
        "height_m": tower.height,
        "alpha_rad": tower.alpha,
        "eta": float_or_nan(tower.eta),
        "tower_mass_kg": float_or_nan(tower.tower_mass),
        "building_mass_kg": float_or_nan(tower.building_mass),
    }
    for key, unit in TOWER_UNITS.items():
        grp.attrs[key] = values[key]
        grp.attrs[f"{key}.units"] = unit


def write_sweep_archive(
    path: str | os.PathLike,
    study: Any,
    results: Iterable[CaseResult],
    *,
    on_result: Callable[[CaseResult], None] | None = None,
) -> list[CaseResult]:
    """Write a sweep archive, streaming histories as results arrive.

    The file is written to ``<path>.part`` and moved to ``path`` only when complete,
    so an interrupted sweep never leaves a half-written archive at the final path.

    Parameters
    ----------
    path : str or path-like
        Final archive path (``.h5``).
    study : rockscreen.pipeline.study.study_file.Study
        The study that was run (its text is stored; the archive reads its attributes and
        never imports the study stage).
    results : iterable of CaseResult
        Typically :func:`rockscreen.pipeline.study.sweep.run_study`.
    on_result : callable, optional
        Called with each result after it is stored (progress reports).

    Returns
    -------
    list of CaseResult
        The results, histories dropped to save memory.
    """
    kept: list[CaseResult] = []
    with atomic_path(path, suffix=".part") as part:
        with h5py.File(part, "w") as h5:
            _write_root(h5, study)
            hist = h5.create_group("histories")
            rows = []
            for result in results:
                sub = hist.create_group(str(result.case.index))
                for name, data in result.histories.items():
                    ds = sub.create_dataset(
                        name, data=data, compression="gzip", shuffle=True, chunks=True
                    )
                    ds.attrs["units"] = HISTORY_UNITS[name]
                rows.append(_case_row(result))
                result.histories = {}
                kept.append(result)
                if on_result is not None:
                    on_result(result)
            table = np.array(rows, dtype=_cases_dtype())
            ds = h5.create_dataset("cases", data=table)
            ds.attrs["columns"] = [name for name, _, _ in CASE_COLUMNS]
            ds.attrs["units"] = [unit for _, _, unit in CASE_COLUMNS]
    return kept


def _text(value: Any) -> Any:
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.generic):
        return value.item()
    return value


def _version(h5: Any, path: Any) -> str | None:
    """Return the sweep format version of an open file, None if it is no sweep archive.

    Raises
    ------
    ArchiveError
        If it is a sweep archive of a version this reader does not take.
    """
    kind = _text(h5.attrs.get("kind"))
    if kind == LEGACY_KIND and "format" not in h5.attrs:
        version = str(_text(h5.attrs.get("format_version")))
    elif kind == ARCHIVE_KIND and _text(h5.attrs.get("format")) == FORMAT:
        version = str(_text(h5.attrs.get("format_version")))
    else:
        return None
    if version not in SUPPORTED_SWEEP_VERSIONS:
        raise ArchiveError(
            f"{str(path)!r}: sweep archive format_version {version!r} is not supported "
            f"(this rockscreen reads {', '.join(SUPPORTED_SWEEP_VERSIONS)})"
        )
    return version


def is_sweep_archive(path: str | os.PathLike) -> bool:
    """Return True if ``path`` is an HDF5 sweep archive written by rockscreen (any version)."""
    path = Path(path)
    if not path.is_file() or not h5py.is_hdf5(path):
        return False
    try:
        with h5py.File(path, "r") as h5:
            kind = _text(h5.attrs.get("kind"))
            return kind in (ARCHIVE_KIND, LEGACY_KIND) and "cases" in h5
    except OSError:
        return False


#: Columns every sweep archive's ``/cases`` has, of every version.
REQUIRED_CASE_COLUMNS = ("index",)


def check_sweep_tables(h5: Any, path: Any) -> None:
    """Check the ``/cases`` table and the histories of an open sweep archive.

    ``/cases`` is one 1-D compound dataset with at least :data:`REQUIRED_CASE_COLUMNS`,
    numbers where :data:`CASE_COLUMNS` declares numbers and text where it declares
    text; each ``/histories/<index>`` is a group of 1-D arrays of one length.

    Parameters
    ----------
    h5 : h5py.File
        The open archive (its tree checked).
    path : str or path-like
        Its path, for messages.

    Raises
    ------
    ArchiveError
        One line naming the file, the table or array and what is wrong.
    """
    name = printable(os.fspath(path))
    cases = h5.get("cases")
    if not isinstance(cases, h5py.Dataset) or cases.dtype.names is None:
        raise ArchiveError(f"{name}: /cases is not a table (a compound dataset)")
    if cases.ndim != 1:
        raise ArchiveError(f"{name}: /cases has shape {cases.shape}; the table is 1-D")
    missing = [c for c in REQUIRED_CASE_COLUMNS if c not in cases.dtype.names]
    if missing:
        raise ArchiveError(f"{name}: table /cases lacks column(s) {', '.join(missing)}")
    for column, _, units in CASE_COLUMNS:
        if column not in cases.dtype.names:
            continue
        dtype = cases.dtype.fields[column][0]
        is_text = h5py.check_string_dtype(dtype) is not None or dtype.kind == "S"
        if (units == TEXT and not (is_text or dtype.kind == "b")) or (
            units != TEXT and dtype.kind not in "biuf"
        ):
            raise ArchiveError(f"{name}: column /cases/{column} has the wrong type ({dtype})")
    group = h5.get("histories")
    if group is None:
        return
    if not isinstance(group, h5py.Group):
        raise ArchiveError(f"{name}: /histories is a dataset where a group belongs")
    for key, case in group.items():
        arrays = list(case.values()) if isinstance(case, h5py.Group) else [case]
        lengths = {
            a.shape[0] if isinstance(a, h5py.Dataset) and a.ndim == 1 else -1 for a in arrays
        }
        if not isinstance(case, h5py.Group) or -1 in lengths or len(lengths) > 1:
            raise ArchiveError(
                f"{name}: /histories/{printable(key)[:40]} is not a group of 1-D arrays "
                "of one length"
            )


def _open(path: str | os.PathLike):
    if not is_sweep_archive(path):
        raise ArchiveError(f"{str(path)!r} is not a rockscreen sweep archive")
    h5 = h5py.File(path, "r")
    with closed_on_failure(h5):
        if _version(h5, path) is None:
            raise ArchiveError(f"{str(path)!r} is not a rockscreen sweep archive")
        with reading(path):
            check_tree(h5, path)  # no external links, external or virtual storage, ...
            check_sweep_tables(h5, path)
    return h5


def read_cases(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Read the ``/cases`` table of a sweep archive as a list of dicts (strings decoded).

    Rows of a version-1 archive get ``formulation = "consistent"`` (the only one then).

    Raises
    ------
    ArchiveError
        If the file is not a sweep archive, or of an unsupported version.
    """
    with _open(path) as h5:
        table = h5["cases"][()]
    rows = [{name: _text(row[name]) for name in table.dtype.names} for row in table]
    for row in rows:
        row.setdefault("formulation", "consistent")
    return rows


def read_history(path: str | os.PathLike, index: int) -> dict[str, np.ndarray]:
    """Read ``/histories/<index>`` of a sweep archive (arrays keyed t, theta, u, regime...).

    Raises
    ------
    ArchiveError
        If the file is not a sweep archive or holds no such case.
    """
    with _open(path) as h5:
        key = f"histories/{index}"
        if key not in h5:
            raise ArchiveError(f"{str(path)!r} holds no history for case {index}")
        return {name: ds[()] for name, ds in h5[key].items()}


def read_histories(path: str | os.PathLike) -> dict[int, dict[str, np.ndarray]]:
    """Read every ``/histories/<index>`` of a sweep archive, opening and checking it once.

    Returns
    -------
    dict
        Case index -> arrays keyed t, theta, u, regime, ... (cases without history absent).

    Raises
    ------
    ArchiveError
        If the file is not a sweep archive.
    """
    with _open(path) as h5:
        group = h5.get("histories", {})
        return {
            int(key): {name: ds[()] for name, ds in group[key].items()}
            for key in group
            if str(key).isdigit()
        }


def read_archive_attrs(path: str | os.PathLike) -> dict[str, Any]:
    """Return the root and ``/tower`` attributes of a sweep archive."""
    with _open(path) as h5:
        attrs = {k: _text(v) for k, v in h5.attrs.items()}
        attrs["tower"] = {k: _text(v) for k, v in h5["tower"].attrs.items()}
    return attrs
