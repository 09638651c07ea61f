r"""Analytic finite-burn loss: Robbins' (1966) estimate, evaluated for the capture chain.

Robbins (1966) estimated the extra velocity change a finite burn needs over the impulse
it replaces as

.. math::

    \Delta V_{loss} \lesssim \frac{1}{24} (\omega_s t_b)^2 \, \Delta V,
    \qquad \omega_s^2 = \mu / r^3,

with :math:`t_b` the burn duration, :math:`\Delta V` the impulsive velocity change and
:math:`\omega_s` the Schuler frequency at the burn radius :math:`r` (:math:`r_p` for a burn
centred on a perilune). Here :math:`t_b` is each LOI's Eq. (19) duration (Song 2011) with
the masses of the impulsive chain, so the estimate is closed-form and independent of the
optimiser.

Sources: H. M. Robbins, "An analytical study of the impulsive approximation", AIAA Journal
4(8):1417-1423, 1966, doi:10.2514/3.3687, as quoted by J. C. F. Confraria, "Finite burn
losses in spacecraft maneuvers revisited", MSc thesis, Instituto Superior Tecnico, Lisbon,
2020, Sec. 2.2, Eq. (2.17)-(2.18), who finds that it overestimates the losses of
velocity-following burns (by about 125 % near T/W0 = 0.1, less at higher T/W0). Neither
text was read (the expression is taken from a public literature review quoting the
thesis), so Robbins' exact form and assumptions (constant thrust or acceleration, the
choice of r, a bound or an estimate) are not verified.

What is verified: the expression is the exact leading-order loss of a burn of constant
acceleration in a fixed inertial direction, centred on an apse, for :math:`\Delta V \ll v`.
Gravity along the burn (:math:`-\omega_s^2 y`, with :math:`y \approx v t` along the
velocity) makes the thrust's work fall short of the impulse's by
:math:`\omega_s^2 v t_b^2 \Delta V / 24`, the velocity loss above at the speed :math:`v`
(checked against a numerical integration by
``tests/studies/test_study.py::test_robbins_is_the_leading_order_loss_of_a_fixed_direction_burn``).
The optimal burns steer, choose their ignition and spend mass, so for them the estimate is
a yardstick, not a prediction.
"""

from __future__ import annotations

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics import constants as C


def schuler_rate_rad_s(r_km: float, mu: float = C.MU_MOON) -> float:
    """Schuler frequency sqrt(mu / r^3), rad/s.

    Parameters
    ----------
    r_km : float
        Radius, km.
    mu : float
        Gravitational parameter, km^3/s^2.
    """
    r_km = np.asarray(r_km, dtype=float)
    if not np.all(np.isfinite(r_km)) or np.any(r_km <= 0):
        raise InputError(f"radius must be a positive number of km, got {r_km!r}")
    return np.sqrt(mu / r_km ** 3)


def robbins_loss_mps(dv_mps, burn_s, r_km: float, mu: float = C.MU_MOON):
    """Robbins' (1966) finite-burn loss estimate (1/24) (omega_s t_b)^2 dV, m/s.

    Parameters
    ----------
    dv_mps : float or ndarray
        Impulsive velocity change, m/s.
    burn_s : float or ndarray
        Burn duration, s.
    r_km : float
        Radius of the burn (its centre), km (the paper's: R_Moon + 100 km).
    mu : float
        Gravitational parameter, km^3/s^2.

    Returns
    -------
    float or ndarray
        Velocity loss, m/s (same units as ``dv_mps``).

    Examples
    --------
    >>> w = float(schuler_rate_rad_s(1838.2))
    >>> round(float(robbins_loss_mps(240.0, 1.0 / w, 1838.2)), 6)  # (omega t)^2 = 1: dV/24
    10.0
    """
    dv = np.asarray(dv_mps, dtype=float)
    tb = np.asarray(burn_s, dtype=float)
    if not (np.all(np.isfinite(dv)) and np.all(np.isfinite(tb))) or np.any(dv < 0) \
            or np.any(tb < 0):
        raise InputError("delta-V and burn duration must be non-negative finite numbers")
    w = schuler_rate_rad_s(r_km, mu)
    out = (w * tb) ** 2 * dv / 24.0
    return float(out) if out.ndim == 0 else out
