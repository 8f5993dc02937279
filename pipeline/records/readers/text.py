"""Parts shared by the plain-text record readers: header lines, whole file, value body."""

from __future__ import annotations

import numpy as np

from pipeline.errors import RecordFormatError


def head_lines(filename, count: int) -> list[str]:
    """Return up to ``count`` first lines of a text file (bytes decoded as Latin-1).

    Latin-1 decodes any byte, so a binary file yields garbage lines rather than an error:
    the ``is_*`` format probes then reject it on content.
    """
    lines = []
    with open(filename, "rb") as handle:
        for raw in handle:
            lines.append(raw.decode("latin-1").rstrip("\r\n"))
            if len(lines) >= count:
                break
    return lines


def read_lines(filename) -> list[str]:
    """Return all lines of a text file (Latin-1).

    Raises
    ------
    RecordFormatError
        If the file cannot be read.
    """
    try:
        with open(filename, "rb") as handle:
            text = handle.read().decode("latin-1")
    except OSError as exc:
        raise RecordFormatError(f"{filename}: cannot read: {exc.strerror or exc}") from exc
    return text.splitlines()


def read_values(body_lines: list[str], npts: int, count_key: str, filename) -> np.ndarray:
    """Parse the whitespace-separated values after a header, exactly ``npts`` of them.

    Parameters
    ----------
    body_lines : list of str
        The lines after the header.
    npts : int
        Number of values the header announces.
    count_key : str
        Header key that announced ``npts`` (``NPTS``, ``NDATA``), for the messages.
    filename : str or path-like
        The file, for the messages.

    Returns
    -------
    ndarray, shape (npts,)
        The values, float64, in the file's units.

    Raises
    ------
    RecordFormatError
        If the count differs from ``npts`` (truncated file) or a value is not a number.
    """
    body = " ".join(body_lines).split()
    if len(body) != npts:
        raise RecordFormatError(
            f"{filename}: {len(body)} values after the header but {count_key}={npts}"
            + (" (truncated file)" if len(body) < npts else "")
        )
    try:
        return np.array(body, dtype=np.float64)
    except ValueError as exc:
        raise RecordFormatError(f"{filename}: non-numeric data value: {exc}") from exc
