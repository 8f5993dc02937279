"""ObsPy waveform plugins for formats ObsPy lacks (ESM/ITACA ASCII, PEER AT2)."""
