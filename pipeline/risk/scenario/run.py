"""A post-event scenario from files to its archive (``rockscreen scenario``).

:func:`run_scenario` reads the ShakeMap grid and the fragilities of an assess archive,
computes every tower's probability of overturning
(:mod:`rockscreen.pipeline.risk.scenario.probability`), writes the scenario archive (with the
ShakeMap PGA grid for the report's contours) and, on request, the map. The command line only parses
options and prints.
"""

from __future__ import annotations

import shlex
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from rockscreen.pipeline.archive.lock import claimed_output
from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.archive.risk_reader import read_summary
from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.hazard.shakemap import (
    DEFAULT_SIGMA_SOURCE,
    ShakeMapGrid,
    find_uncertainty,
    read_shakemap_grid,
    read_uncertainty,
    shakemap_arrays,
)
from rockscreen.pipeline.risk.scenario.probability import scenario_rows
from rockscreen.pipeline.text import printable

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
    overwrite: bool = False,
    inputs: Sequence[str | Path] = (),
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
        grid (:func:`rockscreen.pipeline.hazard.shakemap.find_uncertainty`) when the grid has
        no STDPGA of its own.
    gm_uncertainty : bool
        False: sigma_lnPGA = 0 (the event PGA taken as known), every row says so.
    overwrite : bool
        Replace an existing file at ``out_path`` (refused otherwise, before any work).
    inputs : sequence of str or Path
        Other files the caller read (an inventory of ``--towers``): ``out_path`` is never
        one of them nor ``shakemap``, ``fragility`` or ``uncertainty``.
    notify : callable
        Called with each message for the user (warnings, files written).

    Returns
    -------
    rows : list of dict
        One row per tower (:func:`rockscreen.pipeline.risk.scenario.probability.scenario_rows`).
    failures : list of dict
        The towers that got no probability, with the reason.
    grid : ShakeMapGrid
        The event grid (its ``event`` attributes for the caller's header).

    Raises
    ------
    ArchiveError
        When ``out_path`` is an input, exists without ``overwrite``, sits in a missing or
        read-only folder, or another process is writing it.
    ShakeMapError
        For a grid that cannot be read, or that covers none of the towers.
    """
    read = [shakemap, fragility, uncertainty, *inputs]
    with claimed_output(out_path, read, "scenario", overwrite=overwrite):
        return _run_scenario(
            shakemap,
            fragility,
            out_path,
            tower_ids=tower_ids,
            strict_grid=strict_grid,
            uncertainty=uncertainty,
            gm_uncertainty=gm_uncertainty,
            notify=notify,
        )


def _run_scenario(
    shakemap, fragility, out_path, *, tower_ids, strict_grid, uncertainty, gm_uncertainty, notify
) -> tuple[list[dict[str, Any]], list[dict[str, str]], ShakeMapGrid]:
    """Compute the scenario and write its archive (:func:`run_scenario`, under the lock)."""
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
    covered = [r for r in rows if r["status"] not in ("outside_grid", "no_coordinates")]
    if rows and not covered:
        raise ShakeMapError(
            f"{printable(shakemap)}: the ShakeMap (lon {grid.lon_min:g} to {grid.lon_max:g}, lat "
            f"{grid.lat_min:g} to {grid.lat_max:g} deg) covers none of the {len(rows)} "
            "towers; nothing to estimate, no archive written"
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
