"""Floor motion at the base of the S. Anna tower against the paper's Fig. 8 statements.

The paper (section 3.2): "The tower floor spectrum (Figure 8) has a maximum acceleration
(a = 2.25 g), for periods between 0.1 and 0.2 s, with amplification of about four times with
respect to the ground level." Its ground spectrum peaks at 0.5 g (section 4). We print:
1. the code floor spectra (EC8 eq. 4.25, NTC 2018 Circolare C7.2.11) at the top of the
   building (z = H) for a tower period Ta = 1/7.98 s, as a ratio to the ground's alpha*S;
2. the modal floor accelerogram (first mode, Gamma = 1.5, 5 % damping) of ten stochastic
   ground records: the ratio of floor to ground 5 %-damped spectral peaks and where the floor
   spectrum peaks, for the building periods T1 listed.
Run: python examples/seed_study/floor_check.py
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.motion.floor import (
    ec8_floor_acceleration,
    modal_floor_accelerogram,
    ntc_floor_acceleration,
)
from rockscreen.pipeline.motion.spectra import response_spectrum
from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram

TA = 1.0 / 7.98  # tower period [s] (the paper's 7.98 Hz)
PERIODS = np.linspace(0.02, 1.0, 99)
DT = 0.005  # sampling step of the stochastic ground records [s]
# The stochastic ground records (rockscreen.pipeline.motion.synthetic.stochastic_accelerogram): 20 s
# at DT, peak 2 m/s2, Kanai-Tajimi f_g = 15 Hz and zeta_g = 0.6, Saragoni-Hart t_n = 15 s
# after a 1 s onset.
GROUND_RECORD = {
    "n_samples": 4000,
    "dt": DT,
    "pga": 2.0,
    "ground_frequency": 15.0,
    "ground_damping": 0.6,
    "envelope_duration": 15.0,
    "onset": 1.0,
}


def code_ratios() -> None:
    """Print the code floor spectra at the tower's period, over the ground's alpha S."""
    print("1. code floor spectra at z = H, Ta = 0.1253 s: Sa / (alpha S) [-]")
    print("   T1 [s]   EC8 eq.4.25   NTC C7.2.11   floor peak at 0.5 g ground spectrum / 2.5 [g]")
    for t1 in (0.1253, 0.2, 0.3, 0.5):
        ec8 = ec8_floor_acceleration(1.0, 1.0, 1.0, 1.0, TA, t1)
        ntc = ntc_floor_acceleration(1.0, 1.0, 1.0, 1.0, TA, t1)
        # a ground spectrum of 0.5 g on its plateau (F0 = 2.5) means alpha S = 0.2 g
        print(
            f"   {t1:6.4f}   {ec8:11.2f}   {ntc:11.2f}   "
            f"EC8 {0.2 * ec8:.2f} g, NTC {0.2 * ntc:.2f} g"
        )


def modal_ratios() -> None:
    """Print floor-to-ground spectral peak ratios of the modal floor accelerogram."""
    print("2. modal floor accelerogram (Gamma = 1.5, zeta = 5 %), 10 stochastic records:")
    print("   T1 [s]   SA_floor,max / SA_ground,max [-]   period of SA_floor,max [s]")
    rng = np.random.default_rng(762)
    records = [stochastic_accelerogram(rng, **GROUND_RECORD) for _ in range(10)]
    for t1 in (0.1253, 0.2, 0.3, 0.5):
        ratios, peaks = [], []
        for acc in records:
            ground, _ = response_spectrum(acc, DT, PERIODS)
            floor = modal_floor_accelerogram(acc, DT, building_period=t1)
            sa, _ = response_spectrum(floor, DT, PERIODS)
            ratios.append(sa.max() / ground.max())
            peaks.append(PERIODS[int(np.argmax(sa))])
        print(
            f"   {t1:6.4f}   {np.median(ratios):5.2f} (range {min(ratios):.2f}-{max(ratios):.2f})"
            f"   {np.median(peaks):.3f} (range {min(peaks):.3f}-{max(peaks):.3f})"
        )


if __name__ == "__main__":
    code_ratios()
    modal_ratios()
