"""The record sets an assess archive stores, as the sets a rerun takes.

An assess archive (version 3) keeps every record of its sets once (``/records``) and each
set as references, record and exact scale factor (``/set_records``), beside its
``/selection`` row (site, return period, the mean/target ratios and the period range they
are measured over). :func:`archived_record_sets` rebuilds the sets from them;
:func:`rockscreen.pipeline.risk.assess.run.run_assess` takes them (``record_sets``) instead of
selecting, and so reproduces every verdict of the archive exactly (same towers, same
options). See ``docs/risk.md`` (Archives).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rockscreen.pipeline.archive.risk_reader import read_records, read_selection, read_set_records
from rockscreen.pipeline.hazard.selection import RecordSet, SuiteRecord

__all__ = ["archived_record_sets"]


def _frozen(acc: np.ndarray | None) -> np.ndarray | None:
    if acc is not None:
        acc.setflags(write=False)
    return acc


def archived_record_sets(path: str | Path) -> dict[tuple, RecordSet]:
    """Return the record sets of an assess archive, by site and return period.

    Parameters
    ----------
    path : str or Path
        An assess archive of version 3.

    Returns
    -------
    dict
        (site lon [deg], site lat [deg], soil class, topography, return period [y]) ->
        :class:`~rockscreen.pipeline.hazard.selection.RecordSet`: the records as stored
        (float64, unscaled, read-only; a record held by several sets is one object), the
        exact factors, ``ratio_min``, ``ratio_max``, ``meets_tolerance`` and ``message`` of
        ``/selection``, and ``periods_s`` the two ends of the range the ratios were
        measured over. The mean and target spectra are not stored: ``mean_sa_g`` and
        ``target_sa_g`` are empty.

    Raises
    ------
    ArchiveError
        When the file is not a sound assess archive, or is of version 2 (its factors are
        rounded: the refusal names the command that rebuilds it).
    """
    references = read_set_records(path)
    selection = read_selection(path)
    stored = read_records(path)
    records = {
        record_id: SuiteRecord(
            r["name"], _frozen(r["x"]), _frozen(r["y"]), _frozen(r["z"]), r["dt_s"], r["source"]
        )
        for record_id, r in stored.items()
    }
    out: dict[tuple, RecordSet] = {}
    for row, refs in zip(selection, references, strict=True):
        key = (
            float(row["site_lon_deg"]),
            float(row["site_lat_deg"]),
            str(row["soil_class"]),
            str(row["topography"]),
            float(row["return_period_y"]),
        )
        factors = np.array([factor for _, factor in refs], dtype=float)
        factors.setflags(write=False)
        out[key] = RecordSet(
            records=tuple(records[record_id] for record_id, _ in refs),
            scale_factors=factors,
            periods_s=np.array([row["period_from_s"], row["period_to_s"]], dtype=float),
            mean_sa_g=np.zeros(0),
            target_sa_g=np.zeros(0),
            ratio_min=float(row["ratio_min"]),
            ratio_max=float(row["ratio_max"]),
            meets_tolerance=bool(row["meets_tolerance"]),
            message=str(row["message"]),
        )
    return out
