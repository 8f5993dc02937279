"""The tower models, one module each; :mod:`rockscreen.pipeline.engine.registry` finds them.

A module here defines ``MODEL``, a :class:`rockscreen.pipeline.engine.registry.TowerModel`.
Adding a model is adding a module (with its test and its page in ``docs/``): the
configuration, the command line, the stripes, the archive and the report read the
registry, so nothing else changes. A model module must import nothing heavy at module
level (``rockscreen --help`` lists the models without loading numba).
"""
