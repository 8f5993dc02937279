"""The post-event scenario (``rockscreen scenario``) from a ShakeMap and an assessment.

The probability of overturning of each tower under one event's ground motion (the
grid read by :mod:`rockscreen.pipeline.hazard.shakemap`), the command's run to its
archive, and the example event grid.

Modules:

- :mod:`.example_shakemap`: The example event grid: a ShakeMap 4-style ``grid.xml`` that rockscreen
  generates itself.
- :mod:`.probability`: ``rockscreen scenario``: probability of overturning of each tower under one
  event.
- :mod:`.run`: A post-event scenario from files to its archive (``rockscreen scenario``).
"""
