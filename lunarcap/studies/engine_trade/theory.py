"""The closed-form side of the engine trade study: thrust-to-weight, Eq. (19), Robbins.

Split from :mod:`lunarcap.studies.engine_trade.trade` (which re-exports every name): the
definitions of the abscissa (:func:`thrust_to_weight`, Earth or lunar weight), the analytic
estimate of one engine's capture chain (:func:`capture_chain_estimate`) and the paper's three
engines as points (:func:`paper_points`). Nothing here solves an optimisation problem.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS
from lunarcap.physics import constants as C
from lunarcap.physics.losses import robbins_loss_mps
from lunarcap.physics.rocket import burn_duration_estimate_s, check_engine, rocket_mass_after

#: Lunar surface gravity mu / R^2, m/s^2 (from :data:`lunarcap.physics.constants.MU_MOON` and
#: :data:`lunarcap.physics.constants.R_MOON`, Song 2011's values).
G_MOON_MPS2 = C.MU_MOON / C.R_MOON ** 2 * 1e3

#: Radius of every capture perilune, km (R_Moon + the packaged plans' 100 km, Song 2011
#: Sec. 3.2.1).
PERILUNE_RADIUS_KM = C.R_MOON + paper_scenario().perilune_altitude_km


def thrust_to_weight(thrust_N, mass_kg: float = paper_scenario().mass_kg,
                     g_mps2: float = C.G0_MPS2):
    """Thrust-to-weight ratio T / (m g) (dimensionless).

    Parameters
    ----------
    thrust_N : float or ndarray
        Thrust, N.
    mass_kg : float
        Mass, kg (default: the arrival mass before LOI 1, 524.895 kg).
    g_mps2 : float
        Reference gravity, m/s^2 (default: standard gravity g0 = 9.80665 m/s^2; pass
        :data:`G_MOON_MPS2` for the lunar weight).
    """
    if np.ndim(thrust_N):
        return np.asarray(thrust_N, dtype=float) / (mass_kg * g_mps2)
    return float(thrust_N) / (mass_kg * g_mps2)


def thrust_from_weight_ratio(ratio, mass_kg: float = paper_scenario().mass_kg,
                             g_mps2: float = C.G0_MPS2):
    """Inverse of :func:`thrust_to_weight`: the thrust (N) of a thrust-to-weight ratio."""
    return np.asarray(ratio, dtype=float) * mass_kg * g_mps2


def capture_chain_estimate(thrust_N: float, isp_s: float,
                           mass_kg: float = paper_scenario().mass_kg,
                           dv_mps=PAPER_IMPULSIVE_DV_MPS, r_km: float = PERILUNE_RADIUS_KM,
                           mu: float = C.MU_MOON) -> list[dict]:
    """Eq. (19) durations and Robbins losses of the three LOIs of one engine.

    The mass before each LOI is that of the impulsive chain (rocket equation with the
    impulsive delta-Vs from ``mass_kg``); Eq. (19) turns it into the burn duration.

    Parameters
    ----------
    thrust_N, isp_s : float
        Engine, N and s.
    mass_kg : float
        Mass at the first perilune, kg.
    dv_mps : sequence of three floats
        Impulsive delta-Vs of LOI 1, 2, 3, m/s (default: the paper's, Table B1).
    r_km, mu : burn radius (km) and gravitational parameter (km^3/s^2).

    Returns
    -------
    list of dict
        One per LOI: ``loi``, ``paper_impulsive_delta_v_mps``, ``m_before_kg``,
        ``eq19_duration_min``, ``analytic_loss_mps``, ``analytic_loss_percent``.
    """
    check_engine(thrust_N, isp_s, mass_kg)
    if len(dv_mps) != 3:
        raise InputError(f"three impulsive delta-Vs expected, got {dv_mps!r}")
    rows, m = [], float(mass_kg)
    for i, dv in enumerate(dv_mps):
        tb = float(burn_duration_estimate_s(m, dv, thrust_N, isp_s))
        loss = robbins_loss_mps(dv, tb, r_km, mu)
        rows.append({"loi": i + 1, "paper_impulsive_delta_v_mps": float(dv), "m_before_kg": m,
                     "eq19_duration_min": tb / 60.0, "analytic_loss_mps": loss,
                     "analytic_loss_percent": 100.0 * loss / dv})
        m = float(rocket_mass_after(m, dv, isp_s))
    return rows


def paper_points() -> pd.DataFrame:
    """The paper's three engines with their Table B1 losses, per LOI and for the sequence.

    Columns: thrust_N, isp_s, thrust_to_weight, part, burn_duration_min, paper_delta_v_loss_mps,
    paper_delta_v_loss_percent (per LOI the percentage as printed in Table B1; for the sequence the
    sum of
    the losses in % of the summed impulsive delta-V).
    """
    from lunarcap.paper.printed import paper_table_b1

    b1 = paper_table_b1()
    rows = []
    for t, g in b1.groupby("thrust_N", sort=True):
        isp = float(g.isp_s.iloc[0])
        for r in g.itertuples(index=False):
            rows.append({"thrust_N": float(t), "isp_s": isp, "part": f"LOI{r.loi}",
                         "burn_duration_min": r.burn_duration_min,
                         "paper_delta_v_loss_mps": r.delta_v_mps - r.impulsive_delta_v_mps,
                         "paper_delta_v_loss_percent": r.diff_percent})
        loss = float((g.delta_v_mps - g.impulsive_delta_v_mps).sum())
        rows.append({"thrust_N": float(t), "isp_s": isp, "part": "sequence",
                     "burn_duration_min": float(g.burn_duration_min.sum()),
                     "paper_delta_v_loss_mps": loss,
                     "paper_delta_v_loss_percent":
                         100.0 * loss / float(g.impulsive_delta_v_mps.sum())})
    df = pd.DataFrame(rows)
    df.insert(2, "thrust_to_weight", thrust_to_weight(df.thrust_N.to_numpy()))
    return df
