"""The screening campaign: towers x paired records x components x models -> archive.

Flow (docs/campaign.md):

1. :func:`rockscreen.pipeline.screening.inputs.prepare_records` reads every record file,
   processes each trace and groups traces into records; unreadable or unprocessable
   files are failures, not errors.
2. :func:`rockscreen.pipeline.screening.inputs.pair` pairs towers with the stations of the records
   (:mod:`rockscreen.stations.pairing`); unpaired towers are failures.
3. :func:`run_campaign` splits the paired towers into chunks of tower tasks, has an
   executor (:mod:`pipeline.execution.local`) compute them, and writes each chunk's results
   to the archive (:mod:`rockscreen.pipeline.archive.campaign`) from this process only.

Per tower (:func:`rockscreen.pipeline.screening.evaluate.evaluate_tower`, run in the workers), for
each paired record and each horizontal component:

- components: rotated to the tower's axes when its azimuth and the channel azimuths
  are known (component ``X`` along the azimuth with the tower's ``width_m``, ``Y``
  90 deg clockwise from it with its plan depth); otherwise each recorded horizontal as
  is, with the tower's smaller plan dimension (the more slender direction: the
  conservative choice when the orientation is unknown);
- models: ``ground`` (single block on the component), ``floor`` (single block on the
  modal floor accelerogram at the tower's springing, for towers with building data),
  ``double`` (tower rocking on the building sliding on its foundation, for towers
  with masses and friction coefficients);
- the vertical component, when recorded, is the ``acc_v`` of every model (the
  building is taken as rigid vertically).

The governing case of a tower is the worst one: overturned first, then the largest
``theta_max/alpha`` (ties: the first in record, component, model order). The safety
factor (:func:`pipeline.screening.risk.safety_factor`) is searched on the governing case only.
"""

from __future__ import annotations

import hashlib
import json
import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from rockscreen.pipeline.config import CampaignConfig
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import run_chunk


def chunk_tasks(tasks: Sequence[TowerTask], jobs: int, size: int | None = None) -> list[list]:
    """Split tasks into chunks: many towers each, yet >= ~8 chunks per worker.

    Parameters
    ----------
    tasks : sequence of TowerTask
    jobs : int
        Worker processes.
    size : int, optional
        Towers per chunk; default ``clip(ceil(n / (8 jobs)), 1, 64)``: small enough
        for load balance and a live progress bar, large enough that the per-chunk
        cost (pickling, one archive append) stays negligible.

    Returns
    -------
    list of list of TowerTask
    """
    if size is None:
        size = min(64, max(1, math.ceil(len(tasks) / (8 * max(1, jobs)))))
    return [list(tasks[i : i + size]) for i in range(0, len(tasks), size)]


def fingerprint(
    towers_table: np.ndarray, motions: dict[str, GroundMotion], config: CampaignConfig, version: str
) -> str:
    """Return a SHA-256 of everything that determines an archive's results.

    The tower table, the processed records (ids, sampling, samples), the resolved
    configuration and the software version: a ``.part`` file with another print is
    not resumed.
    """
    digest = hashlib.sha256()
    digest.update(version.encode())
    digest.update(config.to_toml().encode())
    digest.update(towers_table.tobytes())
    digest.update(repr(towers_table.dtype).encode())
    for record_id in sorted(motions):
        motion = motions[record_id]
        header = [record_id, motion.station, motion.dt, motion.channels, motion.azimuths]
        digest.update(json.dumps(header, default=str).encode())
        for array in (*motion.horizontals, motion.vertical):
            if array is not None:
                digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    return digest.hexdigest()


def run_campaign(
    tasks: Sequence[TowerTask],
    shared: CampaignShared,
    writer: Any,
    executor: Any,
    *,
    jobs: int = 1,
    chunk_size: int | None = None,
    progress: Callable[[int], None] | None = None,
) -> int:
    """Compute the tower tasks the archive does not hold yet and append them.

    Parameters
    ----------
    tasks : sequence of TowerTask
        Every paired tower of the campaign.
    shared : CampaignShared
    writer : rockscreen.pipeline.archive.campaign.ArchiveWriter
        Open on the ``.part`` file; its ``done`` set lists towers already written.
    executor : SerialExecutor or ProcessExecutor
    jobs : int
        Worker count (for chunk sizing).
    chunk_size : int, optional
        Towers per chunk (default: :func:`chunk_tasks`).
    progress : callable, optional
        Called with the number of towers of each written chunk.

    Returns
    -------
    int
        Number of towers computed in this call.
    """
    todo = [task for task in tasks if task.tower.id not in writer.done]
    chunks = chunk_tasks(todo, jobs, chunk_size)
    written = 0
    with executor:
        executor.start(run_chunk, shared)
        for chunk in chunks:
            executor.submit(chunk)
        for outcomes in executor.completed():
            writer.append(outcomes)
            written += len(outcomes)
            if progress is not None:
                progress(len(outcomes))
    return written
