"""Where things are: seismic stations, the tower inventory, and tower-record pairing.

This package never imports ``rockscreen.solver``.
"""
