"""Text that came from a file, made safe to print on a terminal.

Record ids, station codes, header strings and file names are data: a file can hold a
terminal escape sequence (``ESC ] 0 ; title BEL`` retitles the window, ``ESC [ 2 J`` clears
it) or bytes that are not UTF-8 (Python keeps them in ``str`` as lone surrogates, which
``print`` cannot encode). :func:`printable` escapes both, so whatever is printed is exactly
one line of visible characters.
"""

from __future__ import annotations

import re

# C0 controls (tab and newline included: printed values must stay on one line), DEL, the
# C1 controls U+0080..U+009F (some terminals act on them as on ESC sequences), and the
# bidirectional formatting characters (U+061C, U+200E/F, U+202A..U+202E, U+2066..U+2069),
# which reorder what follows on the line: an id "TOWER\u202eLIAF" prints as "TOWERFAIL"
# reversed (the "Trojan Source" trick, CVE-2021-42574).
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")
_SURROGATE = re.compile(r"[\ud800-\udfff]")


def _escape_control(match: re.Match) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code <= 0xFF else f"\\u{code:04x}"


def _escape_surrogate(match: re.Match) -> str:
    code = ord(match.group())
    # surrogateescape maps an undecodable byte b to U+DC00 + b: show the byte itself.
    if 0xDC80 <= code <= 0xDCFF:
        return f"\\x{code - 0xDC00:02x}"
    return f"\\u{code:04x}"


def printable(text) -> str:
    r"""Return ``text`` with every character a terminal could act on escaped.

    Parameters
    ----------
    text : str or bytes or object
        Anything to print; bytes are decoded as UTF-8 with undecodable bytes kept as
        escapes, other objects go through ``str``.

    Returns
    -------
    str
        ``text`` with C0 controls (including tab and newline), DEL and C1 controls
        written as ``\xNN``, the bidirectional formatting characters as ``\uNNNN``, and
        lone surrogates (the undecodable bytes of a non-UTF-8
        file name) as ``\xNN`` (the original byte) or ``\uNNNN``. Printable text,
        accents included, is unchanged.

    Examples
    --------
    >>> printable("X\x1b]0;pwned\x07")
    'X\\x1b]0;pwned\\x07'
    >>> printable(b"bad\xffname")
    'bad\\xffname'
    """
    if isinstance(text, bytes):
        text = text.decode("utf-8", "surrogateescape")
    elif not isinstance(text, str):
        text = str(text)
    text = _CONTROL.sub(_escape_control, text)
    return _SURROGATE.sub(_escape_surrogate, text)


def storable(text: str) -> str:
    """Return ``text`` with only its lone surrogates escaped, so HDF5 can store it as UTF-8.

    A non-UTF-8 file name reaches Python as ``str`` with lone surrogates, which no UTF-8
    writer accepts; newlines and every other character are kept (unlike :func:`printable`).
    """
    return _SURROGATE.sub(_escape_surrogate, text)


__all__ = ["printable", "storable"]
