"""Screening (``rockscreen run``): towers × recorded motions, governing case, safety factor.

A thin calculator over the case engine (:mod:`rockscreen.pipeline.engine`): it pairs
towers with records (:mod:`~rockscreen.pipeline.screening.inputs`), runs every case of a
tower through the engine, finds the governing one, searches its safety factor and
classes the tower (:mod:`~rockscreen.pipeline.screening.evaluate`,
:mod:`~rockscreen.pipeline.screening.risk`), and streams the results into the archive
(:mod:`~rockscreen.pipeline.screening.campaign`, :mod:`~rockscreen.pipeline.screening.batch`).
"""
