"""The risk measures: fragility fits, the hazard integral, the LV1 indices, classes.

Pure functions of numbers: the lognormal fragility fitted on stripe counts and on
censored collapse intensities, the site hazard curve and the mean annual frequency of
overturning, the Guidelines' capacity acceleration, its return period, I_S and f_a,
and the classes of I_S. They import no other role of ``risk/``.

Modules:

- :mod:`.censored_fit`: Lognormal fragility fitted by maximum likelihood on right-censored collapse
  intensities.
- :mod:`.classes`: Risk classes of towers from the safety index I_S (the ranking is the report's).
- :mod:`.fragility`: Lognormal fragility fitted by maximum likelihood on multiple-stripe counts.
- :mod:`.hazard_integral`: The site hazard curve and the mean annual frequency of overturning.
- :mod:`.lv1`: LV1 quantities of the MiC 2011 Guidelines from a fragility and the site hazard.
"""
