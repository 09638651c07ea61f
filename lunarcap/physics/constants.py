"""Physical constants of the lunar capture problem, each with its source.

All values are in km, s and kg unless the name says otherwise. The paper is
Song, Park, Kim, Lee & Sim (2011), J. Astron. Space Sci. 28(3) 203-216,
hereafter "Song 2011"; its constants are printed in its Section 3.1. Only physical
constants live here: the paper's scenario (arrival epoch and mass, perilune altitude,
capture periods) and engines are its packaged plans, read by
:mod:`lunarcap.mission.scenario`.
"""

from __future__ import annotations

#: Gravitational parameter of the Moon, km^3/s^2 (Song 2011, Sec. 3.1).
MU_MOON = 4902.800

#: Gravitational parameter of the Earth, km^3/s^2 (Song 2011, Sec. 3.1).
MU_EARTH = 398600.441

#: Gravitational parameter of the Sun, km^3/s^2: DE405's (Standish 1998, JPL IOM
#: 312.F-98-048, GMS = 2.959122082855911e-4 AU^3/day^2), consistent with the ephemeris the
#: dynamics read (not the TCB-compatible IAU 2009 value, 1.32712442099e11). Song 2011
#: (Sec. 3.1) prints a value ten times too small (:data:`MU_SUN_AS_PRINTED`).
MU_SUN = 1.32712440018e11

#: The Sun's gravitational parameter as printed in Song 2011 (erroneous, kept only
#: so the book can show the discrepancy), km^3/s^2.
MU_SUN_AS_PRINTED = 13_271_244_207.6

#: Mean radius of the Moon, km (Song 2011, Sec. 3.1). Every altitude lunarcap reads or
#: writes is a distance from the Moon's centre minus this radius.
R_MOON = 1738.2

#: The IAU's mean radius of the Moon, km (Seidelmann et al. 2007, Celest. Mech. Dyn. Astr.
#: 98, 155, Table 5: 1737.4 +- 1 km), which tools that follow the IAU use: the same
#: state's altitude is R_MOON - R_MOON_IAU = 0.8 km higher there. Named in exported files
#: only; lunarcap computes with R_MOON.
R_MOON_IAU = 1737.4

#: Unnormalised second zonal harmonic of the Moon (Song 2011, Sec. 3.1).
J2_MOON = 0.2027e-3

#: Standard gravity, m/s^2 (exact, CGPM 1901); used in the rocket equation, Eq. (3).
G0_MPS2 = 9.80665

#: Standard gravity in km/s^2.
G0_KMPS2 = G0_MPS2 * 1e-3

#: Lunar unit, km: the length unit of the paper's Figs. 2-3 (Song 2011, Sec. 3.3).
LU_KM = R_MOON

#: Seconds per day (TDB days).
DAY_S = 86400.0

#: Julian date of the J2000.0 epoch, TDB.
JD_J2000 = 2451545.0

#: IAU (2009) orientation of the Moon's pole, constant terms, deg (Archinal et al. 2011,
#: Celest. Mech. Dyn. Astr. 109, 101, Table 2: alpha0 = 269.9949 + 0.0031 T + sum a_k sin
#: E_k, delta0 = 66.5392 + 0.0130 T + sum d_k cos E_k, T in Julian centuries). Alone they
#: are the centre of the pole's 18.6-year precession circle, not the pole at any epoch
#: (:func:`lunarcap.physics.frames.moon_pole_radec_deg` evaluates the whole expression).
MOON_POLE_RA_DEG = 269.9949
MOON_POLE_DEC_DEG = 66.5392
#: Secular rates of alpha0 and delta0, deg per Julian century (same source).
MOON_POLE_RA_RATE_DEG = 0.0031
MOON_POLE_DEC_RATE_DEG = 0.0130
#: The arguments E1..E13 = phase + rate * d, degrees and degrees per day (same source,
#: Table 2 footnote; E1 is the 18.6-year regression of the lunar node).
MOON_E_PHASE_DEG = (125.045, 250.089, 260.008, 176.625, 357.529, 311.589, 134.963,
                    276.617, 34.226, 15.134, 119.743, 239.961, 25.053)
MOON_E_RATE_DEG_PER_DAY = (-0.0529921, -0.1059842, 13.0120009, 13.3407154, 0.9856003,
                           26.4057084, 13.0649930, 0.3287146, 1.7484877, -0.1589763,
                           0.0036096, 0.1643573, 12.9590088)
#: Amplitudes of sin E_k in alpha0 and of cos E_k in delta0, degrees (same source).
MOON_POLE_RA_AMPL_DEG = (-3.8787, -0.1204, 0.0700, -0.0172, 0.0, 0.0072, 0.0, 0.0, 0.0,
                         -0.0052, 0.0, 0.0, 0.0043)
MOON_POLE_DEC_AMPL_DEG = (1.5419, 0.0239, -0.0278, 0.0068, 0.0, -0.0029, 0.0009, 0.0, 0.0,
                          0.0008, 0.0, 0.0, -0.0009)
#: IAU (2009) prime meridian of the Moon, W = W0 + W1 d + W2 d^2 + sum w_k sin E_k, degrees,
#: d in days past J2000 TDB (Archinal et al. 2011, Table 2; E_k as above).
MOON_W_DEG = 38.3213
MOON_W_RATE_DEG_PER_DAY = 13.17635815
MOON_W_ACCEL_DEG_PER_DAY2 = -1.4e-12
MOON_W_AMPL_DEG = (3.5610, 0.1208, -0.0642, 0.0158, 0.0252, -0.0066, -0.0047, -0.0046,
                   0.0028, 0.0052, 0.0040, 0.0019, -0.0044)
