"""A post-event scenario from files to its archive (``rockscreen scenario``).

:func:`run_scenario` reads the ShakeMap grid and the fragilities of an assess archive,
computes every tower's probability of overturning (:mod:`rockscreen.pipeline.risk.scenario`), writes
the scenario archive (with the ShakeMap PGA grid for the report's contours) and, on
request, the map. The command line only parses options and prints.
"""

from __future__ import annotations

import shlex
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from rockscreen.pipeline.archive.risk_archive import read_summary, write_risk_archive
from rockscreen.pipeline.risk.scenario import scenario_rows
from rockscreen.pipeline.risk.shakemap import (
    DEFAULT_SIGMA_SOURCE,
    ShakeMapGrid,
    find_uncertainty,
    read_shakemap_grid,
    read_uncertainty,
    shakemap_arrays,
)

#: Statuses of towers that get no probability, listed in the archive's failures table.
NOT_ESTIMATED = ("outside_grid", "no_coordinates", "no_fragility")


def run_scenario(
    shakemap: str | Path,
    fragility: str | Path,
    out_path: str | Path,
    *,
    tower_ids: Sequence[str] | None = None,
    strict_grid: bool = False,
    uncertainty: str | Path | None = None,
    gm_uncertainty: bool = True,
    notify: Callable[[str], None] = lambda text: None,
) -> tuple[list[dict[str, Any]], list[dict[str, str]], ShakeMapGrid]:
    """Compute a scenario and write its archive.

    Parameters
    ----------
    shakemap : str or Path
        ShakeMap 3 or 4 ``grid.xml``.
    fragility : str or Path
        Assess archive holding the towers' fragilities.
    out_path : str or Path
        Scenario archive to write (atomically).
    tower_ids : sequence of str, optional
        Restrict to these towers.
    strict_grid : bool
        Refuse a grid with fewer rows than its header says (default: warn).
    uncertainty : str or Path, optional
        ShakeMap 4 ``uncertainty.xml`` (STDPGA, ln units); by default the one beside the
        grid (:func:`rockscreen.pipeline.risk.shakemap.find_uncertainty`) when the grid has
        no STDPGA of its own.
    gm_uncertainty : bool
        False: sigma_lnPGA = 0 (the event PGA taken as known), every row says so.
    notify : callable
        Called with each message for the user (warnings, files written).

    Returns
    -------
    rows : list of dict
        One row per tower (:func:`rockscreen.pipeline.risk.scenario.scenario_rows`).
    failures : list of dict
        The towers that got no probability, with the reason.
    grid : ShakeMapGrid
        The event grid (its ``event`` attributes for the caller's header).
    """
    grid = read_shakemap_grid(shakemap, strict=strict_grid)
    if grid.warning:
        notify(f"warning: {grid.warning}")
    if uncertainty is None and grid.sigma_ln_pga is None and gm_uncertainty:
        uncertainty = find_uncertainty(shakemap)
    if uncertainty is not None and gm_uncertainty:
        read_uncertainty(uncertainty, grid)
    if not gm_uncertainty:
        notify("sigma_lnPGA = 0 (--no-gm-uncertainty): the event PGA is taken as known")
    elif grid.sigma_ln_pga is None:
        notify(f"no STDPGA in the grid and no uncertainty.xml: {DEFAULT_SIGMA_SOURCE}")
    else:
        notify(f"sigma_lnPGA from the {grid.sigma_source}")
    rows = scenario_rows(
        read_summary(fragility, "assess"), grid, tower_ids, gm_uncertainty=gm_uncertainty
    )
    metadata = {
        "command_line": shlex.join(["rockscreen", *sys.argv[1:]]),
        "shakemap_source": str(shakemap),
        "shakemap_version": grid.version,
        "shakemap_event": grid.event,
        "shakemap_rows": grid.n_rows,
        "shakemap_warning": grid.warning,
        "shakemap_uncertainty_source": str(uncertainty or ""),
        "gm_uncertainty": bool(gm_uncertainty),
        "fragility_source": str(fragility),
    }
    failures = [
        {"kind": r["status"], "subject": r["id"], "reason": r["note"]}
        for r in rows
        if r["status"] in NOT_ESTIMATED
    ]
    write_risk_archive(
        out_path,
        "scenario",
        {"summary": rows, "failures": failures},
        metadata,
        empty_columns={"failures": ("kind", "subject", "reason")},
        arrays=shakemap_arrays(grid),
    )
    notify(f"scenario archive written to {out_path}")
    return rows, failures, grid
