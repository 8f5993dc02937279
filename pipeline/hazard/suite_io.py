"""A suite of recorded accelerograms read from files, for the record selection.

:func:`load_suite` reads a folder or a list of record files with the project's readers
(:mod:`rockscreen.pipeline.records`) into the candidates
(:class:`~rockscreen.pipeline.hazard.selection.SuiteRecord`) of
:func:`rockscreen.pipeline.hazard.selection.select_records`.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.selection import SuiteRecord

__all__ = ["load_suite"]


def _folder_records(folder: Path) -> tuple[list[Path], Path | None]:
    """Return a folder's record files (format recognised) and its single StationXML, if one."""
    from rockscreen.pipeline.errors import RecordFormatError
    from rockscreen.pipeline.records.io import file_format

    files = []
    for path in sorted(p for p in folder.iterdir() if p.is_file()):
        try:
            file_format(path)
        except RecordFormatError:
            continue  # not a record (StationXML, spectra, notes): skipped in a folder
        files.append(path)
    xml = sorted(folder.glob("*.xml"))
    return files, xml[0] if len(xml) == 1 else None


def _suite_files(paths_or_folder) -> tuple[list[Path], str, list[Path]]:
    """Return the record files, their origin and the StationXML of their folders.

    The origin (a folder, several, or ``"files"``) goes into each record's source; a
    folder's StationXML is its ``*.xml`` file when it holds exactly one.

    Folders and files may be mixed (``--suite DIR --suite DIR --suite FILE``); a file
    reached twice is read once.
    """
    if isinstance(paths_or_folder, (str, Path)):
        entries = [Path(paths_or_folder)]
    else:
        entries = [Path(p) for p in paths_or_folder]
    files: list[Path] = []
    xmls: list[Path] = []
    for entry in entries:
        if entry.is_dir():
            found, xml = _folder_records(entry)
            if xml is not None:
                xmls.append(xml)
        else:
            found = [entry]
        files.extend(found)
    unique, seen = [], set()
    for path in files:
        key = os.path.realpath(path)
        if key not in seen:
            seen.add(key)
            unique.append(path)
    if len(entries) == 1 and entries[0].is_dir():
        origin = str(entries[0])
    elif all(e.is_dir() for e in entries):
        origin = ", ".join(str(e) for e in entries)
    else:
        origin = "files"
    return unique, origin, xmls


def load_suite(paths_or_folder, *, stations=None, units: str | None = None) -> list[SuiteRecord]:
    """Read a suite of records with the project's readers.

    Parameters
    ----------
    paths_or_folder : str, Path or sequence of them
        Folders (every file whose format is recognised; other files, e.g. StationXML or
        text spectra, are skipped) and record files (each must be readable), mixed at will
        (``--suite DIR --suite DIR``); a file reached twice is read once.
    stations : str, Path or obspy.Inventory, optional
        StationXML; by default the ``*.xml`` file of each folder that holds exactly one
        (merged).
    units : str, optional
        Units of files that carry none (``g``, ``m/s2``, ``cm/s2``).

    Returns
    -------
    list of SuiteRecord
        One per record (:func:`pipeline.records.grouping.group_records`): first horizontal
        as ``x``, second as ``y``, vertical as ``z``; records without a horizontal are left
        out.

    Raises
    ------
    HazardError
        When no record is found.
    RecordFormatError, UnitsError, StationMetadataError
        From the readers, for a named file that cannot be read.
    """
    from rockscreen.pipeline.records.grouping import group_records
    from rockscreen.pipeline.records.io import read_stream
    from rockscreen.stations.stationxml import read_station_metadata

    files, origin, folder_xml = _suite_files(paths_or_folder)
    if stations is None and folder_xml:
        stations = folder_xml
    meta = read_station_metadata(stations) if stations is not None else None
    from obspy import Stream

    stream = Stream()
    for path in files:
        stream += read_stream(path, units=units, stations=meta)
    suite = []
    for record in group_records(stream):
        horizontals = [h for h in (record.h1, record.h2) if h is not None]
        if not horizontals:
            continue
        source = ", ".join(sorted({t.split(".")[-1] for t in record.channels.values()}))
        suite.append(
            SuiteRecord(
                name=record.id,
                acc_x_m_s2=np.asarray(horizontals[0], float),
                acc_y_m_s2=np.asarray(horizontals[1], float) if len(horizontals) > 1 else None,
                acc_z_m_s2=None if record.z is None else np.asarray(record.z, float),
                dt_s=float(record.dt),
                source=f"{record.id} ({source}) from {origin}",
            )
        )
    if not suite:
        raise HazardError(f"no record with a horizontal component in {paths_or_folder!s}")
    return suite
