"""The options of ``rockscreen assess`` (:class:`AssessOptions`), apart from its orchestration.

:mod:`rockscreen.pipeline.risk.assess.run` runs an assessment with them (and re-exports them).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from rockscreen.pipeline.hazard import RETURN_PERIODS_Y
from rockscreen.pipeline.hazard.selection import SCALE_LIMITS
from rockscreen.pipeline.risk.assess.compliance import (
    DEFAULT_TOLERANCE,
    SetCompliance,
    set_compliance,
)
from rockscreen.pipeline.risk.assess.ida import IdaOptions
from rockscreen.pipeline.risk.assess.screening_risk import RiskOptions
from rockscreen.pipeline.risk.assess.stripes import StripeOptions
from rockscreen.pipeline.risk.assess.tower_ida import DEFAULT_BOOTSTRAP_RESAMPLES
from rockscreen.pipeline.risk.measures.classes import DEFAULT_LIMITS

__all__ = ["AssessOptions"]


@dataclass(frozen=True)
class AssessOptions:
    """Options of an assessment."""

    #: Stripes [y] (default the nine tabulated return periods of NTC 2018).
    return_periods_y: tuple[float, ...] = ()
    #: Models, damage levels, free motion.
    stripe: StripeOptions = field(default_factory=StripeOptions)
    #: Keyword arguments of :func:`pipeline.hazard.select_records` (``n_records``, ...);
    #: ``seed`` and ``kind`` (``"stochastic"``, the default, or ``"matched"``) choose the
    #: embedded suite; without ``n_records``, 11 records for the stochastic suite, else 7.
    selection: dict[str, Any] = field(default_factory=dict)
    #: Rounding of tower locations into shared sites [deg]; 0 = exact.
    site_resolution_deg: float = 0.01
    #: Lower I_S limits of the classes (:mod:`rockscreen.pipeline.risk.measures.classes`).
    class_limits: tuple[float, ...] = DEFAULT_LIMITS
    #: Run on record sets that fail NTC 2018 §3.2.3.6 / §7.3.5 (every verdict built on them
    #: is marked); False refuses them before any solve
    #: (:mod:`rockscreen.pipeline.risk.assess.compliance`).
    allow_noncompliant: bool = False
    #: Knowledge level of every tower (LC1, LC2, LC3; Circolare 2019 §C8.5.4); its F_C divides
    #: the SLV capacity. None:
    #: :data:`rockscreen.pipeline.risk.checks.knowledge.DEFAULT_KNOWLEDGE_LEVEL`, an assumption
    #: said in the note.
    knowledge_level: str | None = None
    #: Resamples of the record bootstrap (0: no intervals).
    bootstrap_resamples: int = DEFAULT_BOOTSTRAP_RESAMPLES
    #: Seed of the bootstrap (mixed per tower with its id).
    seed: int = 0
    #: Optimiser of the censored fits and their bootstrap
    #: (:data:`rockscreen.pipeline.risk.measures.censored_fit.FIT_METHODS`; ``"trust-exact"`` is the
    #: reference, the same fits to about 1e-9, slower).
    fit_method: str = "newton"
    #: The screening risk (samples, the region's priors; :mod:`.screening_risk`).
    risk: RiskOptions = field(default_factory=RiskOptions)
    #: Search a record's components together, a component's level settled once the other
    #: reaches it lower (:attr:`rockscreen.pipeline.risk.assess.ida.IdaOptions.adaptive`: the same
    #: record intensities, fits and verdicts, fewer solves); False searches every component
    #: in full (the reference).
    adaptive_ida: bool = True

    def ida_options(self, models: Sequence[str] | None = None) -> IdaOptions:
        """Return the IDA search options (models, free motion, early stop, adaptive search)."""
        enabled = self.stripe.models if models is None else tuple(models)
        return IdaOptions(
            models=enabled,
            free_motion_s=self.stripe.free_motion_s,
            early_stop=self.stripe.early_stop,
            adaptive=self.adaptive_ida,
        )

    def set_compliance(self, record_set: Any) -> SetCompliance:
        """Return the compliance of a record set under these options' tolerance and limits."""
        selection = self.selection
        return set_compliance(
            record_set,
            tolerance=tuple(selection.get("tolerance", DEFAULT_TOLERANCE)),
            scale_limits=tuple(selection.get("scale_limits", SCALE_LIMITS)),
        )

    def resolved_return_periods(self) -> tuple[float, ...]:
        """Return the stripes' return periods [y], the nine tabulated ones by default."""
        if self.return_periods_y:
            return tuple(sorted(float(tr) for tr in self.return_periods_y))

        return tuple(float(tr) for tr in RETURN_PERIODS_Y)
