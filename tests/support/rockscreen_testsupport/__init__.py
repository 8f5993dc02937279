"""Helpers shared by the test files (not collected: no ``test_*`` module here).

The tests are not a package (pytest imports them with ``--import-mode=importlib``), so a
helper two test files need lives here instead of being copied: pytest puts
``tests/support`` on ``sys.path`` (``pythonpath`` in ``[tool.pytest.ini_options]``), and
the package's name cannot be mistaken for the project's (``rockscreen``) or a library's.
Its names are public: no test imports another module's private name.

- :mod:`rockscreen_testsupport.records`: the stochastic suite records of the assess tests.
- :mod:`rockscreen_testsupport.towers`: the L'Aquila site and the towers shared by tests.
- :mod:`rockscreen_testsupport.checks`: checks not made, for the verdict tests.
- :mod:`rockscreen_testsupport.cli`: the command line run in a subprocess.
"""
