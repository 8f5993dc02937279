"""The typed verdict: what a tower's checks found, as data, below the risk, archive and report.

A tower's verdict is built from typed check results (:mod:`.status`: a status the code
branches on, a bound as an enum) and messages as codes (:mod:`.messages`: a code and its
parameters, rendered in English or Italian from one catalogue). Nothing here computes a
capacity or reads a file: the products (``risk``, ``screening``) produce these records, the
archive stores them, the report renders them. This package imports no stage of the pipeline.
"""
