"""Which StationXML files the user means: files, folders of StationXML, quoted globs.

``--stations`` may be given several times and each value may be a file, a folder (its
``*.xml`` files, not recursive) or a glob pattern (``'meta/*.xml'``, left unexpanded by
quoting or by the shell). :func:`expand_station_paths` turns them into files, each once,
with the standard library only (the command line checks them before importing ObsPy);
:func:`rockscreen.stations.stationxml.read_station_metadata` reads and merges them.
"""

from __future__ import annotations

import glob
import os
from collections.abc import Iterable
from pathlib import Path

from rockscreen.stations.errors import StationMetadataError

__all__ = ["STATIONXML_EXTENSIONS", "expand_station_paths"]

#: Extensions of the files a folder of StationXML contributes (lower case).
STATIONXML_EXTENSIONS = (".xml", ".stationxml")


def _shown(path: str) -> str:
    return "".join(
        f"\\x{ord(c) & 0xFF:02x}" if ord(c) < 0x20 or 0x7F <= ord(c) <= 0x9F else c
        for c in str(path)
    )


def _folder_files(folder: str) -> list[str]:
    try:
        names = sorted(
            entry.name
            for entry in os.scandir(folder)
            if not entry.name.startswith(".")
            and entry.is_file()
            and os.path.splitext(entry.name)[1].lower() in STATIONXML_EXTENSIONS
        )
    except OSError as exc:
        raise StationMetadataError(
            f"station metadata folder {_shown(folder)!r}: cannot be listed ({exc.strerror or exc})"
        ) from None
    if not names:
        raise StationMetadataError(
            f"station metadata folder {_shown(folder)!r} holds no StationXML file "
            f"({', '.join(STATIONXML_EXTENSIONS)})"
        )
    return [os.path.join(folder, name) for name in names]


def expand_station_paths(sources: str | os.PathLike | Iterable[str | os.PathLike]) -> list[Path]:
    """Return the StationXML files named by files, folders and glob patterns, each once.

    Parameters
    ----------
    sources : str, path-like, or iterable of them
        What the user gave (``--stations`` values, the configuration's ``stations``).

    Returns
    -------
    list of pathlib.Path
        In argument order: a file as given; a folder's ``*.xml`` / ``*.stationxml`` files
        sorted by name; a pattern's matching files sorted by name. A file reached twice (same
        resolved path) is kept at its first place only.

    Raises
    ------
    StationMetadataError
        Naming the argument: no such file or folder, a folder without StationXML, a
        pattern that matches no file.
    """
    if isinstance(sources, (str, os.PathLike)):
        sources = [sources]
    out: list[Path] = []
    seen: set[str] = set()
    for source in sources:
        text = os.fspath(source)
        if os.path.isdir(text):
            found = _folder_files(text)
        elif os.path.lexists(text):
            found = [text]
        elif glob.has_magic(text):
            found = sorted(m for m in glob.glob(text) if not os.path.isdir(m))
            if not found:
                raise StationMetadataError(
                    f"station metadata {_shown(text)!r}: no file matches this pattern"
                )
        else:
            raise StationMetadataError(f"station metadata {_shown(text)!r}: no such file")
        for path in found:
            key = os.path.realpath(path)
            if key not in seen:
                seen.add(key)
                out.append(Path(path))
    return out
