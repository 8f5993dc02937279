"""Figure of the elastic spectra of the four limit states at a site (matplotlib, Agg canvas)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from rockscreen.pipeline.hazard.site import HazardResult
from rockscreen.pipeline.hazard.spectrum import elastic_spectrum

__all__ = ["plot_limit_state_spectra"]


def plot_limit_state_spectra(results: list[HazardResult], path: str | Path) -> Path:
    """Draw Se(T) of each result (one per limit state) into a PNG.

    Parameters
    ----------
    results : list of HazardResult
        Typically the four limit states at one site, same soil and topography.
    path : str or Path
        Output PNG.

    Returns
    -------
    Path
        The written file.
    """
    periods = np.linspace(0.0, 4.0, 401)
    figure = Figure(figsize=(7.0, 4.5))
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    for result in results:
        se = elastic_spectrum(
            periods, result.site, result.soil_class, result.topography, result.damping
        )
        label = result.limit_state or "TR"
        axes.plot(periods, se, label=f"{label}: TR = {result.site.return_period_y:.0f} y, "
                  f"ag = {result.site.ag_g:.3f} g")  # fmt: skip
    first = results[0]
    axes.set_xlabel("period T [s]")
    axes.set_ylabel("elastic spectral acceleration Se [g]")
    axes.set_title(
        f"NTC 2018 elastic spectra at {first.site.lon_deg:.4f} E, {first.site.lat_deg:.4f} N "
        f"(soil {first.soil_class}, {first.topography}, damping {100 * first.damping:g} %)",
        fontsize=9,
    )
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize=8)
    axes.set_xlim(0.0, periods[-1])
    axes.set_ylim(bottom=0.0)
    path = Path(path)
    figure.savefig(path, dpi=120)
    return path
