"""Coast meshes: interval boundaries equally spaced in Sundman's variable, and in a gravity
field weighted towards the perilune (lunarcap.optim.collocation.sundman_fractions).

No NLP here: the fractions of a Kepler ellipse's perilune-to-perilune coast, sampled
from Kepler's equation.
"""

import math

import numpy as np

from lunarcap.optim.collocation import FIELD_PERILUNE_POWER, sundman_fractions
from lunarcap.physics import constants as C


def _kepler_coast(period_s: float, n_samples: int = 20001):
    """Epochs (s) and MEE rows (7, N) of one revolution from perilune, equatorial."""
    a = (C.MU_MOON * (period_s / (2 * math.pi)) ** 2) ** (1 / 3)
    e = 1.0 - (C.R_MOON + 100.0) / a
    t = np.linspace(0.0, period_s, n_samples)
    mean = 2 * math.pi * t / period_s
    ecc = mean.copy()
    for _ in range(50):                                   # Newton on Kepler's equation
        ecc -= (ecc - e * np.sin(ecc) - mean) / (1 - e * np.cos(ecc))
    nu = np.unwrap(2 * np.arctan2(math.sqrt(1 + e) * np.sin(ecc / 2),
                                  math.sqrt(1 - e) * np.cos(ecc / 2)))
    ones = np.ones_like(t)
    return t, np.vstack([a * (1 - e * e) * ones, e * ones, 0 * t, 0 * t, 0 * t, nu, 500 * ones])


def test_sundman_spacing_is_equal_steps_of_the_eccentric_anomaly():
    """On a Kepler orbit s = int dt / r is the eccentric anomaly over sqrt(mu a)."""
    period_s = 12.235 * 3600.0
    t, x = _kepler_coast(period_s)
    frac = sundman_fractions(t, x, 32)
    a = (C.MU_MOON * (period_s / (2 * math.pi)) ** 2) ** (1 / 3)
    e = 1.0 - (C.R_MOON + 100.0) / a
    ecc = np.linspace(0.0, 2 * math.pi, 33)
    expected = (ecc - e * np.sin(ecc)) / (2 * math.pi)   # the epochs of those anomalies
    np.testing.assert_allclose(frac, expected, atol=1e-6)


def test_a_field_coast_mesh_doubles_the_node_density_at_the_perilune():
    """With :data:`FIELD_PERILUNE_POWER` the intervals at the perilune are about half of
    Sundman's and those far above it about as long (a few per cent longer: the nodes they
    lend the perilune).

    Why the weight: a field's terms of degree n fall off as (R/r)^(n+2), so near a 100 km
    perilune they change over minutes. On Sundman's spacing alone, the 4 s burns of the
    impulsive limit of the paper's first burn in LP165P 20x20 (a 12.2 h coast from
    perilune to perilune) missed the flight-path angle by 5.7e-4 deg on 8x32 intervals
    and were solved only on 12x48 (two more NLPs to build, 18 s of CPU for that limit);
    with the weight they pass on 8x32.
    """
    t, x = _kepler_coast(12.235 * 3600.0)
    plain = np.diff(sundman_fractions(t, x, 32))
    weighted = np.diff(sundman_fractions(t, x, 32, FIELD_PERILUNE_POWER))
    ratio = weighted / plain
    assert 0.5 <= ratio[0] < 0.6 and 0.5 <= ratio[-1] < 0.6        # at the perilunes
    assert np.all((ratio[12:20] > 1.0) & (ratio[12:20] < 1.1))      # about the apolune
    np.testing.assert_array_equal(sundman_fractions(t, x, 32, 0.0),
                                  sundman_fractions(t, x, 32))
