"""Example accelerograms from a documented stochastic model, for ``rockscreen run --example``.

The model (see ``docs/inventory.md``): Gaussian white noise, seeded, is multiplied by a
Saragoni-Hart envelope and filtered by the Kanai-Tajimi ground filter followed by the
Clough-Penzien high-pass filter; each component is then scaled to its target peak
ground acceleration (PGA).

- Kanai (1957), Tajimi (1960): ground filter
  H_KT(w) = (w_g^2 + 2i zeta_g w_g w) / (w_g^2 - w^2 + 2i zeta_g w_g w).
- Clough & Penzien (1975): high-pass H_CP(w) = -w^2 / (w_f^2 - w^2 + 2i zeta_f w_f w),
  which removes the power near w = 0 so that velocity and displacement do not drift.
- Saragoni & Hart (1974) envelope in Boore's (2003, Pure Appl. Geophys. 160:635-676)
  parametrisation: e(t) = a (t'/t_n)^b exp(-c t'/t_n), t' = t - t_onset,
  b = -eps ln(eta) / (1 + eps (ln eps - 1)), c = b / eps, a = (e / eps)^b, so the
  envelope peaks at 1 at t' = eps t_n and has fallen to eta at t' = t_n.
- The filters run in the time domain (bilinear transform, :func:`filter_coefficients`),
  so the output is causal.
- The last 2 s are multiplied by a half-cosine so the record ends at rest.

Three stations of the fictitious network ``XX`` stand at increasing distance from a
hypothetical epicentre near Cervino (CE), beside the towers of the example inventory,
with decreasing PGA (0.40 g, 0.20 g, 0.05 g on the strongest horizontal), lower ground
frequencies and longer shaking with distance. The records are written as FLOAT64
miniSEED in m/s² with a StationXML whose unit sensitivity (1 count = 1 m/s², input
units M/S**2) tells a reader the values are already accelerations. Every call writes
the same bytes.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.inventory import (
    Channel,
    InstrumentSensitivity,
    Inventory,
    Network,
    Response,
    Site,
    Station,
)
from scipy.signal import bilinear, lfilter

from rockscreen.solver.constants import G
from rockscreen.stations.pairing import StationSite

__all__ = [
    "COMPONENTS",
    "DURATION_S",
    "EXAMPLE_STATIONS",
    "SAMPLING_RATE_HZ",
    "STARTTIME",
    "SyntheticStation",
    "clough_penzien_gain",
    "example_station_inventory",
    "example_station_sites",
    "example_stream",
    "filter_coefficients",
    "kanai_tajimi_gain",
    "saragoni_hart_envelope",
    "stochastic_accelerogram",
    "write_example_records",
]

SAMPLING_RATE_HZ = 100.0
DURATION_S = 40.0
#: Start of every example record; arbitrary (the scenario is fictitious).
STARTTIME = UTCDateTime("2000-01-01T00:00:00")
NETWORK = "XX"  # the FDSN code for networks that are not registered: nothing real

#: Channel -> (scale of the PGA relative to the station's target, ground-frequency factor).
#: The second horizontal is a little weaker; the vertical is weaker and richer in high
#: frequencies, as usual in near-source records.
COMPONENTS: dict[str, tuple[float, float]] = {
    "HNE": (1.0, 1.0),
    "HNN": (0.85, 1.0),
    "HNZ": (0.6, 1.5),
}

#: Envelope shape: peak at ENVELOPE_EPS * t_n, down to ENVELOPE_ETA at t_n (Boore 2003).
ENVELOPE_EPS = 0.2
ENVELOPE_ETA = 0.05
#: Clough-Penzien corner as a fraction of the ground frequency, and its damping
#: (w_f ~ 0.1 w_g, zeta_f = zeta_g, as in Der Kiureghian & Neuenhofer 1992).
CP_FREQUENCY_RATIO = 0.1
CP_DAMPING = 0.6
#: Length of the half-cosine taper that ends every record at rest [s].
END_TAPER_S = 2.0


@dataclass(frozen=True)
class SyntheticStation:
    """One example station and the parameters of its records."""

    #: Station code (network ``XX``).
    code: str
    #: WGS84 coordinates [deg].
    latitude: float
    longitude: float
    #: Elevation [m].
    elevation_m: float
    #: Target PGA of the strongest horizontal component [g].
    pga_g: float
    #: Kanai-Tajimi ground frequency f_g = w_g / 2 pi [Hz].
    ground_frequency_hz: float
    #: Kanai-Tajimi ground damping ratio zeta_g [-].
    ground_damping: float
    #: Saragoni-Hart duration t_n [s].
    envelope_duration_s: float
    #: Start of the shaking after the record start [s].
    onset_s: float
    #: Seed of ``numpy.random.default_rng``.
    seed: int

    @property
    def key(self) -> str:
        """``"NET.STA"``."""
        return f"{NETWORK}.{self.code}"


#: Near, intermediate and far station of the example scenario (epicentre ~41.00 N, 14.40 E).
EXAMPLE_STATIONS: tuple[SyntheticStation, ...] = (
    SyntheticStation("SYN1", 41.030, 14.430, 80.0, 0.40, 2.5, 0.6, 20.0, 2.0, 20230762),
    SyntheticStation("SYN2", 41.130, 14.600, 150.0, 0.20, 2.0, 0.6, 24.0, 4.0, 20230763),
    SyntheticStation("SYN3", 41.300, 14.850, 300.0, 0.05, 1.5, 0.6, 28.0, 7.0, 20230764),
)


def saragoni_hart_envelope(
    t: np.ndarray, duration: float, *, eps: float = ENVELOPE_EPS, eta: float = ENVELOPE_ETA
) -> np.ndarray:
    """Return the Saragoni-Hart envelope in Boore's (2003) parametrisation.

    Parameters
    ----------
    t : ndarray
        Times after the onset [s]; negative times give 0.
    duration : float
        t_n [s], > 0: the envelope is ``eta`` there.
    eps : float
        Time of the peak as a fraction of ``duration`` [-], in (0, 1).
    eta : float
        Envelope value at ``duration`` [-], in (0, 1).

    Returns
    -------
    ndarray
        Envelope [-], peak 1 at ``eps * duration``.
    """
    b = -eps * np.log(eta) / (1.0 + eps * (np.log(eps) - 1.0))
    c = b / eps
    a = (np.e / eps) ** b
    x = np.clip(np.asarray(t, dtype=float), 0.0, None) / duration
    return a * x**b * np.exp(-c * x)


def kanai_tajimi_gain(
    frequency: np.ndarray, ground_frequency: float, ground_damping: float
) -> np.ndarray:
    """Return the Kanai-Tajimi transfer function (absolute acceleration / bedrock).

    Parameters
    ----------
    frequency : ndarray
        Frequencies [Hz].
    ground_frequency : float
        f_g [Hz].
    ground_damping : float
        zeta_g [-].

    Returns
    -------
    ndarray of complex
        H_KT, 1 at zero frequency.
    """
    w = 2 * np.pi * np.asarray(frequency, dtype=float)
    wg = 2 * np.pi * ground_frequency
    damping = 2j * ground_damping * wg * w
    return (wg**2 + damping) / (wg**2 - w**2 + damping)


def clough_penzien_gain(
    frequency: np.ndarray, corner_frequency: float, damping: float
) -> np.ndarray:
    """Return the Clough-Penzien high-pass transfer function.

    Parameters
    ----------
    frequency : ndarray
        Frequencies [Hz].
    corner_frequency : float
        f_f [Hz].
    damping : float
        zeta_f [-].

    Returns
    -------
    ndarray of complex
        H_CP = -w^2 / (w_f^2 - w^2 + 2i zeta_f w_f w): 0 at zero frequency, -> 1 above f_f.
    """
    w = 2 * np.pi * np.asarray(frequency, dtype=float)
    wf = 2 * np.pi * corner_frequency
    return -(w**2) / (wf**2 - w**2 + 2j * damping * wf * w)


def filter_coefficients(
    ground_frequency: float, ground_damping: float, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """Return the digital Kanai-Tajimi x Clough-Penzien filter.

    The analog cascade H_KT(s) H_CP(s), with s = i w,
    H_KT = (2 zeta_g w_g s + w_g^2) / (s^2 + 2 zeta_g w_g s + w_g^2) and
    H_CP = s^2 / (s^2 + 2 zeta_f w_f s + w_f^2), w_f = ``CP_FREQUENCY_RATIO`` w_g,
    zeta_f = ``CP_DAMPING``, is mapped by the bilinear transform. Filtering in the time
    domain keeps the output causal: nothing before the onset of the noise. At 100 Hz
    the bilinear frequency warping is below 0.5 % up to 4 Hz.

    Parameters
    ----------
    ground_frequency : float
        f_g [Hz].
    ground_damping : float
        zeta_g [-].
    dt : float
        Time step [s].

    Returns
    -------
    b, a : ndarray
        Numerator and denominator for :func:`scipy.signal.lfilter`.
    """
    wg = 2 * np.pi * ground_frequency
    wf = CP_FREQUENCY_RATIO * wg
    numerator = np.polymul([2 * ground_damping * wg, wg**2], [1.0, 0.0, 0.0])
    denominator = np.polymul(
        [1.0, 2 * ground_damping * wg, wg**2], [1.0, 2 * CP_DAMPING * wf, wf**2]
    )
    return bilinear(numerator, denominator, fs=1.0 / dt)


def stochastic_accelerogram(
    rng: np.random.Generator,
    *,
    n_samples: int,
    dt: float,
    pga: float,
    ground_frequency: float,
    ground_damping: float,
    envelope_duration: float,
    onset: float,
) -> np.ndarray:
    """Return one accelerogram of the modulated, filtered white-noise model.

    Parameters
    ----------
    rng : numpy.random.Generator
        Source of the white noise (consumed: ``n_samples`` normal draws).
    n_samples : int
        Number of samples.
    dt : float
        Time step [s].
    pga : float
        Peak absolute acceleration of the result [m/s²].
    ground_frequency : float
        Kanai-Tajimi f_g [Hz]; the Clough-Penzien corner is ``CP_FREQUENCY_RATIO`` of it.
    ground_damping : float
        Kanai-Tajimi zeta_g [-].
    envelope_duration : float
        Saragoni-Hart t_n [s].
    onset : float
        Start of the shaking [s].

    Returns
    -------
    ndarray
        Acceleration [m/s²], shape ``(n_samples,)``.
    """
    t = np.arange(n_samples) * dt
    noise = rng.standard_normal(n_samples) * saragoni_hart_envelope(t - onset, envelope_duration)
    b, a = filter_coefficients(ground_frequency, ground_damping, dt)
    acc = lfilter(b, a, noise)
    # A half-cosine over the last END_TAPER_S brings the filters' ringing to rest.
    n_taper = min(n_samples, round(END_TAPER_S / dt))
    acc[n_samples - n_taper :] *= 0.5 * (1 + np.cos(np.linspace(0.0, np.pi, n_taper)))
    return acc * (pga / np.max(np.abs(acc)))


def example_stream(station: SyntheticStation) -> Stream:
    """Return the three-component example record of one station.

    Parameters
    ----------
    station : SyntheticStation
        The station and its model parameters.

    Returns
    -------
    obspy.Stream
        Traces HNE, HNN, HNZ [m/s², float64], ``SAMPLING_RATE_HZ``, ``DURATION_S``.
    """
    rng = np.random.default_rng(station.seed)
    dt = 1.0 / SAMPLING_RATE_HZ
    n_samples = round(DURATION_S * SAMPLING_RATE_HZ)
    traces = []
    for channel, (pga_scale, frequency_factor) in COMPONENTS.items():
        data = stochastic_accelerogram(
            rng,
            n_samples=n_samples,
            dt=dt,
            pga=station.pga_g * pga_scale * G,
            ground_frequency=station.ground_frequency_hz * frequency_factor,
            ground_damping=station.ground_damping,
            envelope_duration=station.envelope_duration_s,
            onset=station.onset_s,
        )
        header = {
            "network": NETWORK,
            "station": station.code,
            "location": "",
            "channel": channel,
            "starttime": STARTTIME,
            "sampling_rate": SAMPLING_RATE_HZ,
        }
        traces.append(Trace(data=data.astype(np.float64), header=header))
    return Stream(traces)


def example_station_sites() -> list[StationSite]:
    """Return the example stations as pairing sites.

    Returns
    -------
    list of StationSite
        One per entry of :data:`EXAMPLE_STATIONS`.
    """
    return [StationSite(s.key, s.latitude, s.longitude) for s in EXAMPLE_STATIONS]


def example_station_inventory() -> Inventory:
    """Return the StationXML inventory of the example stations.

    Returns
    -------
    obspy.core.inventory.Inventory
        Network ``XX`` with one station per :data:`EXAMPLE_STATIONS`, channels HNE,
        HNN, HNZ at 100 Hz, each with a unit sensitivity (input units M/S**2).
    """
    orientation = {"HNE": (90.0, 0.0), "HNN": (0.0, 0.0), "HNZ": (0.0, -90.0)}
    stations = []
    for site in EXAMPLE_STATIONS:
        channels = [
            Channel(
                code=code,
                location_code="",
                latitude=site.latitude,
                longitude=site.longitude,
                elevation=site.elevation_m,
                depth=0.0,
                azimuth=orientation[code][0],
                dip=orientation[code][1],
                sample_rate=SAMPLING_RATE_HZ,
                start_date=STARTTIME,
                description="synthetic accelerogram (rockscreen example, not a real record)",
                response=Response(
                    instrument_sensitivity=InstrumentSensitivity(
                        value=1.0,
                        frequency=1.0,
                        input_units="M/S**2",
                        output_units="COUNTS",
                        input_units_description="acceleration in metres per second squared",
                    )
                ),
            )
            for code in COMPONENTS
        ]
        stations.append(
            Station(
                code=site.code,
                latitude=site.latitude,
                longitude=site.longitude,
                elevation=site.elevation_m,
                start_date=STARTTIME,
                site=Site(name=f"rockscreen synthetic station {site.code}"),
                channels=channels,
            )
        )
    network = Network(
        code=NETWORK,
        stations=stations,
        description="rockscreen example: fictitious stations with synthetic records",
    )
    return Inventory(networks=[network], source="rockscreen", created=STARTTIME)


def write_example_records(folder: str | Path) -> tuple[list[Path], Path]:
    """Write the example records and their StationXML into a folder.

    Parameters
    ----------
    folder : str or Path
        Output folder; created if absent. Files of the same names are overwritten.

    Returns
    -------
    records : list of Path
        miniSEED files ``XX.<STA>..<CHA>.mseed`` (FLOAT64, m/s²), one per channel,
        nearest station first.
    stationxml : Path
        ``XX.stations.xml``.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    records = []
    for station in EXAMPLE_STATIONS:
        for trace in example_stream(station):
            path = folder / f"{trace.id}.mseed"
            Stream([trace]).write(str(path), format="MSEED", encoding="FLOAT64")
            records.append(path)
    stationxml = folder / f"{NETWORK}.stations.xml"
    example_station_inventory().write(str(stationxml), format="STATIONXML", validate=True)
    return records, stationxml
