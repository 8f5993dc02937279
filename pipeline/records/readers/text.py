"""Parts shared by the plain-text record readers: header lines, whole file, value body.

Also what the readers' ObsPy entry points (``isFormat``, ``readFormat``) have in common:
the never-raising probe (:func:`probe_lines`) and the docstring sections of their fixed
signatures (:data:`PLUGIN_DOCS`, filled by :func:`rockscreen.solver.docstrings.fill_doc`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from rockscreen.pipeline.errors import RecordFormatError

#: Docstring sections of the ObsPy entry points, whose signatures ObsPy fixes: the
#: ``isFormat`` probe's whole Parameters/Returns (``probe_sections``) and the options of
#: ``readFormat`` after its ``filename`` (``read_options``).
PLUGIN_DOCS = {
    "probe_sections": """
Parameters
----------
filename : str or path-like
    File to inspect.

Returns
-------
bool
    Whether the file is of the reader's format.
""",
    "read_options": """
headonly : bool
    Read only the header: ``stats.npts`` from the header's count of samples, no data.
**kwargs
    Ignored (ObsPy passes its own options to every plugin).
""",
}

#: Bytes a format probe reads at most (a header never needs more; a 1 GB file without a
#: line break must not be read whole to learn that it is not a record).
PROBE_BYTES = 64 * 1024


def head_lines(filename, count: int, max_bytes: int = PROBE_BYTES) -> list[str]:
    """Return up to ``count`` first lines of a text file (bytes decoded as Latin-1).

    Latin-1 decodes any byte, so a binary file yields garbage lines rather than an error:
    the ``is_*`` format probes then reject it on content. At most ``max_bytes`` bytes are
    read; a line cut there is returned as it is.
    """
    with open(filename, "rb") as handle:
        prefix = handle.read(max_bytes)
    return [raw.decode("latin-1") for raw in prefix.splitlines()[:count]]


def probe_lines(filename, count: int, accept: Callable[[list[str]], bool]) -> bool:
    """Whether ``accept`` holds for the first ``count`` lines of a file; never raises.

    A file that cannot be opened or read, and lines on which ``accept`` raises
    :class:`ValueError` (a number that is not one), answer False: an ``isFormat`` probe
    must let ObsPy try the next format.
    """
    try:
        return bool(accept(head_lines(filename, count)))
    except (OSError, TypeError, ValueError):
        return False


#: Largest text record read [bytes]: a day of 3 components at 200 Hz in ESM layout is
#: about 250 MB; anything larger is not one accelerogram.
MAX_TEXT_BYTES = 256 * 1024 * 1024


def read_lines(filename) -> list[str]:
    """Return all lines of a text file (Latin-1).

    Raises
    ------
    RecordFormatError
        If the file cannot be read or exceeds :data:`MAX_TEXT_BYTES`.
    """
    try:
        with open(filename, "rb") as handle:
            raw = handle.read(MAX_TEXT_BYTES + 1)
    except OSError as exc:
        raise RecordFormatError(f"{filename}: cannot read: {exc.strerror or exc}") from exc
    if len(raw) > MAX_TEXT_BYTES:
        raise RecordFormatError(
            f"{filename}: more than {MAX_TEXT_BYTES // 2**20} MiB of text; "
            "not one accelerogram (allowed: at most that size)"
        )
    return raw.decode("latin-1").splitlines()


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
        If the count differs from ``npts`` (truncated file), a value is not a number, or
        a value is NaN or infinite.
    """
    body = " ".join(body_lines).split()
    if len(body) != npts:
        raise RecordFormatError(
            f"{filename}: {len(body)} values after the header but {count_key}={npts}"
            + (" (truncated file)" if len(body) < npts else "")
        )
    try:
        values = np.array(body, dtype=np.float64)
    except ValueError as exc:
        raise RecordFormatError(f"{filename}: non-numeric data value: {exc}") from exc
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raise RecordFormatError(
            f"{filename}: {bad.size} data value(s) are NaN or infinite (first: value "
            f"{bad[0] + 1} of {npts}, {body[bad[0]][:20]!r}); a record holds finite numbers"
        )
    return values


def check_sampling(delta: float, key: str, filename) -> float:
    """Return the sampling interval ``delta`` [s] after checking it is finite and > 0.

    Raises
    ------
    RecordFormatError
        Naming the file and header ``key`` when ``delta`` is zero, negative, NaN or
        infinite.
    """
    if not (math.isfinite(delta) and delta > 0):
        raise RecordFormatError(
            f"{filename}: header {key}={delta!r} is not a sampling interval "
            "(allowed: a finite number > 0 [s])"
        )
    return delta
