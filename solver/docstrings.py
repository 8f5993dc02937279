"""Parameter descriptions shared by several docstrings, written once.

The habit of SciPy's ``doccer`` and matplotlib's ``_docstring``: where sibling functions
take the same parameters, their description lives in one mapping and each docstring names
it on a line of its own, ``%(name)s``, at the indentation it should have. :func:`fill_doc`
replaces that line by the description when the module is imported, so ``help()``, IDEs
and Sphinx show the whole text. Used by :mod:`rockscreen.solver` and
:mod:`rockscreen.pipeline` alike (the lowest layer holds it; it imports nothing of either).
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Callable, Mapping
from typing import TypeVar

__all__ = ["fill_doc"]

F = TypeVar("F", bound=Callable)

#: A line that is only a placeholder: its indentation, then ``%(name)s``.
_PLACEHOLDER = re.compile(r"^(?P<indent>[ \t]*)%\((?P<name>\w+)\)s[ \t]*$", re.MULTILINE)


def fill_doc(snippets: Mapping[str, str]) -> Callable[[F], F]:
    """Return a decorator that fills ``%(name)s`` lines of a docstring from ``snippets``.

    Parameters
    ----------
    snippets : mapping of str to str
        Description of each shared parameter block, written at column 0 (a numpydoc
        ``name : type`` line, its description indented by four spaces below it).

    Returns
    -------
    callable
        A decorator returning the same object with its ``__doc__`` filled; a docstring
        stripped by ``python -OO`` is left as None.

    Raises
    ------
    KeyError
        When a docstring names a block that ``snippets`` does not hold (at import time).
    """

    def fill(match: re.Match) -> str:
        block = textwrap.dedent(snippets[match["name"]]).strip("\n")
        return textwrap.indent(block, match["indent"], lambda line: bool(line.strip()))

    def decorate(obj: F) -> F:
        if obj.__doc__:
            obj.__doc__ = _PLACEHOLDER.sub(fill, obj.__doc__)
        return obj

    return decorate
