"""Records in, results out: readers, processing, excitations, spectra, campaigns, archive, CLI."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("rockscreen")
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"
