"""Tell a record file's format from a bounded prefix, before any reader sees the file.

ObsPy's ``read`` without a format tries the ``is_format`` probe of every plugin in turn;
some read a whole line or the whole file, so a 1 GB file without a line break took
minutes and gigabytes to be called "unknown format". :func:`detect_format` reads at most
:data:`PROBE_BYTES` once and asks, on that prefix only: ESM, AT2, K-NET (text), miniSEED,
SAC (binary). A file none of them claims is handed to ObsPy's own detection only when its
first KiB is text with a line break in the prefix (ObsPy's other text formats); any other
binary file is refused at once.
"""

from __future__ import annotations

import io

from obspy.io.mseed.core import _is_mseed
from obspy.io.nied.knet import _is_knet_ascii
from obspy.io.sac.core import _is_sac

from rockscreen.pipeline.errors import RecordFormatError
from rockscreen.pipeline.records.readers.at2 import is_at2
from rockscreen.pipeline.records.readers.esm import is_esm
from rockscreen.pipeline.records.readers.text import PROBE_BYTES
from rockscreen.pipeline.text import printable

#: Bytes whose share decides whether a file is text.
TEXT_SAMPLE_BYTES = 1024

_TEXT_BYTES = frozenset(b"\t\n\r\f") | frozenset(range(0x20, 0x7F))


def looks_like_text(sample: bytes) -> bool:
    """Whether ``sample`` reads as text: no NUL byte and at least 90 % printable ASCII."""
    if not sample or b"\x00" in sample:
        return False
    printable_share = sum(byte in _TEXT_BYTES for byte in sample) / len(sample)
    return printable_share >= 0.9


def _binary_format(prefix: bytes) -> str | None:
    if len(prefix) >= 128 and _is_mseed(io.BytesIO(prefix)):
        return "MSEED"
    if len(prefix) >= 632 and _is_sac(io.BytesIO(prefix)):
        return "SAC"
    return None


def detect_format(path) -> str | None:
    """Return the format of a record file, judged on its first :data:`PROBE_BYTES` bytes.

    Parameters
    ----------
    path : str or path-like
        A regular file (see :func:`rockscreen.pipeline.records.paths.check_record_file`).

    Returns
    -------
    str or None
        ``ESM``, ``AT2``, ``KNET``, ``MSEED`` or ``SAC``; None for a text file none of
        these claims (ObsPy's detection may know it).

    Raises
    ------
    RecordFormatError
        Naming the file when it is binary and neither miniSEED nor SAC, UTF-16 text, or
        text without a line break in its first :data:`PROBE_BYTES` bytes.
    """
    name = printable(str(path))
    try:
        with open(path, "rb") as handle:
            prefix = handle.read(PROBE_BYTES)
    except OSError as exc:
        raise RecordFormatError(f"{name}: cannot read: {exc.strerror or exc}") from exc
    if is_esm(path):
        return "ESM"
    if is_at2(path):
        return "AT2"
    if _is_knet_ascii(io.BytesIO(prefix)):
        return "KNET"
    found = _binary_format(prefix)
    if found is not None:
        return found
    known = "ESM/ITACA ASCII, PEER AT2, K-NET, miniSEED, SAC"
    if prefix.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise RecordFormatError(
            f"{name}: UTF-16 text; record files are ASCII (or UTF-8): save it as such"
        )
    if not looks_like_text(prefix[:TEXT_SAMPLE_BYTES]):
        raise RecordFormatError(
            f"{name}: unknown format: binary, and neither miniSEED nor SAC (known: {known})"
        )
    if len(prefix) == PROBE_BYTES and not any(c in prefix for c in (b"\n", b"\r")):
        raise RecordFormatError(
            f"{name}: unknown format: text without a line break in its first "
            f"{PROBE_BYTES // 1024} KiB (known: {known})"
        )
    return None


__all__ = ["PROBE_BYTES", "detect_format", "looks_like_text"]
