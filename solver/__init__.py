"""Rocking, sliding and double-block dynamics of rigid blocks on a moving base.

Pure numerics: arrays of base acceleration [m/s^2] with their sampling step
``dt`` [s] go in, result objects come out. This package never imports
``pipeline``, ``stations``, ObsPy or h5py.
"""
