"""Shared parameter descriptions are filled into docstrings at their placeholder's indent."""

import pytest

from rockscreen.solver.docstrings import fill_doc

SNIPPETS = {"acc_dt": "acc : array_like\n    Acceleration [m/s2].\ndt : float\n    Step [s]."}


def test_a_placeholder_line_becomes_the_indented_block():
    @fill_doc(SNIPPETS)
    def f(acc, dt):
        """Do it.

        Parameters
        ----------
        %(acc_dt)s
        """

    assert "        acc : array_like\n            Acceleration [m/s2].\n" in f.__doc__
    assert "        dt : float\n            Step [s]." in f.__doc__
    assert "%(" not in f.__doc__


def test_an_unknown_block_fails_at_decoration():
    with pytest.raises(KeyError, match="nope"):

        @fill_doc(SNIPPETS)
        def f():
            """Do it.

            %(nope)s
            """


def test_a_missing_docstring_is_left_alone():
    @fill_doc(SNIPPETS)
    def f():
        pass

    assert f.__doc__ is None
